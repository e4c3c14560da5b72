// SPDX-License-Identifier: GPL-2.0-or-later
// Geometric stiffening of mesh bodies in motion (issue 18): the second-order
// displacement field (fem/continuum_foreshortening.hpp) in the kinematics,
// against the beam models of the same bodies, which derive their stiffening
// independently (the foreshortening of Euler-Bernoulli elements, or their
// nonlinear axial strain).
//  - Kane, Ryan and Banerjee's spin-up with the beam as a CPS8 strip,
//    clamped modes or Craig-Bampton: the tip deflection history within 2 % of
//    the beam model's; without stiffening the strip diverges as the linear
//    beam does. The same with the beam as a solid (a C3D20 tube of the
//    beam's A and Iz), clamped modes or Craig-Bampton; and the tube's first
//    bending frequencies at rest against Euler-Bernoulli's.
//  - Issue 12's free pendulum as a CPS8 strip (Craig-Bampton) with a tip mass
//    on its tip interface, hinged in gravity, no drive: T + V is kept to the
//    integrator's tolerance, and the deflection follows the beam pendulums'.
#include <Eigen/Dense>
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include "flexible_helpers.hpp"
#include "free_strip.hpp"
#include "free_strip_cps8.hpp"
#include "free_strip_cps8_linear.hpp"
#include "free_strip_modal.hpp"
#include "spin_up_beam.hpp"
#ifndef KANEGEN_NO_C3D20_TUBES  // tests/flexible/tests.cmake says when and why
#include "spin_up_c3d20.hpp"
#include "spin_up_c3d20_cb.hpp"
#endif
#include "spin_up_cps8.hpp"
#include "spin_up_cps8_cb.hpp"
#include "spin_up_cps8_linear.hpp"

namespace {

using kanegen_test::initial_state;
using kanegen_test::output_index;

/// A run from x sampled every dt (Dormand-Prince at rtol): the tip's
/// deflection y, and the largest change of T + V relative to the largest T.
struct Run {
  std::vector<double> t, y;
  double drift = 0, largest = 0;
  bool ok = false;
};

template <class System, class Deflection>
Run integrate(const typename System::Params& p, std::vector<double> x, double t_end, double dt, double rtol,
              Deflection&& deflection) {
  Run out;
  const double e0 = kanegen_test::energy<System>(p, x.data());
  double worst = 0, largest_kinetic = 0;
  const auto result = kanegen_test::integrate_sampled<System>(
      p, std::move(x), t_end, dt, rtol, [&](double t, const double* state) {
        worst = std::max(worst, std::abs(kanegen_test::energy<System>(p, state) - e0));
        largest_kinetic = std::max(largest_kinetic, System::kinetic_energy(p, state, state + System::nq));
        double y[System::ny];
        System::outputs(p, t, state, state + System::nq, y);
        const double d = deflection(y);
        out.t.push_back(t);
        out.y.push_back(d);
        out.largest = std::max(out.largest, std::abs(d));
        return std::isfinite(d) && std::abs(d) < 1e6;  // stop a diverging run early
      });
  INFO(result.message);
  out.ok = result.ok();
  out.drift = largest_kinetic > 0 ? worst / largest_kinetic : 0;
  return out;
}

/// A mesh model's tip deflection in the frame of the joint that turns the
/// body (x along the undeformed body): the world position of the body on the
/// tip set (outputs tip.x, tip.y) turned back by the joint angle (angle).
template <class System>
Run mesh_run(std::vector<double> x, double t_end, double dt, double rtol) {
  const int kx = output_index<System>("tip.x"), ky = output_index<System>("tip.y"),
            ka = output_index<System>("angle");
  return integrate<System>({}, std::move(x), t_end, dt, rtol, [&](const double* y) {
    return -std::sin(y[ka]) * y[kx] + std::cos(y[ka]) * y[ky];
  });
}

/// A beam model's tip deflection: its node_displacement output tip.y (link frame).
template <class System>
Run beam_run(std::vector<double> x, double t_end, double dt, double rtol) {
  const int k = output_index<System>("tip.y");
  return integrate<System>({}, std::move(x), t_end, dt, rtol, [&](const double* y) { return y[k]; });
}

template <class System>
Run spin_up(double t_end) {
  return mesh_run<System>(initial_state<System>(), t_end, 0.05, 1e-8);
}

/// The largest |a - b| over the common samples, and the largest |b|.
std::pair<double, double> difference(const std::vector<double>& a, const std::vector<double>& b) {
  double worst = 0, scale = 0;
  for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i) {
    worst = std::max(worst, std::abs(a[i] - b[i]));
    scale = std::max(scale, std::abs(b[i]));
  }
  return {worst, scale};
}

