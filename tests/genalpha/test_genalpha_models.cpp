// SPDX-License-Identifier: GPL-2.0-or-later
// Generalized-alpha on generated models: the slider-crank (two loop
// equations, the crank prescribed) against its exact kinematics, the
// spin-up beam (31 coordinates, stiff axial modes, the hub prescribed) at a
// 1 ms step against DOPRI5, and the N four-bar (N = 2) through the singular
// positions where its loop equations lose rank.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <string>
#include <vector>

#include "kanegen/runtime/genalpha.hpp"
#include "kanegen/runtime/integrators.hpp"
#include "kanegen/runtime/loops.hpp"
#include "nfourbar2.hpp"
#include "slider_crank.hpp"
#include "spin_up_beam.hpp"

using namespace kanegen::runtime;

TEST_CASE("genalpha: the slider-crank's loops hold and its slider follows the exact kinematics",
          "[genalpha][loops]") {
  // The crank turns at omega = 150 rad/s (prescribed); the mechanism has no
  // degree of freedom left, so x3 = L1 cos(phi) + sqrt(L2^2 - L1^2 sin^2 phi)
  // exactly, whatever the step: the index-3 positions are exact up to the
  // loop tolerance, the speeds up to the speed correction's round-off.
  Model model = make_model<kanegen_models::slider_crank::System>();
  const kanegen_models::slider_crank::Params p;
  double q0[3], u0[3], phi[2];
  model.initial_state(q0, u0);
  for (double h : {1e-4, 1e-3}) {  // omega h = 0.015 and 0.15
    GenAlphaOptions o;
    o.h = h;
    GenAlpha ga(model, o);
    REQUIRE(ga.prescribed(0));
    std::string why;
    REQUIRE(ga.start(0.0, q0, u0, nullptr, &why));
    double worst_phi = 0.0, worst_x = 0.0, worst_xdot = 0.0;
    const long steps = std::lround(0.1 / h);
    for (long i = 0; i < steps; ++i) {
      INFO(why);
      REQUIRE(ga.step(nullptr, &why));
      model.constraints(ga.q(), phi);
      worst_phi = std::max({worst_phi, std::abs(phi[0]), std::abs(phi[1])});
      const double a = p.omega * ga.t(), s = std::sin(a), c = std::cos(a);
      const double root = std::sqrt(p.L2 * p.L2 - p.L1 * p.L1 * s * s);
      const double x = p.L1 * c + root, xdot = -p.L1 * s * p.omega - p.L1 * p.L1 * s * c * p.omega / root;
      worst_x = std::max(worst_x, std::abs(ga.q()[2] - x));
      worst_xdot = std::max(worst_xdot, std::abs(ga.u()[2] - xdot));
    }
    INFO("h = " << h << ": max |Phi| " << worst_phi << ", slider error " << worst_x << " m, speed error "
                << worst_xdot << " m/s; " << ga.stats().newton_iterations << " Newton iterations in " << steps
                << " steps");
    CHECK(worst_phi < 1e-10);
    CHECK(worst_x < 1e-10);
    CHECK(worst_xdot < 1e-8);  // |x'| up to 26 m/s
  }
}

namespace {

/// Minimum of tip.y (output 1) over [0, t_end] and its time.
struct TipMinimum {
  double value = 0.0, time = 0.0;
  void track(const Model& model, double t, const double* q, const double* u) {
    double y[4];
    model.outputs(t, q, u, y);
    if (y[1] < value) {
      value = y[1];
      time = t;
    }
  }
};

TipMinimum spin_up_dopri(const Model& model, double t_end) {
  const int n = model.info().nu;
  std::vector<double> x(2 * static_cast<size_t>(n));
  model.initial_state(x.data(), x.data() + n);
  IntegrationOptions opt;
  opt.t_end = t_end;
  opt.dt = 1e-3;
  opt.rtol = 1e-9;
  opt.atol = 1e-11;
  opt.max_steps = 20000000;
  const double tau = 0.0;
  TipMinimum m;
  const auto result = integrate(
      Method::kDopri5,
      [&](double t, const double* s, double* sd) {
        std::copy(s + n, s + 2 * n, sd);
        return model.forward_dynamics(t, s, s + n, &tau, sd + n) == 0;
      },
      0.0, x.data(), 2 * n, opt,
      [&](double t, const double* s) {
        m.track(model, t, s, s + n);
        return true;
      });
  REQUIRE(result.ok());
  return m;
}

}  // namespace

