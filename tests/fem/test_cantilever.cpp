// SPDX-License-Identifier: GPL-2.0-or-later
// Cantilevers against Euler-Bernoulli and bar/shaft theory: bending
// frequencies and their convergence, axial and torsional frequencies (the
// exact frequencies of the discrete model and the continuum limit), and the
// static tip deflection, which Hermite elements reproduce exactly.
#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

#include "fem_test_support.hpp"

using namespace kanegen::fem;
using fem_test::rel_error;

namespace {

constexpr double kLength = 1.2;

struct Plane {
  const char* name;
  std::vector<DofKind> kinds;
  double EI;
};

std::vector<Plane> bending_planes(const BeamProperties& p) {
  const double E = p.material.E;
  if (p.kind == BeamKind::kPlanar) return {{"planar v", {DofKind::kUy, DofKind::kRz}, E * p.section.Iz}};
  return {{"spatial v", {DofKind::kUy, DofKind::kRz}, E * p.section.Iz},
          {"spatial w", {DofKind::kUz, DofKind::kRy}, E * p.section.Iy}};
}

/// Relative errors of the first three bending frequencies in each plane.
std::vector<std::vector<double>> bending_errors(BeamKind kind, int elements) {
  const BeamProperties p = fem_test::steel_beam(kind);
  const Body body = make_beam_chain(p, kLength, elements);
  const Constraint c = support_constraint(body, Support::kClamped);
  const Eigen::MatrixXd M = body.mass(), K = body.stiffness();
  std::vector<std::vector<double>> errors;
  for (const Plane& plane : bending_planes(p)) {
    const auto omega = fem_test::frequencies_of(body, c, M, K, plane.kinds);
    REQUIRE(omega.size() >= 3);
    std::vector<double> e;
    for (int n = 0; n < 3; ++n) {
      const double exact = fem_test::bending_omega(fem_test::cantilever_beta_l(n), plane.EI,
                                                   p.material.rho * p.section.A, kLength);
      e.push_back(rel_error(omega[n], exact));
    }
    errors.push_back(e);
  }
  return errors;
}

/// Bar of n linear elements with consistent mass, clamped-free: mode u_j = sin(j theta),
/// theta = (2k - 1) pi / (2n), omega^2 = 6 c^2 / h^2 (1 - cos theta) / (2 + cos theta).
double discrete_bar_omega(int k, int n, double wave_speed, double length) {
  const double theta = (2.0 * k - 1.0) * M_PI / (2.0 * n), h = length / n;
  return std::sqrt(6.0) * wave_speed / h * std::sqrt((1.0 - std::cos(theta)) / (2.0 + std::cos(theta)));
}

/// Static displacement under the nodal loads f, zero on the fixed dofs.
Eigen::VectorXd solve(const Body& body, const Constraint& c, const Eigen::VectorXd& f) {
  return c.expand(c.reduce(body.stiffness()).ldlt().solve(Eigen::VectorXd(f(c.free()))));
}

double continuum_bar_omega(int k, double wave_speed, double length) {
  return (2.0 * k - 1.0) * M_PI / 2.0 * wave_speed / length;
}

}  // namespace

TEST_CASE("cantilever: 10 elements give the first three bending frequencies within 0.1 %", "[cantilever]") {
  for (BeamKind kind : {BeamKind::kPlanar, BeamKind::kSpatial}) {
    const auto errors = bending_errors(kind, 10);
    const auto planes = bending_planes(fem_test::steel_beam(kind));
    for (std::size_t p = 0; p < errors.size(); ++p)
      for (int n = 0; n < 3; ++n) {
        INFO(planes[p].name << " mode " << n + 1 << " error " << errors[p][n] * 100 << " %");
        CHECK(std::abs(errors[p][n]) < 1e-3);
        CHECK(errors[p][n] > 0.0);  // a conforming Ritz model is stiffer than the beam
      }
  }
}

TEST_CASE("cantilever: bending frequencies converge monotonically from above (2, 5, 10, 20 elements)",
          "[cantilever]") {
  for (BeamKind kind : {BeamKind::kPlanar, BeamKind::kSpatial}) {
    std::vector<std::vector<std::vector<double>>> by_mesh;
    for (int elements : {2, 5, 10, 20}) by_mesh.push_back(bending_errors(kind, elements));
    for (std::size_t p = 0; p < by_mesh[0].size(); ++p)
      for (int n = 0; n < 3; ++n)
        for (std::size_t m = 1; m < by_mesh.size(); ++m) {
          INFO("plane " << p << " mode " << n + 1 << " mesh " << m);
          CHECK(by_mesh[m][p][n] > 0.0);
          CHECK(by_mesh[m][p][n] < by_mesh[m - 1][p][n]);
        }
    // Hermite cubics: the error falls like h^4, so 10 -> 20 elements gains more than 8x on mode 1.
    CHECK(by_mesh[3][0][0] < by_mesh[2][0][0] / 8.0);
  }
}

