// SPDX-License-Identifier: GPL-2.0-or-later
// The shipped loop models in motion against conservation laws, exact
// solutions and an independent reference.
#include <catch2/catch.hpp>
#include <cmath>

#include "four_bar.hpp"
#include "loop_helpers.hpp"
#include "nfourbar2.hpp"
#include "slider_crank.hpp"
#include "slider_crank_free.hpp"

namespace {

using kanegen_test::LoopRun;
using kanegen_test::run_loops;

}  // namespace

TEST_CASE("a free four-bar conserves energy and keeps its loop closed", "[loops][four_bar]") {
  using System = kanegen_models::four_bar::System;
  const LoopRun run = run_loops<System>(10.0, 0.01, 1e-10);
  INFO(run.result.message);
  REQUIRE(run.result.ok());
  REQUIRE(run.times.back() == Approx(10.0));
  CHECK(run.worst_residual < 1e-10);
  // The model's own description gives T + V = 4.418258 J (an independent planar evaluator).
  CHECK(run.initial_energy == Approx(4.418258).epsilon(1e-6));
  CHECK(run.worst_energy_change / run.initial_energy < 1e-8);
  // The crank keeps going round (it has enough energy to pass the top).
  CHECK(std::abs(run.states.back()[0]) > 4 * M_PI);
}

TEST_CASE("assembly closes the four-bar from a rough guess and keeps the marked crank", "[loops][four_bar]") {
  using System = kanegen_models::four_bar::System;
  const LoopRun closed = run_loops<System>(0.0, 0.01, 1e-10);
  const LoopRun rough = run_loops<System>(0.0, 0.01, 1e-10, {}, [](double* x) {
    x[0] = 0.3;   // crank: kept
    x[1] += 0.2;  // coupler and rocker: guesses
    x[2] -= 0.15;
    x[4] = x[5] = 0.0;  // their speeds follow from the crank's
  });
  REQUIRE(rough.assembly.independent == std::vector<int>{0});
  CHECK_FALSE(rough.assembly.picked);
  CHECK(rough.assembly.iterations > 2);
  CHECK(rough.worst_residual < 1e-12);
  const std::vector<double>& x = rough.states.front();
  CHECK(x[0] == 0.3);
  CHECK(x[3] == 10.0);
  // The closed loop's speeds: C u = 0 through the rocker tip (checked from the kernels).
  double C[System::nc * System::nu];
  System::constraint_jacobian(System::Params{}, x.data(), C);
  for (int r = 0; r < System::nc; ++r) {
    double v = 0;
    for (int k = 0; k < System::nu; ++k) v += C[r * System::nu + k] * x[System::nq + k];
    CHECK(std::abs(v) < 1e-12);
  }
  CHECK(closed.assembly.iterations == 0);
}

TEST_CASE("the rigid slider-crank follows the exact slider motion", "[loops][slider_crank]") {
  using System = kanegen_models::slider_crank::System;
  const LoopRun run = run_loops<System>(0.1, 0.001, 1e-11);
  INFO(run.result.message);
  REQUIRE(run.result.ok());
  CHECK(run.worst_residual < 1e-10);
  const double l1 = 0.15, l2 = 0.30, omega = 150.0;
  double worst = 0;
  for (std::size_t k = 0; k < run.times.size(); ++k) {
    const double phi = omega * run.times[k];
    const double exact = l1 * std::cos(phi) + std::sqrt(l2 * l2 - l1 * l1 * std::sin(phi) * std::sin(phi));
    worst = std::max(worst, std::abs(run.states[k][2] - exact));
  }
  CHECK(worst < 1e-9);
}

TEST_CASE("the slider-crank's loop force at the dead centre is the slider's inertia",
          "[loops][slider_crank]") {
  using System = kanegen_models::slider_crank::System;
  System::Params p;
  double q[System::nq], u[System::nu], udot[System::nu], lambda[System::nc],
      tau[System::ntau > 0 ? System::ntau : 1] = {};
  System::initial_state(p, q, u);
  REQUIRE(System::constrained_dynamics(p, 0.0, q, u, tau, udot, lambda) == 0);
  // x3 = L1 cos(wt) + sqrt(L2^2 - L1^2 sin^2(wt)): x3'' = -L1 w^2 (1 + L1/L2) at t = 0.
  const double accel = -0.15 * 150.0 * 150.0 * (1.0 + 0.15 / 0.30);
  CHECK(udot[2] == Approx(accel).epsilon(1e-12));
  // The slider pushes the rod with -m3 x3'' along x, and not across.
  CHECK(lambda[0] == Approx(-p.m3 * accel).epsilon(1e-12));
  CHECK(std::abs(lambda[1]) < 1e-9);
}

TEST_CASE("the N four-bar passes its singular positions on the parallelogram branch", "[loops][nfourbar]") {
  using System = kanegen_models::nfourbar2::System;
  const LoopRun run = run_loops<System>(10.0, 0.5, 1e-9);
  INFO(run.result.message);
  REQUIRE(run.result.ok());
  // The exact 1-dof motion 3 theta'' = -34.335 cos(theta) from theta = pi/2,
  // theta' = -1 (models/nfourbar2.json), integrated independently by
  // classical RK4 with h = 1e-5 s and 2.5e-6 s (agreeing to 1e-11): the
  // cranks pass the ground line (all links in line) twelve times in 10 s.
  REQUIRE(run.times.size() == 21);
  for (int crank = 0; crank < 3; ++crank) {
    CHECK(run.states[2][crank] == Approx(-1.7670744763).margin(1e-7));
    CHECK(run.states[4][crank] == Approx(-4.7702370345).margin(1e-7));
  }
  // Each passage costs up to ~2e-5 of phase (the augmented Lagrangian
  // near the singular position, docs/closed-loops.md), twelve passages up
  // to ~2.4e-4: how much depends on where the steps land, so the kernels'
  // rounding moves it (at this rtol 2.1e-7, 1.2e-4 and 8.7e-5 with the
  // kernels of three commits; 2.2e-4 the most seen at any tolerance). The
  // issue's target of 1e-6 for B0 at 10 s is not met.
  const double theta = -30.17980086019;
  const std::vector<double>& end = run.states.back();
  for (int crank = 0; crank < 3; ++crank) CHECK(end[crank] == Approx(theta).margin(3e-4));
  // B0, the benchmark's output: the tip of the first crank, 1 m long, off
  // by no more than the phase.
  CHECK(std::abs(std::cos(end[0]) - std::cos(theta)) < 3e-4);
  CHECK(std::abs(std::sin(end[0]) - std::sin(theta)) < 3e-4);
  CHECK(run.worst_residual < 1e-10);
  CHECK(run.worst_energy_change < 1e-5 * run.initial_energy);
}

TEST_CASE("a free slider-crank conserves energy and keeps its loop closed", "[loops][slider_crank]") {
  using System = kanegen_models::slider_crank_free::System;
  const LoopRun run = run_loops<System>(1.0, 0.001, 1e-10);
  INFO(run.result.message);
  REQUIRE(run.result.ok());
  REQUIRE(run.assembly.independent == std::vector<int>{0});
  CHECK(run.states.front()[0] == 0.3);
  CHECK(run.worst_residual < 1e-10);
  CHECK(run.worst_energy_change / run.initial_energy < 1e-8);
  CHECK(std::abs(run.states.back()[0]) > 10.0);  // it keeps turning (no dead point stops it)
}
