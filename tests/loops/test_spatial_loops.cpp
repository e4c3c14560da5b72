// SPDX-License-Identifier: GPL-2.0-or-later
// The loop types the shipped (planar) linkages do not use: a spherical joint,
// a spatial revolute and a spatial slider in spatial linkages, and a planar
// slider. Each is held to its geometric meaning, computed here from the joint
// angles alone, to conservation of energy, and the spherical and revolute
// cuts of one linkage to each other.
#include <catch2/catch.hpp>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "loop_helpers.hpp"
#include "quick_return.hpp"
#include "ring_slider.hpp"
#include "ring_slider_flexible.hpp"
#include "rsur_revolute.hpp"
#include "rsur_spherical.hpp"

namespace {

using kanegen_test::LoopRun;
using kanegen_test::run_loops;

struct Vec {
  double x, y, z;
};
Vec operator-(Vec a, Vec b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
double norm(Vec a) { return std::sqrt(a.x * a.x + a.y * a.y + a.z * a.z); }
Vec cross(Vec a, Vec b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }

/// The run reached its end with the loops closed and the energy kept (no
/// damping, no drive in these models; V may be negative, so relative to |E|).
void check_closed_and_conservative(const LoopRun& run) {
  INFO(run.result.message);
  REQUIRE(run.result.ok());
  CHECK(run.worst_residual < 1e-10);
  CHECK(run.worst_energy_change / std::abs(run.initial_energy) < 1e-8);
}

}  // namespace

TEST_CASE("assembly of the RSUR linkage finds the independently solved configuration", "[loops][spatial]") {
  // The configuration at crank angle 0, solved independently (SciPy's brentq,
  // NumPy): the rocker angle th from |Q(th) - P| = c with the crank tip
  // P = (a, 0, 0) and the rocker tip Q = G + Rx(th) (0, b, 0), on the branch
  // near -1.37; the universal joint's yaw = atan2(d_y, d_x) and
  // pitch = -asin(d_z) of d = (Q - P)/c; the ball's z-y-x angles from
  // Rz(s1) Ry(s2) Rx(s3) = (Rz(yaw) Ry(pitch))^T Rx(th): s2 = -asin(R_20),
  // s1 = atan2(R_10, R_00), s3 = atan2(R_21, R_22).
  const LoopRun spherical = run_loops<kanegen_models::rsur_spherical::System>(0.0, 0.01, 1e-10);
  const LoopRun revolute = run_loops<kanegen_models::rsur_revolute::System>(0.0, 0.01, 1e-10);
  REQUIRE(spherical.assembly.independent == std::vector<int>{0});
  REQUIRE(revolute.assembly.independent == std::vector<int>{0});
  const std::vector<double>& s = spherical.states.front();
  const std::vector<double>& r = revolute.states.front();
  for (const auto* x : {&s, &r}) {
    CHECK((*x)[0] == 0.0);
    CHECK((*x)[1] == Approx(1.3937266816277547).margin(1e-10));  // coupler yaw
    CHECK((*x)[2] == Approx(0.329556758319106).margin(1e-10));   // coupler pitch
  }
  CHECK(s[3] == Approx(-1.3734007669450181).margin(1e-10));  // rocker angle
  CHECK(r[3] == Approx(-1.4030729316977457).margin(1e-10));  // ball z, y, x
  CHECK(r[4] == Approx(-0.057035868512889616).margin(1e-10));
  CHECK(r[5] == Approx(-1.048639668850257).margin(1e-10));
}

TEST_CASE("the RSUR linkage cut at its spherical joint and at its hinge moves alike", "[loops][spatial]") {
  using Spherical = kanegen_models::rsur_spherical::System;
  using Revolute = kanegen_models::rsur_revolute::System;
  const LoopRun a = run_loops<Spherical>(1.0, 0.05, 1e-11);
  const LoopRun b = run_loops<Revolute>(1.0, 0.05, 1e-11);
  check_closed_and_conservative(a);
  check_closed_and_conservative(b);
  REQUIRE(a.times == b.times);
  // The two files must describe the same linkage.
  const Spherical::Params p;
  const Revolute::Params p2;
  for (const auto& [x, y] : {std::pair{p.a, p2.a},
                             {p.b, p2.b},
                             {p.c, p2.c},
                             {p.gx, p2.gx},
                             {p.gy, p2.gy},
                             {p.gz, p2.gz},
                             {p.m1, p2.m1},
                             {p.m2, p2.m2},
                             {p.m3, p2.m3}})
    REQUIRE(x == y);
  CHECK(a.initial_energy == Approx(b.initial_energy).epsilon(1e-10));
  double worst_angle = 0, worst_rocker = 0, worst_joint = 0;
  for (std::size_t k = 0; k < a.times.size(); ++k) {
    const std::vector<double>& x = a.states[k];
    const std::vector<double>& y = b.states[k];
    // Same crank, same coupler (the tree above the cut is the same).
    for (int i = 0; i < 3; ++i) worst_angle = std::max(worst_angle, std::abs(x[i] - y[i]));
    // The rocker's midpoint from the spherical cut's rocker angle, and from the revolute cut's outputs.
    double out[Revolute::ny];
    Revolute::outputs(p2, b.times[k], y.data(), y.data() + Revolute::nq, out);
    const double th = x[3];
    const Vec mid_a{p.gx, p.gy + p.b / 2 * std::cos(th), p.gz + p.b / 2 * std::sin(th)};
    worst_rocker = std::max(worst_rocker, norm(mid_a - Vec{out[0], out[1], out[2]}));
    // The spherical joint's meaning: the coupler's end, from the crank, yaw
    // (about z) and pitch (about the cross's y) angles, is the rocker's tip.
    const double yaw = x[0] + x[1], pitch = x[2];
    const Vec coupler_end{p.a * std::cos(x[0]) + p.c * std::cos(yaw) * std::cos(pitch),
                          p.a * std::sin(x[0]) + p.c * std::sin(yaw) * std::cos(pitch),
                          -p.c * std::sin(pitch)};
    const Vec rocker_tip{p.gx, p.gy + p.b * std::cos(th), p.gz + p.b * std::sin(th)};
    worst_joint = std::max(worst_joint, norm(rocker_tip - coupler_end));
  }
  CHECK(worst_angle < 1e-8);
  CHECK(worst_rocker < 1e-9);
  CHECK(worst_joint < 1e-10);
  CHECK(a.states.back()[0] > 2 * M_PI);  // the crank goes round
}

TEST_CASE("a rod through a ring keeps the ring on its axis and conserves energy", "[loops][spatial]") {
  using System = kanegen_models::ring_slider::System;
  const LoopRun run = run_loops<System>(1.0, 0.01, 1e-10);
  check_closed_and_conservative(run);
  const System::Params p;
  double worst = 0;
  for (const std::vector<double>& x : run.states) {
    // The rod's axis from the crank, yaw (about z) and pitch (about the cross's y) angles.
    const double yaw = x[0] + x[1], pitch = x[2];
    const Vec axis{std::cos(yaw) * std::cos(pitch), std::sin(yaw) * std::cos(pitch), -std::sin(pitch)};
    const Vec crank_tip{p.a * std::cos(x[0]), p.a * std::sin(x[0]), 0.0};
    worst = std::max(worst, norm(cross(Vec{p.rx, p.ry, p.rz} - crank_tip, axis)));
  }
  CHECK(worst < 1e-10);
  CHECK(std::abs(run.states.back()[0]) > 2 * M_PI);  // the crank goes round
}

TEST_CASE("the quick-return rocker follows the crank pin exactly and energy is conserved",
          "[loops][planar]") {
  using System = kanegen_models::quick_return::System;
  const LoopRun run = run_loops<System>(2.0, 0.01, 1e-10);
  check_closed_and_conservative(run);
  const System::Params p;
  double worst = 0;
  for (const std::vector<double>& x : run.states) {
    const double exact = std::atan2(p.a * std::sin(x[0]) + p.d, p.a * std::cos(x[0]));
    worst = std::max(worst, std::abs(std::remainder(x[1] - exact, 2 * M_PI)));
  }
  CHECK(worst < 1e-10);
  CHECK(std::abs(run.states.back()[0]) > 2 * M_PI);
}

TEST_CASE("a slider loop's line on a beam node turns with the node's rotation", "[loops][spatial][node]") {
  // ring_slider_flexible: at all-zero coordinates the rod runs along world x
  // from the crank tip (a, 0, 0); its line passes through node 2 at x = a +
  // 0.3 and the ring sits at (0.3, 0.1, 0.1). The rows are e1 . gap, e2 . gap
  // with e1 = y, e2 = z of the line's frame, gap = node - ring =
  // (a, -0.1, -0.1). Turning the node by delta about z turns e1 to
  // (-sin delta, cos delta, 0): row 1 changes by -a delta, row 2 not; a twist
  // about the line's own axis (x) turns e1, e2 about it, which leaves the
  // ring's distance from the line, |phi|, as it was.
  using System = kanegen_models::ring_slider_flexible::System;
  const System::Params p;
  const double a = p.a, delta = 1e-6;
  const auto index = [](const char* name) {
    for (int i = 0; i < System::nq; ++i)
      if (std::string(System::coordinate_names()[i]) == name) return i;
    FAIL("no coordinate " << name);
    return -1;
  };
  std::vector<double> q(System::nq, 0.0);
  double phi0[System::nc], phi[System::nc];
  System::constraints(p, q.data(), phi0);
  CHECK(phi0[0] == Approx(-0.1).epsilon(1e-12));
  CHECK(phi0[1] == Approx(-0.1).epsilon(1e-12));
  q[index("rod.n2.theta_z")] = delta;
  System::constraints(p, q.data(), phi);
  CHECK((phi[0] - phi0[0]) / delta == Approx(-a).epsilon(1e-4));
  CHECK(std::abs(phi[1] - phi0[1]) < 1e-15);
  q[index("rod.n2.theta_z")] = 0.0;
  q[index("rod.n2.theta_x")] = delta;
  System::constraints(p, q.data(), phi);
  CHECK(std::hypot(phi[0], phi[1]) == Approx(std::hypot(phi0[0], phi0[1])).epsilon(1e-13));
  CHECK((phi[1] - phi0[1]) / delta == Approx(0.1).epsilon(1e-4));  // the rows turn by delta
}
