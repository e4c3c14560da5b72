// SPDX-License-Identifier: GPL-2.0-or-later
#include "fem/element_families.hpp"

#include <array>
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

Eigen::MatrixXd quad4_nodes() { return table_nodes(kQuadNodes, 4); }
Eigen::MatrixXd quad8_nodes() { return table_nodes(kQuadNodes, 8); }
Eigen::MatrixXd hex8_nodes() { return table_nodes(kHexNodes, 8); }
Eigen::MatrixXd hex20_nodes() { return table_nodes(kHexNodes, 20); }

const std::array<FamilyRow, 4> kFamilies{{
    {ContinuumFamily::kQuad4, "CPS4", 2, 4, quad4_nodes, serendipity_shape<quad4_nodes, false>,
     tensor_gauss<2, 2>},
    {ContinuumFamily::kQuad8, "CPS8", 2, 8, quad8_nodes, serendipity_shape<quad8_nodes, true>,
     tensor_gauss<2, 3>},
    {ContinuumFamily::kHex8, "C3D8", 3, 8, hex8_nodes, serendipity_shape<hex8_nodes, false>,
     tensor_gauss<3, 2>},
    {ContinuumFamily::kHex20, "C3D20", 3, 20, hex20_nodes, serendipity_shape<hex20_nodes, true>,
     tensor_gauss<3, 3>},
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
