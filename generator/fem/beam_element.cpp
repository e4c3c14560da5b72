// SPDX-License-Identifier: GPL-2.0-or-later
#include "fem/beam_element.hpp"

#include <stdexcept>

#include "fem/quadrature.hpp"

namespace kanegen::fem {

namespace {

// Dof offsets within a node.
constexpr int kU = 0, kV = 1;
constexpr int kPlanarRz = 2;
constexpr int kW = 2, kRx = 3, kRy = 4, kRz = 5;

// Scatters a 4 x 4 bending block into m with the plane's dof signs.
void add_bending_block(Eigen::MatrixXd& m, const int dof[4], const double sign[4], const Eigen::Matrix4d& b) {
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) m(dof[i], dof[j]) += sign[i] * sign[j] * b(i, j);
}

void add_two_node_block(Eigen::MatrixXd& m, int d0, int d1, double diag, double off) {
  m(d0, d0) += diag;
  m(d1, d1) += diag;
  m(d0, d1) += off;
  m(d1, d0) += off;
}

}  // namespace

BeamElement::BeamElement(BeamKind kind, double length, const BeamSection& section, const Material& material,
                         bool bending_rotary_inertia)
    : kind_(kind),
      length_(length),
      section_(section),
      material_(material),
      bending_rotary_inertia_(bending_rotary_inertia) {
  if (!(length > 0.0)) throw std::invalid_argument("BeamElement: length must be positive");
  if (!(section.A > 0.0 && section.Iz > 0.0))
    throw std::invalid_argument("BeamElement: section needs A > 0 and Iz > 0");
  if (!(material.E > 0.0 && material.rho > 0.0))
    throw std::invalid_argument("BeamElement: material needs E > 0 and rho > 0");
  if (kind == BeamKind::kSpatial && !(section.Iy > 0.0 && section.J > 0.0 && material.G > 0.0))
    throw std::invalid_argument("BeamElement: a spatial beam needs Iy > 0, J > 0 and G > 0");
}

const DofLayout& BeamElement::node_layout() const {
  return kind_ == BeamKind::kPlanar ? planar_layout() : spatial_layout();
}

Eigen::Matrix3Xd BeamElement::node_positions() const {
  Eigen::Matrix3Xd p = Eigen::Matrix3Xd::Zero(3, 2);
  p(0, 1) = length_;
  return p;
}

Eigen::Vector4d BeamElement::hermite(double xi, double length) {
  const double x2 = xi * xi, x3 = x2 * xi;
  return {1.0 - 3.0 * x2 + 2.0 * x3, length * (xi - 2.0 * x2 + x3), 3.0 * x2 - 2.0 * x3, length * (x3 - x2)};
}

Eigen::Vector4d BeamElement::hermite_dx(double xi, double length) {
  const double x2 = xi * xi;
  return {(6.0 * x2 - 6.0 * xi) / length, 1.0 - 4.0 * xi + 3.0 * x2, (6.0 * xi - 6.0 * x2) / length,
          3.0 * x2 - 2.0 * xi};
}

Eigen::Vector4d BeamElement::hermite_dxx(double xi, double length) {
  return {(12.0 * xi - 6.0) / (length * length), (6.0 * xi - 4.0) / length,
          (6.0 - 12.0 * xi) / (length * length), (6.0 * xi - 2.0) / length};
}

Eigen::MatrixXd BeamElement::resultant_matrix(double xi) const {
  const bool spatial = kind_ == BeamKind::kSpatial;
  Eigen::MatrixXd r = Eigen::MatrixXd::Zero(spatial ? 4 : 2, num_dofs());
  const double ea = material_.E * section_.A / length_;
  r(0, dof(0, kU)) = -ea;
  r(0, dof(1, kU)) = ea;
  const Eigen::Vector4d ddh = hermite_dxx(xi, length_);
  const auto planes = bending_planes();
  // v plane: M_z = E Iz v''; w plane: M_y = -E Iy w'' (the plane's signs map dofs to w).
  const int row[2] = {spatial ? 3 : 1, 2};
  const double sign[2] = {1.0, -1.0};
  for (std::size_t p = 0; p < planes.size(); ++p)
    for (int i = 0; i < 4; ++i)
      r(row[p], planes[p].dof[i]) += sign[p] * planes[p].EI * planes[p].sign[i] * ddh[i];
  if (spatial) {
    const double gj = material_.G * section_.J / length_;
    r(1, dof(0, kRx)) = -gj;
    r(1, dof(1, kRx)) = gj;
  }
  return r;
}

