// SPDX-License-Identifier: GPL-2.0-or-later
// The plane-stress and solid elements of a mesh body, written for the
// numeric path over any scalar type: a table of element families by
// CalculiX type (solid_family: serendipity shape functions from the nodes'
// natural coordinates, full Gauss-Legendre quadrature by gauss_rule of
// beam.hpp), the material points and the small-strain energy
// 1/2 int eps^T D eps. Nothing is shared with generator/fem but the basis B
// of the coordinates (FlexibleData::basis).
#pragma once

#include <array>
#include <stdexcept>
#include <string>
#include <vector>

#include "numeric/beam.hpp"
#include "numeric/instance.hpp"

namespace kanegen::numeric {

/// The natural coordinates (-1, 0, 1) of the corner nodes of a quadrilateral
/// (D = 2) or a hexahedron (D = 3), CalculiX order: counter-clockwise (the
/// bottom face, then the top), and with Quadratic the mid-edge nodes of the
/// edges 1-2, 2-3, ... (then the vertical edges).
template <int D, bool Quadratic>
std::vector<std::array<int, 3>> box_nodes() {
  const std::vector<std::array<int, 3>> quad{{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
  std::vector<std::array<int, 3>> corners = quad;
  if (D == 3) {
    corners.clear();
    for (int z : {-1, 1})
      for (const auto& c : quad) corners.push_back({c[0], c[1], z});
  }
  if (!Quadratic) return corners;
  const auto middle = [](const std::array<int, 3>& a, const std::array<int, 3>& b) {
    return std::array<int, 3>{(a[0] + b[0]) / 2, (a[1] + b[1]) / 2, (a[2] + b[2]) / 2};
  };
  std::vector<std::array<int, 3>> out = corners;
  for (int face = 0; face < (D == 3 ? 8 : 4); face += 4)
    for (int i = 0; i < 4; ++i) out.push_back(middle(corners[face + i], corners[face + (i + 1) % 4]));
  if (D == 3)
    for (int i = 0; i < 4; ++i) out.push_back(middle(corners[i], corners[i + 4]));
  return out;
}

/// Shape function of the node at natural coordinates a, at xi, over a scalar
/// type (a dual number gives its derivative). d: the dimension.
template <class T>
T shape_value(const std::array<int, 3>& a, const std::array<T, 3>& xi, int d, bool quadratic) {
  T product(1.0);
  int zero_axis = -1;
  for (int k = 0; k < d; ++k) {
    if (a[k] == 0) {
      zero_axis = k;
      product = product * (T(1.0) - xi[k] * xi[k]);
    } else {
      product = product * (T(1.0) + xi[k] * static_cast<double>(a[k])) * 0.5;
    }
  }
  if (!quadratic || zero_axis >= 0) return product;
  // A corner of a serendipity element.
  T sum(-(d - 1.0));
  for (int k = 0; k < d; ++k) sum = sum + xi[k] * static_cast<double>(a[k]);
  return product * sum;
}

/// A quadrature point in natural coordinates and its weight.
struct NaturalPoint {
  std::array<double, 3> xi;
  double weight;
};

/// An element family as the numeric path writes it, independently of
/// generator/fem: its nodes, its shape functions (over dual numbers, whose
/// derivative part gives dN/dxi) and its quadrature.
struct SolidFamily {
  const char* name;  ///< CalculiX type
  int dimension;
  int nodes;
  Dual<double> (*shape)(int node, const std::array<Dual<double>, 3>& xi);
  std::vector<NaturalPoint> (*points)();
};

template <int D, bool Quadratic>
Dual<double> box_shape(int node, const std::array<Dual<double>, 3>& xi) {
  static const std::vector<std::array<int, 3>> natural = box_nodes<D, Quadratic>();
  return shape_value(natural[static_cast<std::size_t>(node)], xi, D, Quadratic);
}

/// Full Gauss-Legendre integration on [-1, 1]^D, N points per direction.
template <int D, int N>
std::vector<NaturalPoint> box_gauss() {
  const GaussRule rule = gauss_rule(N);  // on [0, 1]
  int total = 1;
  for (int k = 0; k < D; ++k) total *= N;
  std::vector<NaturalPoint> points;
  for (int p = 0; p < total; ++p) {
    NaturalPoint point{{0, 0, 0}, 1};
    for (int k = 0, rest = p; k < D; ++k, rest /= N) {
      point.xi[k] = 2 * rule.points[rest % N] - 1;
      point.weight *= 2 * rule.weights[rest % N];
    }
    points.push_back(point);
  }
  return points;
}

/// Tetrahedra and wedges, from the vertices each node lies between: a corner
/// is (a, a), a mid-edge node (a, b). The tetrahedron's volume coordinates
/// are (1 - xi - eta - zeta, xi, eta, zeta); the wedge's vertices are
/// triangle vertex t (area coordinates (1 - xi - eta, xi, eta)) at level
/// h = -1 (bottom, vertices 0-2) or h = 1 (top, 3-5), zeta in [-1, 1].
/// CalculiX order: C3D10's mid-edge nodes on 1-2, 2-3, 3-1, 1-4, 2-4, 3-4;
/// C3D15's on 1-2, 2-3, 3-1, 4-5, 5-6, 6-4, 1-4, 2-5, 3-6.
inline const std::array<std::array<int, 2>, 15>& simplex_node_vertices(bool tet) {
  static const std::array<std::array<int, 2>, 15> tet10{
      {{0, 0}, {1, 1}, {2, 2}, {3, 3}, {0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}}};
  static const std::array<std::array<int, 2>, 15> wedge{{{0, 0},
                                                         {1, 1},
                                                         {2, 2},
                                                         {3, 3},
                                                         {4, 4},
                                                         {5, 5},
                                                         {0, 1},
                                                         {1, 2},
                                                         {2, 0},
                                                         {3, 4},
                                                         {4, 5},
                                                         {5, 3},
                                                         {0, 3},
                                                         {1, 4},
                                                         {2, 5}}};
  return tet ? tet10 : wedge;
}

/// The quadratic tetrahedron: L_a (2 L_a - 1) at a corner, 4 L_a L_b between.
inline Dual<double> tet10_shape(int node, const std::array<Dual<double>, 3>& xi) {
  const std::array<Dual<double>, 4> L{Dual<double>(1.0) - xi[0] - xi[1] - xi[2], xi[0], xi[1], xi[2]};
  const auto& v = simplex_node_vertices(true)[static_cast<std::size_t>(node)];
  if (v[0] == v[1]) return L[v[0]] * (L[v[0]] * 2.0 - 1.0);
  return L[v[0]] * L[v[1]] * 4.0;
}

/// The wedges: a linear one is the triangle's L_t times (1 + h zeta) / 2. The
/// quadratic (serendipity) one: a corner L_t (1 + h zeta) (2 L_t + h zeta - 2) / 2,
/// a node between two vertices of one level 2 L_s L_t (1 + h zeta), a node
/// between the levels L_t (1 - zeta^2).
template <bool Quadratic>
Dual<double> wedge_shape(int node, const std::array<Dual<double>, 3>& xi) {
  const std::array<Dual<double>, 3> L{Dual<double>(1.0) - xi[0] - xi[1], xi[0], xi[1]};
  const auto& v = simplex_node_vertices(false)[static_cast<std::size_t>(node)];
  const int s = v[0] % 3, t = v[1] % 3;
  const double h0 = v[0] < 3 ? -1.0 : 1.0, h1 = v[1] < 3 ? -1.0 : 1.0;
  const Dual<double> up = xi[2] * h0 + 1.0;  // 1 + h zeta
  if (!Quadratic) return L[t] * up * 0.5;
  if (v[0] == v[1]) return L[t] * up * (L[t] * 2.0 + xi[2] * h0 - 2.0) * 0.5;
  if (h0 == h1) return L[s] * L[t] * up * 2.0;
  return L[t] * (Dual<double>(1.0) - xi[2] * xi[2]);
}

/// CalculiX's rule for C3D10: 4 points, the volume coordinates a, a, a and
/// 1 - 3a in turn, a = 0.1381966011250105 ((5 - sqrt 5) / 20), weight 1/24.
inline std::vector<NaturalPoint> tet_gauss() {
  const double a = 0.1381966011250105, b = 1 - 3 * a;
  std::vector<NaturalPoint> points;
  for (int k = 0; k < 4; ++k) {
    std::array<double, 4> L{a, a, a, a};
    L[static_cast<std::size_t>(k)] = b;
    points.push_back({{L[1], L[2], L[3]}, 1.0 / 24});
  }
  return points;
}

/// CalculiX's rules for the wedges: C3D6 the triangle's centroid (weight
/// 1/2) times 2 Gauss points in zeta; C3D15 the triangle's points with area
/// coordinates (2/3, 1/6, 1/6) in turn (weight 1/6) times 3 Gauss points.
template <bool Quadratic>
std::vector<NaturalPoint> wedge_gauss() {
  const int n = Quadratic ? 3 : 2;
  const GaussRule rule = gauss_rule(n);  // on [0, 1]
  std::vector<NaturalPoint> points;
  for (int z = 0; z < n; ++z) {
    const double zeta = 2 * rule.points[z] - 1, wz = 2 * rule.weights[z];
    if (!Quadratic) {
      points.push_back({{1.0 / 3, 1.0 / 3, zeta}, 0.5 * wz});
      continue;
    }
    for (int k = 0; k < 3; ++k) {
      std::array<double, 3> L{1.0 / 6, 1.0 / 6, 1.0 / 6};
      L[static_cast<std::size_t>(k)] = 2.0 / 3;
      points.push_back({{L[1], L[2], zeta}, wz / 6});
    }
  }
  return points;
}

/// The family of a CalculiX element type; throws std::invalid_argument for
/// one the numeric path does not know.
inline const SolidFamily& solid_family(const std::string& type) {
  static const SolidFamily families[] = {
      {"CPS4", 2, 4, box_shape<2, false>, box_gauss<2, 2>},
      {"CPS8", 2, 8, box_shape<2, true>, box_gauss<2, 3>},
      {"C3D8", 3, 8, box_shape<3, false>, box_gauss<3, 2>},
      {"C3D20", 3, 20, box_shape<3, true>, box_gauss<3, 3>},
      {"C3D10", 3, 10, tet10_shape, tet_gauss},
      {"C3D6", 3, 6, wedge_shape<false>, wedge_gauss<false>},
      {"C3D15", 3, 15, wedge_shape<true>, wedge_gauss<true>},
  };
  for (const SolidFamily& f : families)
    if (type == f.name) return f;
  throw std::invalid_argument("numeric path: no element family " + type + " in numeric/solid.hpp");
}

/// The element's quadrature, from the undeformed node positions `x` (link
/// frame); thickness for plane elements. Throws on a non-positive det J.
inline void set_up_solid(SolidElementData& e, const std::vector<Vec<double>>& x, double thickness) {
  const SolidFamily& family = solid_family(e.type);
  const int d = family.dimension, n = family.nodes;
  e.dimension = d;
  for (const NaturalPoint& q : family.points()) {
    const std::array<double, 3>& xi = q.xi;
    const double w = q.weight;
    // dN/dxi by dual numbers, one axis at a time.
    std::vector<double> N(n), dxi(n * d);
    for (int k = 0; k < d; ++k) {
      std::array<Dual<double>, 3> z{Dual<double>(xi[0]), Dual<double>(xi[1]), Dual<double>(xi[2])};
      z[k].d = 1;
      for (int i = 0; i < n; ++i) {
        const Dual<double> v = family.shape(i, z);
        N[i] = v.v;
        dxi[i * d + k] = v.d;
      }
    }
    // J(a, k) = dX_a / dxi_k over the element's own dimensions.
    double J[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
    Vec<double> X{0, 0, 0};
    for (int i = 0; i < n; ++i)
      for (int a = 0; a < 3; ++a) {
        X[a] += N[i] * x[i][a];
        for (int k = 0; k < d; ++k)
          if (a < d) J[a][k] += dxi[i * d + k] * x[i][a];
      }
    double det, inv[3][3];
    if (d == 2) {
      det = J[0][0] * J[1][1] - J[0][1] * J[1][0];
      inv[0][0] = J[1][1] / det, inv[0][1] = -J[0][1] / det;
      inv[1][0] = -J[1][0] / det, inv[1][1] = J[0][0] / det;
    } else {
      det = J[0][0] * (J[1][1] * J[2][2] - J[1][2] * J[2][1]) -
            J[0][1] * (J[1][0] * J[2][2] - J[1][2] * J[2][0]) +
            J[0][2] * (J[1][0] * J[2][1] - J[1][1] * J[2][0]);
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) {
          // inverse = adjugate / det: cofactor of (c, r)
          const int r1 = (c + 1) % 3, r2 = (c + 2) % 3, c1 = (r + 1) % 3, c2 = (r + 2) % 3;
          inv[r][c] = (J[r1][c1] * J[r2][c2] - J[r1][c2] * J[r2][c1]) / det;
        }
    }
    if (!(det > 0)) throw std::invalid_argument("an element of the mesh body is inverted");
    SolidElementData::Point point;
    point.N = N;
    point.X = X;
    point.weight = det * w * (d == 2 ? thickness : 1.0);
    // dN/dX_a = sum_k dN/dxi_k dxi_k/dX_a, dxi/dX = J^-1.
    point.dN.assign(n * d, 0.0);
    for (int i = 0; i < n; ++i)
      for (int a = 0; a < d; ++a)
        for (int k = 0; k < d; ++k) point.dN[i * d + a] += dxi[i * d + k] * inv[k][a];
    e.points.push_back(std::move(point));
  }
}

/// A material point's displaced position, link frame: by the dofs, and by
/// the second-order displacement u2 (second_order_displacement) if not empty.
template <class S>
Vec<S> solid_point(const FlexibleData& f, const SolidElementData& e, const SolidElementData::Point& p,
                   const std::vector<S>& dofs, const std::vector<S>& u2 = {}) {
  Vec<S> x{S(p.X[0]), S(p.X[1]), S(p.X[2])};
  for (std::size_t i = 0; i < e.nodes.size(); ++i)
    for (int a = 0; a < f.dofs_per_node; ++a) {
      const int dof = f.dof(e.nodes[i], a);
      x[a] += p.N[i] * (u2.empty() ? dofs[dof] : dofs[dof] + u2[dof]);
    }
  return x;
}

/// Small-strain energy of the element: 1/2 int eps^T D eps, isotropic, plane
/// stress in the plane.
template <class S>
S solid_strain_energy(const FlexibleData& f, const SolidElementData& e, const std::vector<S>& dofs) {
  const int d = e.dimension;
  const double E = f.E, nu = f.poisson;
  S energy(0.0);
  for (const SolidElementData::Point& p : e.points) {
    S g[3][3];  // du_a / dX_b
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) g[a][b] = S(0.0);
    for (std::size_t i = 0; i < e.nodes.size(); ++i)
      for (int a = 0; a < d; ++a)
        for (int b = 0; b < d; ++b) g[a][b] += p.dN[i * d + b] * dofs[f.dof(e.nodes[i], a)];
    S density(0.0);
    if (d == 2) {
      const S exx = g[0][0], eyy = g[1][1], gxy = g[0][1] + g[1][0];
      const double c = E / (1 - nu * nu);
      density = c * (exx * exx + eyy * eyy + 2 * nu * exx * eyy + 0.5 * (1 - nu) * gxy * gxy);
    } else {
      const double lambda = E * nu / ((1 + nu) * (1 - 2 * nu)), mu = E / (2 * (1 + nu));
      const S trace = g[0][0] + g[1][1] + g[2][2];
      density = lambda * trace * trace;
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b) {
          const S eps = 0.5 * (g[a][b] + g[b][a]);
          density += 2 * mu * eps * eps;
        }
    }
    energy += 0.5 * p.weight * density;
  }
  return energy;
}

}  // namespace kanegen::numeric
