// SPDX-License-Identifier: GPL-2.0-or-later
// Inertia invariants: totals, one element against hand integration, the
// consistent mass, coordinate changes, and the floating-frame mass matrix and
// velocity forces built from them against point-by-point sums.
#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

#include "fem/floating_frame.hpp"
#include "fem/invariants.hpp"
#include "fem_test_support.hpp"

using namespace kanegen::fem;

namespace {

double max_abs(const Eigen::MatrixXd& m) { return m.size() ? m.cwiseAbs().maxCoeff() : 0.0; }

/// A spatial L-shaped body with a tip mass and inertia: no symmetry left to hide a wrong term.
Body l_body() {
  BeamProperties p = fem_test::steel_beam(BeamKind::kSpatial);
  Body body(spatial_layout());
  const int root = body.add_node(Eigen::Vector3d(0.05, 0.0, 0.0));
  const int corner = add_beam_run(body, root, Eigen::Vector3d(0.65, 0.0, 0.0), 3, p);
  const int tip = add_beam_run(body, corner, Eigen::Vector3d(0.65, 0.4, 0.1), 2, p);
  Eigen::Matrix3d inertia;
  inertia << 0.02, 0.001, -0.002, 0.001, 0.03, 0.0005, -0.002, 0.0005, 0.025;
  body.add_point_mass(tip, 0.7, inertia);
  return body;
}

/// Every mass point with N, Nrot over all body dofs.
std::vector<MassPoint> full_points(const Body& body) {
  std::vector<MassPoint> out;
  for (const MassPointGroup& g : body.mass_point_groups())
    for (MassPoint p : g.points) {
      Eigen::MatrixXd n = Eigen::MatrixXd::Zero(3, body.num_dofs()), nr = n;
      n(Eigen::all, g.dofs) = p.N;
      nr(Eigen::all, g.dofs) = p.Nrot;
      p.N = n;
      p.Nrot = nr;
      out.push_back(p);
    }
  return out;
}

/// Partial velocities (v0, omega, qdot) of a point at r + N q: [I, -skew(r_p), N].
Eigen::MatrixXd partials(const MassPoint& p, const Eigen::VectorXd& q) {
  const int n = static_cast<int>(q.size());
  Eigen::MatrixXd l(3, 6 + n);
  l << Eigen::Matrix3d::Identity(), -skew(p.r + p.N * q), p.N;
  return l;
}

Eigen::MatrixXd rotary_partials(const MassPoint& p) {
  Eigen::MatrixXd l = Eigen::MatrixXd::Zero(3, 6 + p.Nrot.cols());
  l.block<3, 3>(0, 3).setIdentity();
  l.rightCols(p.Nrot.cols()) = p.Nrot;
  return l;
}

}  // namespace

TEST_CASE("invariants: totals of a chain are the bar's mass, moments and section inertia", "[invariants]") {
  const BeamProperties p = fem_test::steel_beam(BeamKind::kSpatial);
  const double L = 0.8, rho = p.material.rho, rho_a = rho * p.section.A;
  const Body body = make_beam_chain(p, L, 5);
  const InertiaInvariants inv = body_invariants(body);
  CHECK(inv.n == body.num_dofs());
  CHECK(inv.mass == Approx(rho_a * L));
  CHECK((inv.first_moment - Eigen::Vector3d(rho_a * L * L / 2.0, 0, 0)).norm() < 1e-14 * rho_a);
  Eigen::Matrix3d second = Eigen::Matrix3d::Zero();
  second(0, 0) = rho_a * L * L * L / 3.0;
  CHECK(max_abs(inv.second_moment - second) < 1e-14 * second(0, 0));
  const Eigen::Vector3d section(rho * p.section.polar_moment(), rho * p.section.Iy, rho * p.section.Iz);
  CHECK(max_abs(inv.J - Eigen::Matrix3d(L * section.asDiagonal())) < 1e-14 * L * section.maxCoeff());
  // A rigid translation of all nodes along y moves the whole mass: S e_y-translation = m.
  Eigen::VectorXd ty = Eigen::VectorXd::Zero(body.num_dofs());
  for (int node = 0; node < body.num_nodes(); ++node) ty[body.dof(node, DofKind::kUy)] = 1.0;
  CHECK((inv.S * ty - Eigen::Vector3d(0, inv.mass, 0)).norm() < 1e-12 * inv.mass);
}