/// The natural frequencies (rad/s, ascending) of System about its initial
/// state at rest, with the coordinate named held fixed (the prescribed hub):
/// M from the mass matrix, K from central differences of the potential
/// energy, with a step small enough for the quartic terms of a beam's
/// nonlinear axial strain (1e-3 puts mode 1 of spin_up_beam 4 % high).
template <class System>
std::vector<double> frequencies_at_rest(const char* held) {
  static_assert(System::nq == System::nu, "coordinates and speeds pair up");
  const typename System::Params p{};
  std::vector<double> q(System::q0(), System::q0() + System::nq);
  std::vector<int> free;
  for (int i = 0; i < System::nq; ++i)
    if (std::strcmp(System::coordinate_names()[i], held) != 0) free.push_back(i);
  const int n = static_cast<int>(free.size());
  Eigen::MatrixXd m_all(System::nu, System::nu);
  System::mass_matrix(p, q.data(), m_all.data());  // symmetric: the storage order does not matter
  const auto energy_at = [&](int i, double di, int j, double dj) {
    std::vector<double> x = q;
    x[static_cast<std::size_t>(i)] += di;
    x[static_cast<std::size_t>(j)] += dj;
    return System::potential_energy(p, x.data());
  };
  const double h = 1e-6;
  Eigen::MatrixXd k(n, n), m(n, n);
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < n; ++b) {
      const int i = free[static_cast<std::size_t>(a)], j = free[static_cast<std::size_t>(b)];
      m(a, b) = m_all(i, j);
      k(a, b) = (energy_at(i, h, j, h) - energy_at(i, h, j, -h) - energy_at(i, -h, j, h) +
                 energy_at(i, -h, j, -h)) /
                (4 * h * h);
    }
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> solver(k, m);
  std::vector<double> omega;
  for (int a = 0; a < n; ++a) omega.push_back(std::sqrt(std::max(0.0, solver.eigenvalues()(a))));
  return omega;
}

/// The smallest lambda_min / lambda_max over the spin-up (25 s) of System's
/// whole mass matrix and of its elastic block (all but coordinate 0, the
/// prescribed hub: the block the integration inverts).
template <class System>
std::pair<double, double> smallest_mass_ratios() {
  const typename System::Params p{};
  const auto ratio = [](const Eigen::MatrixXd& m) {
    const Eigen::VectorXd lambda = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(m).eigenvalues();
    return lambda.minCoeff() / lambda.maxCoeff();
  };
  double whole = 1, elastic = 1;
  const auto result = kanegen_test::integrate_sampled<System>(
      p, initial_state<System>(), 25.0, 0.05, 1e-8, [&](double, const double* state) {
        Eigen::MatrixXd m(System::nu, System::nu);
        System::mass_matrix(p, state, m.data());
        whole = std::min(whole, ratio(m));
        elastic = std::min(elastic, ratio(m.bottomRightCorner(System::nu - 1, System::nu - 1)));
        return true;
      });
  INFO(result.message);
  REQUIRE(result.ok());
  return {whole, elastic};
}

