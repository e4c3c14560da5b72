// SPDX-License-Identifier: GPL-2.0-or-later
// A free, undamped flexible model keeps T + V, with geometric stiffening
// (its default) or without: both forms of the stiffening are conservative,
// the nonlinear axial strain of nodal beams and the foreshortening of modal
// ones (docs/flexible-bodies.md). Issue 12's free flexible pendulum, released
// from rest and at 9 rad/s, in both forms, and the two-link arm with a heavy
// payload: T + V drifts by less than 1e-7 of the largest kinetic energy over
// 5 s, the deflection stays within what the energy allows, the two forms
// agree, and at low speed the stiffened pendulum follows the linear one.
#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

#include "flex_tip_body_linear.hpp"
#include "flexible_arm2.hpp"
#include "flexible_helpers.hpp"
#include "free_strip.hpp"
#include "free_strip_linear.hpp"
#include "free_strip_modal.hpp"

namespace {

template <class System>
double energy_drift(const std::vector<double>& x, double t_end, double* e0_out) {
  const kanegen_test::EnergyDrift d = kanegen_test::energy_drift<System>(x, t_end, 20000000);
  INFO(d.result.message);
  REQUIRE(d.result.ok());
  *e0_out = d.initial_energy;
  return d.relative_drift;
}

using kanegen_test::initial_state;

/// A free run from x0 (Dormand-Prince at rtol 1e-10): the drift of T + V
/// relative to the largest kinetic energy, and the largest |output| of `tip`
/// (a node displacement's y) with its series.
struct FreeRun {
  double drift = 0, largest_kinetic = 0, largest_tip = 0;
  std::vector<double> t, tip;
  bool ok = false;
};

template <class System>
FreeRun free_run(const typename System::Params& p, std::vector<double> x, double t_end, const char* tip) {
  const int k = kanegen_test::output_index<System>(tip);
  FreeRun run;
  const double e0 = kanegen_test::energy<System>(p, x.data());
  double worst = 0;
  kanegen::runtime::IntegrationOptions opt;
  opt.t_end = t_end;
  opt.dt = 0.01;
  opt.rtol = 1e-10;
  opt.atol = 1e-12;
  opt.max_steps = 20000000;
  const auto result = kanegen::runtime::integrate(
      kanegen::runtime::Method::kDopri5, kanegen_test::rhs<System>(p), 0.0, x.data(),
      static_cast<int>(x.size()), opt, [&](double t, const double* state) {
        worst = std::max(worst, std::abs(kanegen_test::energy<System>(p, state) - e0));
        run.largest_kinetic =
            std::max(run.largest_kinetic, System::kinetic_energy(p, state, state + System::nq));
        double y[System::ny];
        System::outputs(p, t, state, state + System::nq, y);
        run.t.push_back(t);
        run.tip.push_back(y[k]);
        run.largest_tip = std::max(run.largest_tip, std::abs(y[k]));
        return true;
      });
  INFO(result.message);
  run.ok = result.ok();
  run.drift = worst / run.largest_kinetic;
  return run;
}

/// The strip's largest tip deflection that its energy allows: with T >= 0
/// and the gravity potential at least that of the whole mass hanging a
/// length below the hinge, U <= E0 + g (m_beam L / 2 + m_tip L) (1 + 1 %
/// for the stretch), and a cantilever's tip moves by at most
/// sqrt(2 U L^3 / (3 E I)) for strain energy U (the static tip-load shape
/// stores the least).
double energy_bound(double e0) {
  const double g = 9.81, L = 1.0, m_beam = 2700 * 1e-4 * L, m_tip = 0.2, EI = 7e10 * 1.3333e-10;
  const double u = e0 + 1.01 * g * (m_beam * L / 2 + m_tip * L);
  return std::sqrt(2 * u * L * L * L / (3 * EI));
}

template <class System>
FreeRun released(double speed, double t_end = 5.0) {
  std::vector<double> x = initial_state<System>();
  x[System::nq] = speed;  // the hinge rate; the strip starts horizontal and straight
  return free_run<System>(typename System::Params{}, x, t_end, "tip.y");
}

}  // namespace

TEST_CASE("a free flexible pendulum without stiffening conserves energy", "[flexible][energy]") {
  using System = kanegen_models::flex_tip_body_linear::System;
  std::vector<double> x = initial_state<System>();
  x[0] = 0.3;                // hub angle: swinging in gravity
  x[System::nq] = 1.0;       // hub rate
  x[System::nq + 2] = 0.05;  // some bending velocity
  double e0 = 0;
  const double drift = energy_drift<System>(x, 5.0, &e0);
  INFO("E0 = " << e0 << ", relative drift " << drift);
  CHECK(drift < 1e-8);
}