TEST_CASE("cantilever: axial and torsional frequencies, discrete exact and continuum limit", "[cantilever]") {
  const BeamProperties p = fem_test::steel_beam(BeamKind::kSpatial);
  const double c_axial = std::sqrt(p.material.E / p.material.rho);
  const double c_torsion =
      std::sqrt(p.material.G * p.section.J / (p.material.rho * p.section.polar_moment()));
  for (int elements : {10, 40}) {
    const Body body = make_beam_chain(p, kLength, elements);
    const Constraint c = support_constraint(body, Support::kClamped);
    const Eigen::MatrixXd M = body.mass(), K = body.stiffness();
    const auto axial = fem_test::frequencies_of(body, c, M, K, {DofKind::kUx});
    const auto torsion = fem_test::frequencies_of(body, c, M, K, {DofKind::kRx});
    REQUIRE(axial.size() == static_cast<std::size_t>(elements));
    REQUIRE(torsion.size() == static_cast<std::size_t>(elements));
    for (int k = 1; k <= 3; ++k) {
      INFO(elements << " elements, mode " << k);
      CHECK(axial[k - 1] == Approx(discrete_bar_omega(k, elements, c_axial, kLength)).epsilon(1e-10));
      CHECK(torsion[k - 1] == Approx(discrete_bar_omega(k, elements, c_torsion, kLength)).epsilon(1e-10));
      // Linear elements converge like h^2: (theta^2 / 24) relative, from above.
      const double theta = (2.0 * k - 1.0) * M_PI / (2.0 * elements);
      const double bound = theta * theta / 24.0 * 1.05;
      const double ea = rel_error(axial[k - 1], continuum_bar_omega(k, c_axial, kLength));
      const double et = rel_error(torsion[k - 1], continuum_bar_omega(k, c_torsion, kLength));
      CHECK(ea > 0.0);
      CHECK(ea < bound);
      CHECK(et > 0.0);
      CHECK(et < bound);
    }
  }
}

TEST_CASE("cantilever: static tip load gives P L^3 / (3 E I) and P L^2 / (2 E I) exactly", "[cantilever]") {
  const double P = 37.0;
  for (BeamKind kind : {BeamKind::kPlanar, BeamKind::kSpatial})
    for (int elements : {1, 3, 10}) {
      const BeamProperties p = fem_test::steel_beam(kind);
      const Body body = make_beam_chain(p, kLength, elements);
      const Constraint c = support_constraint(body, Support::kClamped);
      const int tip = body.num_nodes() - 1;
      const double E = p.material.E, L = kLength;
      INFO("kind " << static_cast<int>(kind) << ", " << elements << " elements");
      // Load along y: v_tip = P L^3 / (3 E Iz), theta_z = + P L^2 / (2 E Iz).
      Eigen::VectorXd f = Eigen::VectorXd::Zero(body.num_dofs());
      f[body.dof(tip, DofKind::kUy)] = P;
      Eigen::VectorXd u = solve(body, c, f);
      CHECK(u[body.dof(tip, DofKind::kUy)] ==
            Approx(P * L * L * L / (3.0 * E * p.section.Iz)).epsilon(1e-10));
      CHECK(u[body.dof(tip, DofKind::kRz)] == Approx(P * L * L / (2.0 * E * p.section.Iz)).epsilon(1e-10));
      // Axial: N L / (E A).
      f.setZero();
      f[body.dof(tip, DofKind::kUx)] = P;
      u = solve(body, c, f);
      CHECK(u[body.dof(tip, DofKind::kUx)] == Approx(P * L / (E * p.section.A)).epsilon(1e-10));
      if (kind == BeamKind::kPlanar) continue;
      // Load along z: w_tip = P L^3 / (3 E Iy) and theta_y = -dw/dx = -P L^2 / (2 E Iy).
      f.setZero();
      f[body.dof(tip, DofKind::kUz)] = P;
      u = solve(body, c, f);
      CHECK(u[body.dof(tip, DofKind::kUz)] ==
            Approx(P * L * L * L / (3.0 * E * p.section.Iy)).epsilon(1e-10));
      CHECK(u[body.dof(tip, DofKind::kRy)] == Approx(-P * L * L / (2.0 * E * p.section.Iy)).epsilon(1e-10));
      CHECK(std::abs(u[body.dof(tip, DofKind::kUy)]) < 1e-15);
      // Torque: theta_x = T L / (G J).
      f.setZero();
      f[body.dof(tip, DofKind::kRx)] = P;
      u = solve(body, c, f);
      CHECK(u[body.dof(tip, DofKind::kRx)] == Approx(P * L / (p.material.G * p.section.J)).epsilon(1e-10));
    }
}