/// The smallest lambda_min / lambda_max of System's mass matrix, and of its
/// block of coordinates from `first_elastic` on, at 200 random states: joint
/// coordinates in [-pi, pi], elastic coordinates in [-a, a] (mass-normalised:
/// a / sqrt(body mass) is a displacement).
template <class System>
std::pair<double, double> smallest_random_mass_ratios(int first_elastic, double a) {
  const typename System::Params p{};
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const auto ratio = [](const Eigen::MatrixXd& m) {
    const Eigen::VectorXd lambda = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(m).eigenvalues();
    return lambda.minCoeff() / lambda.maxCoeff();
  };
  double whole = 1, elastic = 1;
  for (int sample = 0; sample < 200; ++sample) {
    std::vector<double> q(System::nq);
    for (int i = 0; i < System::nq; ++i)
      q[static_cast<std::size_t>(i)] = (i < first_elastic ? 3.14159 : a) * unit(rng);
    Eigen::MatrixXd m(System::nu, System::nu);
    System::mass_matrix(p, q.data(), m.data());
    whole = std::min(whole, ratio(m));
    const int n = System::nu - first_elastic;
    elastic = std::min(elastic, ratio(m.bottomRightCorner(n, n)));
  }
  return {whole, elastic};
}

/// Kane, Ryan and Banerjee's spin-up of a mesh body in clamped modes (Modal)
/// and in Craig-Bampton (CB) against the beam model: the tip deflection
/// history within 2 % of the beam's largest.
template <class Modal, class CB>
void spin_up_against_beam(const char* body) {
  const double t_end = 25.0;  // Ts = 15 s, and 10 s of steady spin at 6 rad/s
  const Run beam = beam_run<kanegen_models::spin_up_beam::System>(
      initial_state<kanegen_models::spin_up_beam::System>(), t_end, 0.05, 1e-8);
  const Run modal = spin_up<Modal>(t_end);
  const Run cb = spin_up<CB>(t_end);
  REQUIRE(beam.ok);
  REQUIRE(modal.ok);
  REQUIRE(cb.ok);
  REQUIRE(modal.t.size() == beam.t.size());
  REQUIRE(cb.t.size() == beam.t.size());
  const auto [modal_worst, scale] = difference(modal.y, beam.y);
  const auto [cb_worst, cb_scale] = difference(cb.y, beam.y);
  INFO("largest |tip deflection| of the beam " << scale << " m; largest difference: clamped modes "
                                               << modal_worst << " m, Craig-Bampton " << cb_worst << " m");
  CHECK(scale > 0.3);
  CHECK(modal_worst < 0.02 * scale);
  CHECK(cb_worst < 0.02 * scale);
  WARN("spin-up, Ws = 6 rad/s, 25 s: " << body << " against the beam, largest difference "
                                       << modal_worst / scale * 100 << " % (clamped modes), "
                                       << cb_worst / scale * 100
                                       << " % (Craig-Bampton) of the largest deflection " << scale << " m");
}

}  // namespace

TEST_CASE("spin-up: a CPS8 strip with stiffening follows the beam model within 2 %",
          "[flexible][spin-up][mesh_stiffening]") {
  spin_up_against_beam<kanegen_models::spin_up_cps8::System, kanegen_models::spin_up_cps8_cb::System>(
      "CPS8 strip");
}

TEST_CASE("spin-up: a CPS8 strip without stiffening diverges", "[flexible][spin-up][mesh_stiffening]") {
  const Run linear = spin_up<kanegen_models::spin_up_cps8_linear::System>(20.0);
  const Run stiff = spin_up<kanegen_models::spin_up_cps8::System>(20.0);
  const double reached = linear.largest, bounded = stiff.largest;
  INFO("linear: |tip| reached " << reached << " m by t = " << linear.t.back() << " s; stiffened: " << bounded
                                << " m");
  CHECK(reached > 100.0 * bounded);
  WARN("spin-up, Ws = 6 rad/s, CPS8 strip without stiffening: |tip deflection| reached "
       << reached << " m by t = " << linear.t.back() << " s (stiffened: " << bounded << " m)");
}