TEST_CASE("invariants: int rho N^T N (+ torsion) is the consistent mass matrix", "[invariants]") {
  for (BeamKind kind : {BeamKind::kPlanar, BeamKind::kSpatial}) {
    const Body body = make_beam_chain(fem_test::steel_beam(kind), 1.1, 7);
    const InertiaInvariants inv = body_invariants(body);
    const Eigen::MatrixXd M = body.mass();
    CHECK(max_abs(inv.elastic_mass() - M) < 1e-14 * max_abs(M));
    Eigen::MatrixXd translational = M;
    for (int node = 0; node < body.num_nodes(); ++node) {  // the torsion rows are rho Ip, not rho A
      const int d = body.dof(node, DofKind::kRx);
      if (d < 0) continue;
      translational.row(d).setZero();
      translational.col(d).setZero();
    }
    CHECK(max_abs(inv.NtN() - translational) < 1e-14 * max_abs(M));
    if (kind == BeamKind::kPlanar) CHECK(max_abs(inv.Nrot_J_Nrot) == 0.0);
  }
}

TEST_CASE("invariants: one planar element against hand integration", "[invariants]") {
  // Element from x0 to x0 + L on the x axis; dofs (u0, v0, theta0, u1, v1, theta1).
  const BeamProperties p = fem_test::steel_beam(BeamKind::kPlanar);
  const double x0 = 0.3, L = 0.5, m = p.material.rho * p.section.A * L;
  const Body body = make_beam_chain(p, L, 1, x0);
  const InertiaInvariants inv = element_invariants(body, 0);
  const double tol = 1e-14 * m;
  // int H dxi = (1/2, L/12, 1/2, -L/12); int xi H dxi = (3/20, L/30, 7/20, -L/20).
  const Eigen::Vector4d int_h(0.5, L / 12.0, 0.5, -L / 12.0), int_xi_h(0.15, L / 30.0, 0.35, -L / 20.0);
  const int v_dofs[4] = {1, 2, 4, 5};
  CHECK(inv.mass == Approx(m));
  CHECK(inv.first_moment.x() == Approx(m * (x0 + L / 2.0)));
  CHECK(inv.second_moment(0, 0) == Approx(m * (x0 * x0 + x0 * L + L * L / 3.0)));
  CHECK(inv.S(0, 0) == Approx(m / 2.0));
  CHECK(inv.S(0, 3) == Approx(m / 2.0));
  for (int i = 0; i < 4; ++i) {
    INFO("v dof " << i);
    CHECK(inv.S(1, v_dofs[i]) == Approx(m * int_h[i]).margin(tol));
    // int rho A x N_v, x = x0 + xi L.
    CHECK(inv.S_r(3 * 0 + 1, v_dofs[i]) == Approx(m * (x0 * int_h[i] + L * int_xi_h[i])).margin(tol));
    // int rho A N_u^T N_v: the u0 row is int (1 - xi) H, the u1 row int xi H.
    CHECK(inv.S_nn[3 * 0 + 1](0, v_dofs[i]) == Approx(m * (int_h[i] - int_xi_h[i])).margin(tol));
    CHECK(inv.S_nn[3 * 0 + 1](3, v_dofs[i]) == Approx(m * int_xi_h[i]).margin(tol));
  }
  CHECK(inv.S_r(0, 0) == Approx(m * (x0 / 2.0 + L / 6.0)));
  CHECK(inv.S_r(0, 3) == Approx(m * (x0 / 2.0 + L / 3.0)));
  // int rho skew(r) N, r = (x, 0, 0): the z row is int rho x N_y.
  CHECK(max_abs(inv.skew_r_N().row(2) - inv.S_r.row(1)) == 0.0);
  CHECK(max_abs(inv.skew_r_N().row(1) + inv.S_r.row(2)) == 0.0);
  // Coriolis about z: int rho N^T skew(e_z) N = int rho (N_y^T N_x - N_x^T N_y), antisymmetric.
  const Eigen::MatrixXd cz = inv.coriolis(2);
  CHECK(max_abs(cz + cz.transpose()) < 1e-15 * m);
  CHECK(cz(v_dofs[0], 0) == Approx(m * (int_h[0] - int_xi_h[0])));
  CHECK(max_abs(inv.coriolis(0)) == 0.0);  // a planar body has no z motion
}

TEST_CASE("invariants: a change of coordinates q = B eta", "[invariants]") {
  const Body body = l_body();
  const InertiaInvariants inv = body_invariants(body);
  const Constraint c = support_constraint(body, Support::kClamped);
  const InertiaInvariants reduced = transform(inv, c.selection());
  CHECK(reduced.n == c.num_free());
  CHECK(max_abs(reduced.elastic_mass() - c.reduce(body.mass())) < 1e-14 * max_abs(body.mass()));
  CHECK(max_abs(reduced.S - inv.S(Eigen::all, c.free())) == 0.0);
  const ModalBasis modes = modal_analysis(c.reduce(body.mass()), c.reduce(body.stiffness()), 4);
  const InertiaInvariants modal = transform(reduced, modes.shapes);
  CHECK(max_abs(modal.elastic_mass() - Eigen::MatrixXd::Identity(4, 4)) < 1e-10);
  CHECK(modal.mass == inv.mass);
}

