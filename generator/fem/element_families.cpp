// SPDX-License-Identifier: GPL-2.0-or-later
#include "fem/element_families.hpp"

#include <array>
#include <cmath>
#include <stdexcept>

#include "fem/quadrature.hpp"

namespace kanegen::fem {

namespace {

/// The serendipity shape function of the node at natural coordinates c, and
/// its gradient, at x. Linear: prod_k (1 + x_k c_k) / 2. Serendipity corner:
/// that product times (sum_k x_k c_k - (d - 1)); serendipity mid-edge node
/// (c_m = 0): (1 - x_m^2) prod_{k != m} (1 + x_k c_k) / 2.
double serendipity_node(bool quadratic, int d, const Eigen::VectorXd& c, const Eigen::Vector3d& x,
                        Eigen::Ref<Eigen::RowVectorXd, 0, Eigen::InnerStride<>> grad) {
  int mid = -1;
  for (int k = 0; k < d; ++k)
    if (c[k] == 0.0) mid = k;
  // p_k = (1 + x_k c_k) / 2 over the non-mid directions; prod_except(j) leaves p_j out.
  auto p = [&](int k) { return 0.5 * (1.0 + x[k] * c[k]); };
  auto prod_except = [&](int skip1, int skip2) {
    double out = 1.0;
    for (int k = 0; k < d; ++k)
      if (k != skip1 && k != skip2) out *= p(k);
    return out;
  };
  if (mid >= 0) {
    const double bubble = 1.0 - x[mid] * x[mid];
    for (int j = 0; j < d; ++j)
      grad[j] = j == mid ? -2.0 * x[mid] * prod_except(mid, -1) : bubble * 0.5 * c[j] * prod_except(mid, j);
    return bubble * prod_except(mid, -1);
  }
  const double product = prod_except(-1, -1);
  if (!quadratic) {
    for (int j = 0; j < d; ++j) grad[j] = 0.5 * c[j] * prod_except(j, -1);
    return product;
  }
  double s = -(d - 1.0);
  for (int k = 0; k < d; ++k) s += x[k] * c[k];
  for (int j = 0; j < d; ++j) grad[j] = 0.5 * c[j] * prod_except(j, -1) * s + product * c[j];
  return product * s;
}

// Corners counter-clockwise seen from +z (bottom face first for hexahedra),
// then the mid-edge nodes in CalculiX's order.
constexpr double kQuadNodes[2][8] = {{-1, 1, 1, -1, 0, 1, 0, -1}, {-1, -1, 1, 1, -1, 0, 1, 0}};
constexpr double kHexNodes[3][20] = {{-1, 1, 1, -1, -1, 1, 1, -1, 0, 1, 0, -1, 0, 1, 0, -1, -1, 1, 1, -1},
                                     {-1, -1, 1, 1, -1, -1, 1, 1, -1, 0, 1, 0, -1, 0, 1, 0, -1, -1, 1, 1},
                                     {-1, -1, -1, -1, 1, 1, 1, 1, -1, -1, -1, -1, 1, 1, 1, 1, 0, 0, 0, 0}};

/// The first `nodes` columns of a table of natural coordinates.
template <int D, int N>
Eigen::MatrixXd table_nodes(const double (&table)[D][N], int nodes) {
  Eigen::MatrixXd c(D, nodes);
  for (int k = 0; k < D; ++k)
    for (int i = 0; i < nodes; ++i) c(k, i) = table[k][i];
  return c;
}

/// Serendipity (Lagrange for the linear ones) shape functions of a family of
/// quadrilaterals or hexahedra given by its natural nodes.
template <Eigen::MatrixXd (*Nodes)(), bool Quadratic>
NaturalShape serendipity_shape(const Eigen::Vector3d& xi) {
  const Eigen::MatrixXd c = Nodes();
  const int d = static_cast<int>(c.rows()), n = static_cast<int>(c.cols());
  NaturalShape s{Eigen::VectorXd(n), Eigen::MatrixXd(n, d)};
  for (int i = 0; i < n; ++i) s.N[i] = serendipity_node(Quadratic, d, c.col(i), xi, s.dN.row(i));
  return s;
}

/// The tensor Gauss-Legendre rule of `order` points per direction on
/// [-1, 1]^D: full integration, as CalculiX integrates C3D8 (2) and C3D20 (3).
template <int D, int Order>
std::vector<NaturalPoint> tensor_gauss(double scale) {
  const QuadratureRule rule = gauss_legendre(Order);
  const int m = static_cast<int>(rule.points.size());
  int count = 1;
  for (int k = 0; k < D; ++k) count *= m;
  std::vector<NaturalPoint> points;
  for (int p = 0; p < count; ++p) {
    // Map [0, 1] to [-1, 1]: the weights double per direction.
    const int index[3] = {p % m, (p / m) % m, p / (m * m)};
    NaturalPoint point{Eigen::Vector3d::Zero(), scale};
    for (int k = 0; k < D; ++k) {
      point.xi[k] = 2.0 * rule.points[index[k]] - 1.0;
      point.weight *= 2.0 * rule.weights[index[k]];
    }
    points.push_back(point);
  }
  return points;
}

// Tetrahedra and wedges: natural coordinates on the unit simplex (CalculiX's
// shape10tet, shape6w, shape15w): the tetrahedron's corners (0,0,0), (1,0,0),
// (0,1,0), (0,0,1); the wedge's triangle in (xi, eta) times zeta in [-1, 1],
// the bottom corners (zeta = -1) first. Mid-edge nodes of C3D10 on the edges
// 1-2, 2-3, 3-1, 1-4, 2-4, 3-4; of C3D15 on 1-2, 2-3, 3-1, 4-5, 5-6, 6-4,
// 1-4, 2-5, 3-6.
constexpr double kTetNodes[3][10] = {{0, 1, 0, 0, 0.5, 0.5, 0, 0, 0.5, 0},
                                     {0, 0, 1, 0, 0, 0.5, 0.5, 0, 0, 0.5},
                                     {0, 0, 0, 1, 0, 0, 0, 0.5, 0.5, 0.5}};
constexpr double kWedgeNodes[3][15] = {{0, 1, 0, 0, 1, 0, 0.5, 0.5, 0, 0.5, 0.5, 0, 0, 1, 0},
                                       {0, 0, 1, 0, 0, 1, 0, 0.5, 0.5, 0, 0.5, 0.5, 0, 0, 1},
                                       {-1, -1, -1, 1, 1, 1, -1, -1, -1, 1, 1, 1, 0, 0, 0}};
constexpr int kTetEdges[6][2] = {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}};
constexpr int kWedgeEdges[9][2] = {{0, 1}, {1, 2}, {2, 0}, {3, 4}, {4, 5}, {5, 3}, {0, 3}, {1, 4}, {2, 5}};

/// The quadratic tetrahedron: corners L_i (2 L_i - 1), mid-edge nodes
/// 4 L_a L_b, with the volume coordinates L = (1 - xi - eta - zeta, xi, eta, zeta).
NaturalShape tet10_shape(const Eigen::Vector3d& x) {
  const double L[4] = {1.0 - x[0] - x[1] - x[2], x[0], x[1], x[2]};
  // dL_i / dxi_k
  const double dL[4][3] = {{-1, -1, -1}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  NaturalShape s{Eigen::VectorXd(10), Eigen::MatrixXd(10, 3)};
  for (int i = 0; i < 4; ++i) {
    s.N[i] = L[i] * (2.0 * L[i] - 1.0);
    for (int k = 0; k < 3; ++k) s.dN(i, k) = (4.0 * L[i] - 1.0) * dL[i][k];
  }
  for (int e = 0; e < 6; ++e) {
    const int a = kTetEdges[e][0], b = kTetEdges[e][1];
    s.N[4 + e] = 4.0 * L[a] * L[b];
    for (int k = 0; k < 3; ++k) s.dN(4 + e, k) = 4.0 * (dL[a][k] * L[b] + L[a] * dL[b][k]);
  }
  return s;
}

/// The wedges: the triangle's area coordinates L = (1 - xi - eta, xi, eta)
/// times a function of zeta. Linear: L_i (1 + z_i zeta) / 2. Quadratic
/// (serendipity): corners L_i (1 + z) (2 L_i + z - 2) / 2 with z = z_i zeta,
/// triangle mid-edge nodes 2 L_a L_b (1 + z), vertical mid-edge nodes
/// L_i (1 - zeta^2).
template <bool Quadratic>
NaturalShape wedge_shape(const Eigen::Vector3d& x) {
  const double L[3] = {1.0 - x[0] - x[1], x[0], x[1]};
  const double dL[3][2] = {{-1, -1}, {1, 0}, {0, 1}};
  const int n = Quadratic ? 15 : 6;
  NaturalShape s{Eigen::VectorXd(n), Eigen::MatrixXd(n, 3)};
  for (int c = 0; c < 6; ++c) {
    const int i = c % 3;
    const double zi = c < 3 ? -1.0 : 1.0, z = zi * x[2];
    if (!Quadratic) {
      s.N[c] = 0.5 * L[i] * (1.0 + z);
      s.dN.row(c) << 0.5 * dL[i][0] * (1.0 + z), 0.5 * dL[i][1] * (1.0 + z), 0.5 * L[i] * zi;
      continue;
    }
    const double g = 2.0 * L[i] + z - 2.0;
    s.N[c] = 0.5 * L[i] * (1.0 + z) * g;
    for (int k = 0; k < 2; ++k) s.dN(c, k) = 0.5 * (1.0 + z) * dL[i][k] * (g + 2.0 * L[i]);
    s.dN(c, 2) = 0.5 * L[i] * zi * (g + 1.0 + z);
  }
  if (!Quadratic) return s;
  for (int e = 0; e < 6; ++e) {
    const int a = kWedgeEdges[e][0] % 3, b = kWedgeEdges[e][1] % 3;
    const double zi = e < 3 ? -1.0 : 1.0, z = zi * x[2];
    s.N[6 + e] = 2.0 * L[a] * L[b] * (1.0 + z);
    for (int k = 0; k < 2; ++k) s.dN(6 + e, k) = 2.0 * (dL[a][k] * L[b] + L[a] * dL[b][k]) * (1.0 + z);
    s.dN(6 + e, 2) = 2.0 * L[a] * L[b] * zi;
  }
  for (int i = 0; i < 3; ++i) {
    s.N[12 + i] = L[i] * (1.0 - x[2] * x[2]);
    for (int k = 0; k < 2; ++k) s.dN(12 + i, k) = dL[i][k] * (1.0 - x[2] * x[2]);
    s.dN(12 + i, 2) = -2.0 * L[i] * x[2];
  }
  return s;
}

/// CalculiX's C3D10 rule (gauss3d5): 4 points at the volume coordinates
/// (b, a, a, a) and its permutations, a = (5 - sqrt 5) / 20, b = 1 - 3 a,
/// weight 1/24 each (exact for quadratic integrands; the consistent mass of
/// the quadratic tetrahedron is quartic, so the mass is CalculiX's
/// 4-point mass, not the exact one: the frequencies then agree with ccx's).
std::vector<NaturalPoint> tet_4_points(double scale) {
  const double a = (5.0 - std::sqrt(5.0)) / 20.0, b = 1.0 - 3.0 * a;
  const Eigen::Vector3d xi[4] = {{a, a, a}, {b, a, a}, {a, b, a}, {a, a, b}};
  std::vector<NaturalPoint> points;
  for (const Eigen::Vector3d& p : xi) points.push_back({p, scale / 24.0});
  return points;
}

/// CalculiX's wedge rules: C3D6 (gauss3d7) 2 points, the triangle's centroid
/// times Gauss-Legendre 2 in zeta; C3D15 (gauss3d8) 9 points, the triangle's
/// 3-point rule (2/3, 1/6, 1/6 and permutations, weight 1/6) times
/// Gauss-Legendre 3 in zeta.
template <bool Quadratic>
std::vector<NaturalPoint> wedge_points(double scale) {
  std::vector<std::array<double, 3>> triangle;  // xi, eta, weight
  if (Quadratic)
    triangle = {{1.0 / 6, 1.0 / 6, 1.0 / 6}, {2.0 / 3, 1.0 / 6, 1.0 / 6}, {1.0 / 6, 2.0 / 3, 1.0 / 6}};
  else
    triangle = {{1.0 / 3, 1.0 / 3, 0.5}};
  const QuadratureRule line = gauss_legendre(Quadratic ? 3 : 2);
  std::vector<NaturalPoint> points;
  for (std::size_t z = 0; z < line.points.size(); ++z)
    for (const auto& t : triangle)
      points.push_back(
          {Eigen::Vector3d(t[0], t[1], 2.0 * line.points[z] - 1.0), scale * t[2] * 2.0 * line.weights[z]});
  return points;
}

Eigen::MatrixXd quad4_nodes() { return table_nodes(kQuadNodes, 4); }
Eigen::MatrixXd quad8_nodes() { return table_nodes(kQuadNodes, 8); }
Eigen::MatrixXd hex8_nodes() { return table_nodes(kHexNodes, 8); }
Eigen::MatrixXd hex20_nodes() { return table_nodes(kHexNodes, 20); }
Eigen::MatrixXd tet10_nodes() { return table_nodes(kTetNodes, 10); }
Eigen::MatrixXd wedge6_nodes() { return table_nodes(kWedgeNodes, 6); }
Eigen::MatrixXd wedge15_nodes() { return table_nodes(kWedgeNodes, 15); }

// The faces kanegen animate draws, outward (CalculiX's ifaceq, ifacet, ifacew).
constexpr std::array<int, 4> kLinear{-1, -1, -1, -1};
const std::vector<FamilyFace> kHexFaces{{{0, 1, 2, 3}, kLinear}, {{4, 7, 6, 5}, kLinear},
                                        {{0, 4, 5, 1}, kLinear}, {{1, 5, 6, 2}, kLinear},
                                        {{2, 6, 7, 3}, kLinear}, {{3, 7, 4, 0}, kLinear}};
const std::vector<FamilyFace> kHex20Faces{{{0, 1, 2, 3}, {8, 9, 10, 11}},   {{4, 7, 6, 5}, {15, 14, 13, 12}},
                                          {{0, 4, 5, 1}, {16, 12, 17, 8}},  {{1, 5, 6, 2}, {17, 13, 18, 9}},
                                          {{2, 6, 7, 3}, {18, 14, 19, 10}}, {{3, 7, 4, 0}, {19, 15, 16, 11}}};
const std::vector<FamilyFace> kTet10Faces{{{0, 2, 1, -1}, {6, 5, 4, -1}},
                                          {{0, 1, 3, -1}, {4, 8, 7, -1}},
                                          {{1, 2, 3, -1}, {5, 9, 8, -1}},
                                          {{0, 3, 2, -1}, {7, 9, 6, -1}}};
const std::vector<FamilyFace> kWedge15Faces{{{0, 2, 1, -1}, {8, 7, 6, -1}},
                                            {{3, 4, 5, -1}, {9, 10, 11, -1}},
                                            {{0, 1, 4, 3}, {6, 13, 9, 12}},
                                            {{1, 2, 5, 4}, {7, 14, 10, 13}},
                                            {{2, 0, 3, 5}, {8, 12, 11, 14}}};

/// The faces of a quadratic family without their mid-edge nodes.
std::vector<FamilyFace> linear_faces(const std::vector<FamilyFace>& faces) {
  std::vector<FamilyFace> out;
  for (const FamilyFace& f : faces) out.push_back({f.corner, kLinear});
  return out;
}

// VTK's wedge has its first triangle facing away from the second, CalculiX's
// towards it: the same cell with the triangles' corners 2 and 3 swapped.
const std::vector<int> kVtkWedge6{0, 2, 1, 3, 5, 4};
const std::vector<int> kVtkWedge15{0, 2, 1, 3, 5, 4, 8, 7, 6, 11, 10, 9, 12, 14, 13};

const std::array<FamilyRow, 7> kFamilies{{
    {ContinuumFamily::kQuad4,
     "CPS4",
     2,
     4,
     quad4_nodes,
     serendipity_shape<quad4_nodes, false>,
     tensor_gauss<2, 2>,
     9,
     {},
     {{{0, 1, 2, 3}, kLinear}}},
    {ContinuumFamily::kQuad8,
     "CPS8",
     2,
     8,
     quad8_nodes,
     serendipity_shape<quad8_nodes, true>,
     tensor_gauss<2, 3>,
     23,
     {},
     {{{0, 1, 2, 3}, {4, 5, 6, 7}}}},
    {ContinuumFamily::kHex8,
     "C3D8",
     3,
     8,
     hex8_nodes,
     serendipity_shape<hex8_nodes, false>,
     tensor_gauss<3, 2>,
     12,
     {},
     kHexFaces},
    {ContinuumFamily::kHex20,
     "C3D20",
     3,
     20,
     hex20_nodes,
     serendipity_shape<hex20_nodes, true>,
     tensor_gauss<3, 3>,
     25,
     {},
     kHex20Faces},
    {ContinuumFamily::kTet10, "C3D10", 3, 10, tet10_nodes, tet10_shape, tet_4_points, 24, {}, kTet10Faces},
    {ContinuumFamily::kWedge6, "C3D6", 3, 6, wedge6_nodes, wedge_shape<false>, wedge_points<false>, 13,
     kVtkWedge6, linear_faces(kWedge15Faces)},
    {ContinuumFamily::kWedge15, "C3D15", 3, 15, wedge15_nodes, wedge_shape<true>, wedge_points<true>, 26,
     kVtkWedge15, kWedge15Faces},
}};

}  // namespace

const FamilyRow& family_row(ContinuumFamily family) {
  for (const FamilyRow& row : kFamilies)
    if (row.family == family) return row;
  throw std::logic_error("fem: a continuum family without a row in element_families.cpp");
}

bool family_from_ccx_name(const std::string& name, ContinuumFamily& family) {
  for (const FamilyRow& row : kFamilies)
    if (name == row.ccx_name) {
      family = row.family;
      return true;
    }
  return false;
}

std::string supported_ccx_names() {
  std::string names;
  for (const FamilyRow& row : kFamilies) names += (names.empty() ? "" : ", ") + std::string(row.ccx_name);
  return names;
}

}  // namespace kanegen::fem