TEST_CASE("a free CPS8 pendulum with stiffening keeps T + V and follows the beam pendulum",
          "[flexible][energy][mesh_stiffening]") {
  using Mesh = kanegen_models::free_strip_cps8::System;
  using Linear = kanegen_models::free_strip_cps8_linear::System;
  using Nodal = kanegen_models::free_strip::System;
  using Modal = kanegen_models::free_strip_modal::System;
  const double speed = 9.0;  // released horizontal and straight at 9 rad/s, as test_energy.cpp's beams
  const auto released = [&](auto model) {
    using System = decltype(model);
    std::vector<double> x = initial_state<System>();
    x[System::nq] = speed;
    return x;
  };
  const Run mesh = mesh_run<Mesh>(released(Mesh{}), 2.0, 0.01, 1e-10);
  const Run nodal = beam_run<Nodal>(released(Nodal{}), 2.0, 0.01, 1e-10);
  const Run modal = beam_run<Modal>(released(Modal{}), 2.0, 0.01, 1e-10);
  // The linear model deflects far and slowly; 1 s shows the contrast.
  const Run linear = mesh_run<Linear>(released(Linear{}), 1.0, 0.01, 1e-10);
  REQUIRE(mesh.ok);
  REQUIRE(nodal.ok);
  REQUIRE(modal.ok);
  REQUIRE(linear.ok);
  // The nodal beam (the nonlinear axial strain) is the reference history; the
  // modal beam, an independent form of the same stiffening, shows how far two
  // correct models of this vibration apart already are.
  const auto [worst, scale] = difference(mesh.y, nodal.y);
  const auto [beams_apart, beam_scale] = difference(modal.y, nodal.y);
  INFO("T + V drift / T_max: mesh " << mesh.drift << ", linear mesh " << linear.drift
                                    << "; largest |tip| mesh " << mesh.largest << " m, nodal beam "
                                    << nodal.largest << " m, modal beam " << modal.largest
                                    << " m, linear mesh " << linear.largest
                                    << " m; largest difference from the nodal beam: mesh " << worst
                                    << " m, modal beam " << beams_apart << " m");
  CHECK(mesh.drift < 1e-7);
  CHECK(linear.drift < 1e-7);
  CHECK(std::abs(mesh.largest - nodal.largest) < 0.02 * nodal.largest);
  CHECK(std::abs(mesh.largest - modal.largest) < 0.02 * modal.largest);
  CHECK(worst < 0.1 * scale);
  CHECK(mesh.largest < 0.1 * linear.largest);
  WARN("free CPS8 pendulum at 9 rad/s, 2 s: T + V drift / T_max "
       << mesh.drift << "; largest |tip| " << mesh.largest << " m (nodal beam " << nodal.largest
       << " m, modal beam " << modal.largest << " m, linear mesh " << linear.largest
       << " m in 1 s); largest difference from the nodal beam " << worst / scale * 100 << " % (modal beam "
       << beams_apart / beam_scale * 100 << " %)");
}

#ifndef KANEGEN_NO_C3D20_TUBES
TEST_CASE("spin-up: a C3D20 tube with stiffening follows the beam model within 2 %",
          "[flexible][spin-up][mesh_stiffening]") {
  spin_up_against_beam<kanegen_models::spin_up_c3d20::System, kanegen_models::spin_up_c3d20_cb::System>(
      "C3D20 tube");
}

TEST_CASE("a C3D20 tube has the beam's first bending frequencies within 2 %", "[flexible][mesh_stiffening]") {
  // Euler-Bernoulli's clamped-free cantilever: omega_k = (beta_k L)^2 sqrt(E I / (rho A L^4)).
  const double beta_l[] = {1.8751040687, 4.6940911330, 7.8547574382};
  const double scale = std::sqrt(7e10 * 2e-7 / (3000 * 4e-4 * std::pow(10.0, 4)));
  const std::vector<double> beam = frequencies_at_rest<kanegen_models::spin_up_beam::System>("hub");
  const std::vector<double> modal = frequencies_at_rest<kanegen_models::spin_up_c3d20::System>("hub");
  const std::vector<double> cb = frequencies_at_rest<kanegen_models::spin_up_c3d20_cb::System>("hub");
  REQUIRE(beam.size() >= 3);
  REQUIRE(modal.size() >= 6);
  REQUIRE(cb.size() >= 6);
  for (int k = 0; k < 3; ++k) {
    const double exact = beta_l[k] * beta_l[k] * scale;
    const auto i = static_cast<std::size_t>(k);
    INFO("bending mode " << k + 1 << ": Euler-Bernoulli " << exact << " rad/s, beam model " << beam[i]
                         << ", tube clamped modes " << modal[2 * i] << ", " << modal[2 * i + 1]
                         << ", Craig-Bampton " << cb[2 * i] << ", " << cb[2 * i + 1]);
    CHECK(beam[i] == Approx(exact).epsilon(0.01));
    // The tube bends alike across and in the plane of rotation: a pair per beam mode.
    for (std::size_t j : {2 * i, 2 * i + 1}) {
      CHECK(modal[j] == Approx(exact).epsilon(0.02));
      CHECK(cb[j] == Approx(exact).epsilon(0.02));
      CHECK(cb[j] == Approx(beam[i]).epsilon(0.02));
    }
    WARN("C3D20 tube, bending mode " << k + 1 << ": Euler-Bernoulli " << exact << " rad/s, beam model "
                                     << beam[i] << " (" << (beam[i] / exact - 1) * 100 << " %), tube "
                                     << modal[2 * i] << " (" << (modal[2 * i] / exact - 1) * 100
                                     << " %, clamped modes), " << cb[2 * i] << " ("
                                     << (cb[2 * i] / exact - 1) * 100 << " %, Craig-Bampton)");
  }
}