TEST_CASE("genalpha: the spin-up beam at a 1 ms step against DOPRI5", "[genalpha][flexible]") {
  // Ws = 6 rad/s; the tip's minimum (about -0.575 m at 6.77 s) is reached
  // before t = 9 s. The axial modes (about 8e3 rad/s, omega h = 8) are not
  // resolved and rho_inf = 0.8 damps them; the bending motion that makes the
  // minimum is (a few rad/s, omega h < 0.01), with a second-order error
  // measured at 1.4e-7 of the minimum at 1 ms (5.7e-7 at 2 ms, 4e-8 at 0.5 ms;
  // bench/genalpha.sh). 1e-5 leaves room for DOPRI5's own error at rtol 1e-9
  // and is still a thousand times inside the 1 %.
  Model model = make_model<kanegen_models::spin_up_beam::System>();
  const double t_end = 9.0;
  const TipMinimum reference = spin_up_dopri(model, t_end);
  const int n = model.info().nu;
  std::vector<double> q(n), u(n);
  model.initial_state(q.data(), u.data());
  GenAlphaOptions o;
  o.h = 1e-3;
  GenAlpha ga(model, o);
  CHECK(ga.prescribed(0));  // the hub, found without coordinate_roles
  for (int i = 1; i < n; ++i) CHECK_FALSE(ga.prescribed(i));
  const double tau = 0.0;
  std::string why;
  REQUIRE(ga.start(0.0, q.data(), u.data(), &tau, &why));
  TipMinimum m;
  bool ok = true;
  for (long i = 0; i < std::lround(t_end / o.h) && ok; ++i) {
    ok = ga.step(&tau, &why);
    m.track(model, ga.t(), ga.q(), ga.u());
  }
  INFO(why);
  REQUIRE(ok);
  const ImplicitStats& s = ga.stats();
  INFO("tip minimum " << m.value << " m at " << m.time << " s; DOPRI5 " << reference.value << " m at "
                      << reference.time << " s; " << s.steps << " steps, " << s.newton_iterations
                      << " Newton, " << s.jacobian_evaluations << " Jacobians, " << s.factorizations
                      << " LU");
  CHECK(std::abs(m.value - reference.value) < 1e-5 * std::abs(reference.value));
  CHECK(std::abs(m.time - reference.time) <= 2e-3);  // two samples of the 1 ms grids
  // Simplified Newton at this step: about one iteration a step, few Jacobians.
  CHECK(s.newton_iterations < 2 * s.steps);
  CHECK(s.jacobian_evaluations < s.steps / 100);
}

TEST_CASE("genalpha: the N four-bar passes its singular positions on the parallelogram branch",
          "[genalpha][loops]") {
  // All links collinear twice per turn: C loses rank 2 there, and the
  // explicit path stops at the third such position (t = 2.66 s). The
  // physical motion is the parallelogram's, 3 theta'' = -34.335 cos(theta)
  // (the model's description), from theta = pi/2 at -1 rad/s. At h = 0.5 ms
  // the steps never land on a singular position exactly, and the index-3
  // Newton iteration follows the branch. The crank's error after 10 s is
  // second order down to h = 2 ms (8.5e-6), below that each passage adds
  // phase that depends on where the steps land, so the kernels' rounding
  // moves it: at h = 1, 0.5 and 0.25 ms -1.8e-6, -1.7e-7 and 2.0e-7 with the
  // kernels of 5bbed2d, -2.0e-6, 3.4e-6 and -3.2e-6 with bc2b592's (sums
  // ordered by readiness; docs/closed-loops.md). Energy 2e-8 off its start.
  // Observed behaviour, not a guarantee: a step landing on the singular
  // position itself has a singular iteration matrix.
  Model model = make_model<kanegen_models::nfourbar2::System>();
  const int n = model.info().nu;
  std::vector<double> q(n), u(n), tau(static_cast<size_t>(model.info().ntau), 0.0);
  model.initial_state(q.data(), u.data());
  LoopSolver(model).assemble(q.data(), u.data());
  double reference[2] = {std::acos(-1.0) / 2.0, -1.0};
  IntegrationOptions opt;
  opt.t_end = 10.0;
  opt.dt = 10.0;
  opt.rtol = 1e-13;
  opt.atol = 1e-15;
  const auto parallelogram = [](double, const double* s, double* sd) {
    sd[0] = s[1];
    sd[1] = -34.335 / 3.0 * std::cos(s[0]);
    return true;
  };
  REQUIRE(integrate(Method::kDopri5, parallelogram, 0.0, reference, 2, opt, nullptr).ok());

  GenAlphaOptions o;
  o.h = 5e-4;
  GenAlpha ga(model, o);
  std::string why;
  REQUIRE(ga.start(0.0, q.data(), u.data(), tau.data(), &why));
  const double e0 = model.kinetic_energy(ga.q(), ga.u()) + model.potential_energy(ga.q());
  double worst_phi = 0.0, worst_drift = 0.0, phi[4];
  bool ok = true;
  for (long i = 0; i < 20000 && ok; ++i) {
    ok = ga.step(tau.data(), &why);
    model.constraints(ga.q(), phi);
    for (double p : phi) worst_phi = std::max(worst_phi, std::abs(p));
    const double e = model.kinetic_energy(ga.q(), ga.u()) + model.potential_energy(ga.q());
    worst_drift = std::max(worst_drift, std::abs(e - e0) / std::abs(e0));
  }
  INFO(why);
  REQUIRE(ok);
  INFO("crank0 " << ga.q()[0] << " rad at t = " << ga.t() << ", parallelogram " << reference[0]
                 << "; max |Phi| " << worst_phi << ", energy drift " << worst_drift);
  CHECK(ga.t() == Approx(10.0));
  CHECK(std::abs(ga.q()[0] - reference[0]) < 1e-5);  // B0 = (cos, sin) of it: within 1e-5 too
  CHECK(std::abs(ga.q()[1] - ga.q()[0]) < 1e-9);     // the cranks stay parallel
  CHECK(std::abs(ga.q()[2] - ga.q()[0]) < 1e-9);
  CHECK(worst_phi < 1e-10);
  // The energy error over a turn (measured 1.0e-6 at most, 2e-8 at the end)
  // is the method's O(h^2) oscillation, not a drift.
  CHECK(worst_drift < 3e-6);
}
