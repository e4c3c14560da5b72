// The loop types the shipped (planar) linkages do not use: a spherical joint,
// a spatial revolute and a spatial slider in spatial linkages, and a planar
// slider. Each is held to its geometric meaning, computed here from the joint
// angles alone, to conservation of energy, and the spherical and revolute
// cuts of one linkage to each other.
#include <catch2/catch.hpp>
#include <cmath>

#include "loop_helpers.hpp"
#include "quick_return.hpp"
#include "ring_slider.hpp"
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

}  // namespace

TEST_CASE("assembly of the RSUR linkage finds the independently solved configuration", "[loops][spatial]") {
  // The configuration at crank angle 0, solved independently: |P - Q| = c for
  // the rocker angle by bracketing root-finding (SciPy's brentq), then the
  // universal joint's angles from the direction P -> Q and the ball's z-y-x
  // angles from the rocker's rotation relative to the coupler (NumPy).
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
  INFO(a.result.message << " / " << b.result.message);
  REQUIRE(a.result.ok());
  REQUIRE(b.result.ok());
  REQUIRE(a.times.size() == b.times.size());
  for (const LoopRun* run : {&a, &b}) {
    CHECK(run->worst_residual < 1e-10);
    CHECK(run->worst_energy_change / std::abs(run->initial_energy) < 1e-8);
  }
  CHECK(a.initial_energy == Approx(b.initial_energy).epsilon(1e-10));
  const Spherical::Params p;
  double worst_angle = 0, worst_rocker = 0, worst_distance = 0;
  for (std::size_t k = 0; k < a.times.size(); ++k) {
    const std::vector<double>& x = a.states[k];
    const std::vector<double>& y = b.states[k];
    // Same crank, same coupler (the tree above the cut is the same).
    for (int i = 0; i < 3; ++i) worst_angle = std::max(worst_angle, std::abs(x[i] - y[i]));
    // The rocker's midpoint from the spherical cut's rocker angle, and from the revolute cut's outputs.
    double out[Revolute::ny];
    Revolute::outputs(Revolute::Params{}, a.times[k], y.data(), y.data() + Revolute::nq, out);
    const double th = x[3];
    const Vec mid_a{p.gx, p.gy + p.b / 2 * std::cos(th), p.gz + p.b / 2 * std::sin(th)};
    worst_rocker = std::max(worst_rocker, norm(mid_a - Vec{out[0], out[1], out[2]}));
    // The spherical joint's meaning: crank tip to rocker tip is the coupler's length.
    const Vec crank_tip{p.a * std::cos(x[0]), p.a * std::sin(x[0]), 0.0};
    const Vec rocker_tip{p.gx, p.gy + p.b * std::cos(th), p.gz + p.b * std::sin(th)};
    worst_distance = std::max(worst_distance, std::abs(norm(rocker_tip - crank_tip) - p.c));
  }
  CHECK(worst_angle < 1e-8);
  CHECK(worst_rocker < 1e-9);
  CHECK(worst_distance < 1e-10);
  CHECK(a.states.back()[0] > 2 * M_PI);  // the crank goes round
}

TEST_CASE("a rod through a ring keeps the ring on its axis and conserves energy", "[loops][spatial]") {
  using System = kanegen_models::ring_slider::System;
  const LoopRun run = run_loops<System>(1.0, 0.01, 1e-10);
  INFO(run.result.message);
  REQUIRE(run.result.ok());
  CHECK(run.worst_residual < 1e-10);
  CHECK(run.worst_energy_change / std::abs(run.initial_energy) < 1e-8);
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
}

TEST_CASE("the quick-return rocker follows the crank pin exactly and energy is conserved",
          "[loops][planar]") {
  using System = kanegen_models::quick_return::System;
  const LoopRun run = run_loops<System>(2.0, 0.01, 1e-10);
  INFO(run.result.message);
  REQUIRE(run.result.ok());
  CHECK(run.worst_residual < 1e-10);
  CHECK(run.worst_energy_change / std::abs(run.initial_energy) < 1e-8);
  const System::Params p;
  double worst = 0;
  for (const std::vector<double>& x : run.states) {
    const double exact = std::atan2(p.a * std::sin(x[0]) + p.d, p.a * std::cos(x[0]));
    worst = std::max(worst, std::abs(std::remainder(x[1] - exact, 2 * M_PI)));
  }
  CHECK(worst < 1e-10);
  CHECK(std::abs(run.states.back()[0]) > 2 * M_PI);
}