TEST_CASE("spin-up: the C3D20 tube's mass matrix stays positive definite where it is inverted",
          "[flexible][spin-up][mesh_stiffening]") {
  // docs/flexible-bodies.md, "Limit: Craig-Bampton bases and the truncated
  // mass": with stiffening the mass can lose definiteness at large interface
  // motions; the block the spin-up inverts must not.
  const auto [cb_whole, cb_elastic] = smallest_mass_ratios<kanegen_models::spin_up_c3d20_cb::System>();
  const auto [modal_whole, modal_elastic] = smallest_mass_ratios<kanegen_models::spin_up_c3d20::System>();
  CHECK(cb_elastic > 0);
  CHECK(modal_elastic > 0);
  // The whole M too, since the elastic mass is kept to second order (it reached -3.0e-6 without).
  CHECK(cb_whole > 0);
  CHECK(modal_whole > 0);
  WARN("spin-up, C3D20 tube, smallest lambda_min / lambda_max of M over 25 s: Craig-Bampton "
       << cb_elastic << " (elastic block), " << cb_whole << " (with the hub); clamped modes " << modal_elastic
       << " (elastic block), " << modal_whole << " (with the hub)");
}

#endif  // KANEGEN_NO_C3D20_TUBES

TEST_CASE("Craig-Bampton bodies with stiffening keep M positive definite at verify's interface motions",
          "[flexible][mesh_stiffening]") {
  // docs/flexible-bodies.md, "The elastic mass to second order": with the
  // elastic block kept to first order, an interface's axial shape, which
  // moves points along u2, made M indefinite at verify's random states
  // (displacements of about 1e-3 of the body's length; the coordinates are
  // mass-normalised, so that is 1e-3 L sqrt(m)): the free strip (1 m,
  // 0.27 kg) hinged, the 10 m spin-up strip (12 kg) on its prescribed hub,
  // whose elastic block is what the integration inverts. Definiteness is
  // not by construction (the coupling rows keep first order): at ten times
  // those motions M is indefinite again, reported.
  const auto strip = smallest_random_mass_ratios<kanegen_models::free_strip_cps8::System>(1, 5e-4);
  const auto spin = smallest_random_mass_ratios<kanegen_models::spin_up_cps8_cb::System>(1, 0.035);
  CHECK(strip.first > 0);
  CHECK(spin.second > 0);
  const auto strip10 = smallest_random_mass_ratios<kanegen_models::free_strip_cps8::System>(1, 5e-3);
  const auto spin10 = smallest_random_mass_ratios<kanegen_models::spin_up_cps8_cb::System>(1, 0.35);
  WARN(
      "Craig-Bampton with stiffening, 200 random states, smallest lambda_min / lambda_max of M (of its "
      "elastic "
      "block): free CPS8 strip "
      << strip.first << " (" << strip.second << "), spin-up CPS8 strip " << spin.first << " (" << spin.second
      << "); at ten times the motions " << strip10.first << " (" << strip10.second << "), " << spin10.first
      << " (" << spin10.second << ")");
}