TEST_CASE("invariants: the floating-frame mass matrix equals the sum over the mass points", "[invariants]") {
  const Body body = l_body();
  const InertiaInvariants inv = body_invariants(body);
  const int n = body.num_dofs();
  const Eigen::VectorXd q = 1e-2 * Eigen::VectorXd::Random(n);
  Eigen::MatrixXd direct = Eigen::MatrixXd::Zero(6 + n, 6 + n);
  for (const MassPoint& p : full_points(body)) {
    const Eigen::MatrixXd l = partials(p, q), lr = rotary_partials(p);
    direct += p.mass * l.transpose() * l + lr.transpose() * p.J * lr;
  }
  const Eigen::MatrixXd m = ffr_mass_matrix(inv, q);
  CHECK(max_abs(m - direct) < 1e-12 * max_abs(direct));
  CHECK(max_abs(m - m.transpose()) == 0.0);
  // Free elastic dofs repeat the frame's rigid motion (M singular); the clamp removes them.
  const Constraint c = support_constraint(body, Support::kClamped);
  const Eigen::VectorXd q_free = q(c.free());
  CHECK(Eigen::LLT<Eigen::MatrixXd>(m).info() != Eigen::Success);
  CHECK(Eigen::LLT<Eigen::MatrixXd>(ffr_mass_matrix(transform(inv, c.selection()), q_free)).info() ==
        Eigen::Success);
}

TEST_CASE("invariants: the velocity forces equal the sum over the mass points", "[invariants]") {
  const Body body = l_body();
  const InertiaInvariants inv = body_invariants(body);
  const int n = body.num_dofs();
  const Eigen::VectorXd q = 1e-2 * Eigen::VectorXd::Random(n), qdot = Eigen::VectorXd::Random(n);
  const Eigen::Vector3d omega(0.7, -1.3, 2.1), g(0.5, -9.81, 1.0);
  Eigen::VectorXd direct = Eigen::VectorXd::Zero(6 + n), gravity = Eigen::VectorXd::Zero(6 + n);
  for (const MassPoint& p : full_points(body)) {
    const Eigen::Vector3d rp = p.r + p.N * q;
    const Eigen::Vector3d a = omega.cross(omega.cross(rp)) + 2.0 * omega.cross(Eigen::Vector3d(p.N * qdot));
    direct -= p.mass * partials(p, q).transpose() * a;
    gravity += p.mass * partials(p, q).transpose() * g;
    const Eigen::Vector3d omega_p = omega + p.Nrot * qdot;
    direct.segment<3>(3) -= omega.cross(Eigen::Vector3d(p.J * omega_p));
  }
  CHECK(max_abs(ffr_velocity_forces(inv, q, qdot, omega) - direct) < 1e-12 * max_abs(direct));
  CHECK(max_abs(ffr_gravity_forces(inv, q, g) - gravity) < 1e-12 * max_abs(gravity));
}

TEST_CASE("invariants: the inertia forces do the work -dT/dt (energy consistency)", "[invariants]") {
  // With F* = -M(q) (a0, alpha, qddot) + Q and a0 = v0dot + omega x v0:
  // -u.F* = dT/dt = u.M udot + u.Mdot u / 2  <=>  u.M (omega x v0, 0, 0) - u.Q = u.Mdot u / 2.
  const Body body = l_body();
  const InertiaInvariants inv = body_invariants(body);
  const int n = body.num_dofs();
  const Eigen::VectorXd q = 1e-2 * Eigen::VectorXd::Random(n), qdot = Eigen::VectorXd::Random(n);
  const Eigen::Vector3d v0(0.3, -0.2, 0.5), omega(0.7, -1.3, 2.1);
  Eigen::VectorXd u(6 + n);
  u << v0, omega, qdot;
  const double h = 1e-6;
  const Eigen::MatrixXd mdot =
      (ffr_mass_matrix(inv, q + h * qdot) - ffr_mass_matrix(inv, q - h * qdot)) / (2 * h);
  Eigen::VectorXd transport = Eigen::VectorXd::Zero(6 + n);
  transport.head<3>() = omega.cross(v0);
  const Eigen::MatrixXd m = ffr_mass_matrix(inv, q);
  const double lhs = u.dot(m * transport) - u.dot(ffr_velocity_forces(inv, q, qdot, omega));
  const double rhs = 0.5 * u.dot(mdot * u);
  CHECK(lhs == Approx(rhs).epsilon(1e-6).margin(1e-9 * u.dot(m * u)));
  INFO("u.Mdot u / 2 = " << rhs << ", u.M u = " << u.dot(m * u));
  CHECK(std::abs(rhs) > 1e-3 * u.dot(m * u));  // the identity is not 0 = 0
}