TEST_CASE("the free two-link flexible arm conserves energy", "[flexible][energy]") {
  using System = kanegen_models::flexible_arm2::System;
  double e0 = 0;
  const double drift = energy_drift<System>(initial_state<System>(), 3.0, &e0);
  INFO("E0 = " << e0 << ", relative drift " << drift);
  CHECK(drift < 1e-8);
}

TEST_CASE("the free flexible pendulum with geometric stiffening conserves energy and stays bounded",
          "[flexible][energy][stiffening]") {
  for (const double speed : {0.0, 9.0}) {
    const FreeRun nodal = released<kanegen_models::free_strip::System>(speed);
    const FreeRun modal = released<kanegen_models::free_strip_modal::System>(speed);
    // Released at 9 rad/s, the linear strip has deflected over ten times as
    // far as the stiffened one within 1 s (0.23 m against 0.009 m), and its
    // large motion then costs DOPRI5 minutes for the remaining 4 s: it is
    // run for 1.2 s, which shows the contrast.
    const FreeRun linear = released<kanegen_models::free_strip_linear::System>(speed, speed > 0 ? 1.2 : 5.0);
    REQUIRE(nodal.ok);
    REQUIRE(modal.ok);
    REQUIRE(linear.ok);
    const double e0 = 0.5 * (2700 * 1e-4 / 3 + 0.2) * speed * speed;  // horizontal: V = 0
    INFO("released at " << speed << " rad/s: largest |tip deflection| nodal " << nodal.largest_tip
                        << " m, modal " << modal.largest_tip << " m, linear " << linear.largest_tip
                        << " m; energy bound " << energy_bound(e0) << " m; drift/T_max nodal " << nodal.drift
                        << ", modal " << modal.drift << ", linear " << linear.drift);
    CHECK(nodal.drift < 1e-7);
    CHECK(modal.drift < 1e-7);
    CHECK(linear.drift < 1e-7);
    CHECK(nodal.largest_tip < energy_bound(e0));
    CHECK(modal.largest_tip < energy_bound(e0));
    // The two forms of the stiffening, independent derivations, agree.
    CHECK(std::abs(nodal.largest_tip - modal.largest_tip) < 0.02 * modal.largest_tip);
    // At 9 rad/s the linear model loses its in-plane bending stiffness to
    // the spin (its first frequency near 10 rad/s on a clamped hub) and
    // deflects over ten times as far.
    if (speed > 0) CHECK(nodal.largest_tip < 0.1 * linear.largest_tip);
    WARN("free pendulum released at "
         << speed << " rad/s, 5 s: largest |tip deflection| " << nodal.largest_tip << " m (nodal), "
         << modal.largest_tip << " m (modal), " << linear.largest_tip << " m (linear"
         << (speed > 0 ? ", 1.2 s" : "") << "); T + V drift / T_max " << nodal.drift << ", " << modal.drift
         << ", " << linear.drift);
  }
}

TEST_CASE("at low speed the stiffened pendulum follows the linear one", "[flexible][energy][stiffening]") {
  // From rest, the first 0.12 s: the hinge stays below 1.7 rad/s and the
  // strip bends through its first vibration (about 60 rad/s on the free
  // hinge). Later the stiffening by the swing, by gravity's pull and by the
  // vibration's own second-order axial force shifts the phase, and the
  // nodal and modal stiffened models agree with each other, not with the
  // linear one (the test above).
  const FreeRun stiff = released<kanegen_models::free_strip::System>(0.0, 0.12);
  const FreeRun linear = released<kanegen_models::free_strip_linear::System>(0.0, 0.12);
  REQUIRE(stiff.tip.size() == linear.tip.size());
  double difference = 0;
  for (std::size_t i = 0; i < stiff.tip.size(); ++i)
    difference = std::max(difference, std::abs(stiff.tip[i] - linear.tip[i]));
  INFO("largest difference " << difference << " m against a largest deflection " << linear.largest_tip
                             << " m");
  CHECK(difference < 0.03 * linear.largest_tip);
}

TEST_CASE("the two-link arm with a heavy payload and stiffening conserves energy",
          "[flexible][energy][stiffening]") {
  using System = kanegen_models::flexible_arm2::System;
  System::Params p;
  p.m_payload = 2.0;  // ten times the shipped payload
  const FreeRun run = free_run<System>(p, initial_state<System>(), 5.0, "tip2.y");
  REQUIRE(run.ok);
  INFO("drift / T_max " << run.drift << ", largest |tip2.y| " << run.largest_tip << " m");
  CHECK(run.drift < 1e-7);
  WARN("two-link arm, 2 kg payload, 5 s: T + V drift / T_max " << run.drift << ", largest |tip2.y| "
                                                               << run.largest_tip << " m");
}