Eigen::MatrixXd BeamElement::slope_matrix(double xi) const {
  const auto planes = bending_planes();
  Eigen::MatrixXd g = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(planes.size()), num_dofs());
  const Eigen::Vector4d dh = hermite_dx(xi, length_);
  for (std::size_t p = 0; p < planes.size(); ++p)
    for (int i = 0; i < 4; ++i)
      g(static_cast<Eigen::Index>(p), planes[p].dof[i]) += planes[p].sign[i] * dh[i];
  return g;
}

std::vector<BeamElement::Bending> BeamElement::bending_planes() const {
  const double E = material_.E, rho = material_.rho;
  if (kind_ == BeamKind::kPlanar)
    return {{{dof(0, kV), dof(0, kPlanarRz), dof(1, kV), dof(1, kPlanarRz)},
             {1, 1, 1, 1},
             E * section_.Iz,
             rho * section_.Iz}};
  return {
      {{dof(0, kV), dof(0, kRz), dof(1, kV), dof(1, kRz)}, {1, 1, 1, 1}, E * section_.Iz, rho * section_.Iz},
      // w = H0 w_0 - H1 theta_y0 + H2 w_1 - H3 theta_y1, since theta_y = -dw/dx.
      {{dof(0, kW), dof(0, kRy), dof(1, kW), dof(1, kRy)},
       {1, -1, 1, -1},
       E * section_.Iy,
       rho * section_.Iy}};
}

ShapeSample BeamElement::shape(const Eigen::Vector3d& xi_vec) const {
  const double xi = xi_vec.x();
  const int n = num_dofs();
  ShapeSample s;
  s.r = Eigen::Vector3d(xi * length_, 0.0, 0.0);
  s.N = Eigen::MatrixXd::Zero(3, n);
  s.Nrot = Eigen::MatrixXd::Zero(3, n);
  s.N(0, dof(0, kU)) = 1.0 - xi;
  s.N(0, dof(1, kU)) = xi;
  const Eigen::Vector4d h = hermite(xi, length_), dh = hermite_dx(xi, length_);
  const auto planes = bending_planes();
  // The plane's displacement row (y or z) and the rotation row (z: +v', y: -w').
  const int disp_row[2] = {1, 2}, rot_row[2] = {2, 1};
  const double rot_sign[2] = {1.0, -1.0};
  for (std::size_t p = 0; p < planes.size(); ++p)
    for (int i = 0; i < 4; ++i) {
      s.N(disp_row[p], planes[p].dof[i]) += planes[p].sign[i] * h[i];
      s.Nrot(rot_row[p], planes[p].dof[i]) += rot_sign[p] * planes[p].sign[i] * dh[i];
    }
  if (kind_ == BeamKind::kSpatial) {
    s.Nrot(0, dof(0, kRx)) = 1.0 - xi;
    s.Nrot(0, dof(1, kRx)) = xi;
  }
  return s;
}

std::vector<MassPoint> BeamElement::mass_points() const {
  const QuadratureRule rule = gauss_legendre(4);
  const double rho = material_.rho;
  const Eigen::Vector3d section_inertia(rho * section_.polar_moment(), rho * section_.Iy, rho * section_.Iz);
  std::vector<MassPoint> points;
  for (std::size_t q = 0; q < rule.points.size(); ++q) {
    const ShapeSample s = shape(Eigen::Vector3d(rule.points[q], 0.0, 0.0));
    const double dx = length_ * rule.weights[q];
    MassPoint p;
    p.mass = rho * section_.A * dx;
    p.r = s.r;
    p.N = s.N;
    p.J = (dx * section_inertia).asDiagonal();
    p.Nrot = s.Nrot;
    // Euler-Bernoulli: the slopes carry no rotary inertia unless asked for.
    if (!bending_rotary_inertia_) p.Nrot.bottomRows(2).setZero();
    points.push_back(std::move(p));
  }
  return points;
}

