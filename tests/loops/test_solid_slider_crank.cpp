// SPDX-License-Identifier: GPL-2.0-or-later
// models/solid_slider_crank.json (issue 18): Simeon's slider-crank with a
// connecting rod of solid hexahedra, Craig-Bampton reduced, in the loop
// through its small-end bore's node set. The slider must be where the rigid
// slider-crank's exact motion puts it for the rod's deformed pin distance,
// and the rod, which is stiff, must stretch by what its axial load
// explains.
#include <catch2/catch.hpp>
#include <cmath>
#include <string>

#include "loop_helpers.hpp"
#include "solid_slider_crank.hpp"

namespace {

using System = kanegen_models::solid_slider_crank::System;

int output(const std::string& name) {
  for (int i = 0; i < System::ny; ++i)
    if (name == System::output_names()[i]) return i;
  FAIL("no output " << name);
  return -1;
}

/// The slider of a rigid slider-crank with crank l1 at angle phi and rod l2.
double rigid_slider(double l1, double l2, double phi) {
  return l1 * std::cos(phi) + std::sqrt(l2 * l2 - l1 * l1 * std::sin(phi) * std::sin(phi));
}

}  // namespace

TEST_CASE("the solid slider-crank's slider is the rigid mechanism's for the rod's deformed pin distance",
          "[loops][solid_slider_crank]") {
  const kanegen_test::LoopRun run = kanegen_test::run_loops<System>(0.1, 0.001, 1e-9);
  INFO(run.result.message);
  REQUIRE(run.result.ok());
  REQUIRE(run.times.back() == Approx(0.1));
  CHECK(run.assembly.iterations == 0);  // it starts closed: the rigid state, the rod undeformed
  CHECK(run.worst_residual < 1e-10);
  const int ux = output("small_end.x"), uy = output("small_end.y");
  const double l1 = 0.15, l2 = 0.30, omega = 150.0;
  double to_rigid = 0, to_deformed = 0, stretch = 0, turn = 0;
  System::Params p;
  double y[System::ny];
  for (std::size_t k = 0; k < run.times.size(); ++k) {
    const double t = run.times[k], phi = omega * t;
    const std::vector<double>& x = run.states[k];
    CHECK(x[0] == Approx(phi).margin(1e-12));  // the crank is prescribed
    System::outputs(p, t, x.data(), x.data() + System::nq, y);
    // The small-end bore's mean displacement in the rod frame (clamped at the big-end bore).
    const double pins = std::hypot(l2 + y[ux], y[uy]);
    to_rigid = std::max(to_rigid, std::abs(x[2] - rigid_slider(l1, l2, phi)));
    to_deformed = std::max(to_deformed, std::abs(x[2] - rigid_slider(l1, pins, phi)));
    stretch = std::max(stretch, std::abs(y[ux]));
    turn = std::max(turn, std::abs(y[uy]) / l2);
  }
  WARN("solid slider-crank over 0.1 s: slider within "
       << to_rigid << " m of the rigid rod's motion, " << to_deformed << " m of the deformed rod's; "
       << "small-end stretch " << stretch << " m, chord turned by " << turn << " rad");
  // The loop closes at the set's averaged motion: exactly the rigid kinematics of the deformed rod.
  CHECK(to_deformed < 1e-9);
  // The rod carries about the slider's inertia force m3 L1 omega^2 (1 + L1/L2) = 383 N at the dead
  // centres (plus its own), along it: the shank alone stretches by F L / (E A) = 9e-6 m; the eyes and
  // the axial vibration the start excites (undamped) add to it. Ten times stiffer or softer shows.
  CHECK(stretch > 9e-6);
  CHECK(stretch < 9e-5);
  // The rod bends as Simeon's beam rod does (simeon_crank_fe: the slope at the crank pin reaches 0.018
  // rad), so the chord turns against the big-end frame by up to 0.025 rad; the linear elastic field does
  // not shorten the small end with it, which adds turn^2 L / 2, 1e-4 m, to the pin distance.
  CHECK(turn > 0.01);
  CHECK(turn < 0.04);
  CHECK(to_rigid < 1.5e-4);
}