Eigen::MatrixXd BeamElement::stiffness() const {
  const int n = num_dofs();
  const double L = length_, L2 = L * L;
  Eigen::MatrixXd k = Eigen::MatrixXd::Zero(n, n);
  const double ea = material_.E * section_.A / L;
  add_two_node_block(k, dof(0, kU), dof(1, kU), ea, -ea);
  if (kind_ == BeamKind::kSpatial) {
    const double gj = material_.G * section_.J / L;
    add_two_node_block(k, dof(0, kRx), dof(1, kRx), gj, -gj);
  }
  for (const Bending& b : bending_planes()) {
    Eigen::Matrix4d kb;
    // clang-format off
    kb << 12, 6 * L, -12, 6 * L,
          6 * L, 4 * L2, -6 * L, 2 * L2,
          -12, -6 * L, 12, -6 * L,
          6 * L, 2 * L2, -6 * L, 4 * L2;
    // clang-format on
    add_bending_block(k, b.dof, b.sign, b.EI / (L2 * L) * kb);
  }
  return k;
}

Eigen::MatrixXd BeamElement::consistent_mass() const {
  const int n = num_dofs();
  const double L = length_, L2 = L * L, rho = material_.rho;
  Eigen::MatrixXd m = Eigen::MatrixXd::Zero(n, n);
  const double bar = rho * section_.A * L / 6.0;
  add_two_node_block(m, dof(0, kU), dof(1, kU), 2.0 * bar, bar);
  if (kind_ == BeamKind::kSpatial) {
    const double tor = rho * section_.polar_moment() * L / 6.0;
    add_two_node_block(m, dof(0, kRx), dof(1, kRx), 2.0 * tor, tor);
  }
  Eigen::Matrix4d mb, rb;
  // clang-format off
  mb << 156, 22 * L, 54, -13 * L,
        22 * L, 4 * L2, 13 * L, -3 * L2,
        54, 13 * L, 156, -22 * L,
        -13 * L, -3 * L2, -22 * L, 4 * L2;
  rb << 36, 3 * L, -36, 3 * L,
        3 * L, 4 * L2, -3 * L, -L2,
        -36, -3 * L, 36, -3 * L,
        3 * L, -L2, -3 * L, 4 * L2;
  // clang-format on
  for (const Bending& b : bending_planes()) {
    add_bending_block(m, b.dof, b.sign, rho * section_.A * L / 420.0 * mb);
    if (bending_rotary_inertia_) add_bending_block(m, b.dof, b.sign, b.rhoI / (30.0 * L) * rb);
  }
  return m;
}

Eigen::MatrixXd BeamElement::geometric_stiffness_linear(double n0, double n1) const {
  const int n = num_dofs();
  const double L = length_, L2 = L * L;
  // int (1 - xi) G^T G dx and int xi G^T G dx, times 60 L.
  Eigen::Matrix4d a0, a1;
  // clang-format off
  a0 << 36, 0, -36, 6 * L,
        0, 6 * L2, 0, -L2,
        -36, 0, 36, -6 * L,
        6 * L, -L2, -6 * L, 2 * L2;
  a1 << 36, 6 * L, -36, 0,
        6 * L, 2 * L2, -6 * L, -L2,
        -36, -6 * L, 36, 0,
        0, -L2, 0, 6 * L2;
  // clang-format on
  const Eigen::Matrix4d kb = (n0 * a0 + n1 * a1) / (60.0 * L);
  Eigen::MatrixXd k = Eigen::MatrixXd::Zero(n, n);
  for (const Bending& b : bending_planes()) add_bending_block(k, b.dof, b.sign, kb);
  return k;
}

Eigen::MatrixXd BeamElement::geometric_stiffness(const Prestress& prestress) const {
  if (!prestress.axial_force) throw std::invalid_argument("BeamElement: the prestress has no axial force");
  const QuadratureRule rule = gauss_legendre(6);
  Eigen::Matrix4d kb = Eigen::Matrix4d::Zero();
  for (std::size_t q = 0; q < rule.points.size(); ++q) {
    const Eigen::Vector4d g = hermite_dx(rule.points[q], length_);
    kb += (length_ * rule.weights[q] * prestress.axial_force(rule.points[q])) * g * g.transpose();
  }
  const int n = num_dofs();
  Eigen::MatrixXd k = Eigen::MatrixXd::Zero(n, n);
  for (const Bending& b : bending_planes()) add_bending_block(k, b.dof, b.sign, kb);
  return k;
}

}  // namespace kanegen::fem
