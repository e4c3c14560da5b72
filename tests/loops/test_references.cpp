// SPDX-License-Identifier: GPL-2.0-or-later
// Closed-loop models against the published reference solutions of the IVP
// test set (Mazzia & Magherini, archimede.uniba.it/~testset): Andrews'
// squeezing mechanism at t = 0.03 s (andrews.f, PSIDE at tolerance 1e-14)
// and Simeon's flexible slider-crank at t = 0.1 s (crank.f).
#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>
#include <string>

#include "andrews_squeezer.hpp"
#include "loop_helpers.hpp"
#include "simeon_crank.hpp"
#include "simeon_crank_fe.hpp"

namespace {

using kanegen_test::LoopRun;
using kanegen_test::run_loops;

template <class System>
int coordinate(const char* name) {
  for (int i = 0; i < System::nq; ++i)
    if (std::strcmp(System::coordinate_names()[i], name) == 0) return i;
  FAIL("no coordinate " << name);
  return -1;
}

double relative(double value, double reference) { return std::abs(value - reference) / std::abs(reference); }

// crank.f's initial state: positions phi1, phi2 (absolute), x3, q1..q4 and
// their speeds (q3, q4: the axial field; q4 the tip's axial displacement).
constexpr double kCrankQ[7] = {
    0.0, 0.0, 4.500169330000000e-1, 0.0, 0.0, 1.033398630000000e-5, 1.693279690000000e-5};
constexpr double kCrankU[7] = {1.5e2,
                               -7.499576703969453e1,
                               -2.689386719979040e-6,
                               4.448961125815990e-1,
                               4.634339319238670e-3,
                               -1.785910760000550e-6,
                               -2.689386719979040e-6};
// crank.f's solut() at t = 0.1.
constexpr double kCrankRef[7] = {0.1500000000000104e2,  -0.3311734988256260,   0.1697373328427860,
                                 0.1893192899613509e-3, 0.2375751249879174e-4, -0.5323896770569702e-5,
                                 -0.8363313279112129e-5};

/// The model's initial state as simulate starts from it (before assembly).
/// crank.f gives x3 = 0.450016933 to nine digits, and its tip displacement
/// q4 to nine: its state closes the loop to 2e-10 m, and assembly closes
/// the rest. The state is checked here, not what assembly makes of it.
template <class System>
std::vector<double> initial_state() {
  const kanegen::runtime::Model model = kanegen::runtime::make_model<System>();
  std::vector<double> x(System::nq + System::nu);
  model.initial_state(x.data(), x.data() + System::nq);
  const double residual = kanegen::runtime::LoopSolver(model).residual(x.data());
  WARN(System::name << ": loop residual at the model's initial state " << residual);
  CHECK(residual < 3e-10);
  return x;
}

/// crank.f's elastic fields at xi = x/L from its amplitudes a = q1..q4 (or
/// their speeds): v = q1 sin(pi xi) + q2 sin(2 pi xi), theta_z = dv/dx,
/// u = q3 4 xi (1 - xi) + q4 xi (2 xi - 1); L = 0.3 m.
double crank_field(const double* a, const std::string& dof, double xi) {
  const double pi = M_PI, length = 0.3;
  if (dof == "v") return a[0] * std::sin(pi * xi) + a[1] * std::sin(2 * pi * xi);
  if (dof == "theta_z") return pi / length * (a[0] * std::cos(pi * xi) + 2 * a[1] * std::cos(2 * pi * xi));
  return a[2] * 4 * xi * (1 - xi) + a[3] * xi * (2 * xi - 1);
}

/// The joint part of crank.f's state in kanegen's coordinates: the crank
/// angle, the rod's angle relative to the crank, the slider; and the speeds.
void check_crank_joints(const double* q, const double* u) {
  CHECK(q[0] == kCrankQ[0]);
  CHECK(q[1] == Approx(kCrankQ[1] - kCrankQ[0]).margin(1e-15));
  CHECK(q[2] == Approx(kCrankQ[2]).epsilon(1e-15));
  CHECK(u[0] == Approx(kCrankU[0]).epsilon(1e-15));
  CHECK(u[1] == Approx(kCrankU[1] - kCrankU[0]).epsilon(1e-15));
  CHECK(u[2] == Approx(kCrankU[2]).epsilon(1e-15));
}

}  // namespace

TEST_CASE("Andrews' squeezer matches the IVP test set at t = 0.03 s", "[loops][andrews][reference]") {
  using System = kanegen_models::andrews_squeezer::System;
  const LoopRun run = run_loops<System>(0.03, 0.03, 1e-12);
  INFO(run.result.message);
  REQUIRE(run.result.ok());
  // andrews.f, SOLN: beta, Theta, gamma, Phi, delta, Omega, epsilon.
  const double reference[7] = {0.1581077119629904e2, -0.1575637105984298e2, 0.4082224013073101e-1,
                               -0.5347301163226948,  0.5244099658805304,    0.5347301163226948,
                               0.1048080741042263e1};
  const char* names[7] = {"beta", "Theta", "gamma", "Phi", "delta", "Omega", "epsilon"};
  const std::vector<double>& x = run.states.back();
  double worst = 0;
  for (int k = 0; k < 7; ++k) {
    const double error = relative(x[coordinate<System>(names[k])], reference[k]);
    INFO(names[k] << " = " << x[coordinate<System>(names[k])] << ", reference " << reference[k]);
    CHECK(error < 1e-7);
    worst = std::max(worst, error);
  }
  WARN("Andrews: largest relative error " << worst << ", loop residual " << run.worst_residual);
  CHECK(run.worst_residual < 1e-10);
}

TEST_CASE("Simeon's shipped models start in the IVP test set's initial state", "[loops][simeon][initial]") {
  {
    using System = kanegen_models::simeon_crank::System;
    const std::vector<double> x = initial_state<System>();
    check_crank_joints(x.data(), x.data() + System::nq);
    const int q1 = coordinate<System>("rod.mode1");  // the assumed modes are crank.f's q1..q4
    for (int k = 0; k < 4; ++k) {
      INFO("rod.mode" << k + 1);
      CHECK(x[q1 + k] == Approx(kCrankQ[3 + k]).epsilon(1e-15).margin(1e-300));
      CHECK(x[System::nq + q1 + k] == Approx(kCrankU[3 + k]).epsilon(1e-15));
    }
  }
  {
    using System = kanegen_models::simeon_crank_fe::System;
    const std::vector<double> x = initial_state<System>();
    check_crank_joints(x.data(), x.data() + System::nq);
    REQUIRE(System::nq == 27);
    for (int i = 3; i < System::nq; ++i) {
      const std::string name = System::coordinate_names()[i];  // rod.n<node>.<dof>
      const std::size_t dot = name.find('.', 4);
      const double xi = std::stoi(name.substr(5, dot - 5)) / 8.0;
      const std::string dof = name.substr(dot + 1);
      INFO(name);
      CHECK(x[i] == Approx(crank_field(kCrankQ + 3, dof, xi)).epsilon(1e-14).margin(1e-20));
      CHECK(x[System::nq + i] == Approx(crank_field(kCrankU + 3, dof, xi)).epsilon(1e-14).margin(1e-15));
    }
  }
}

TEST_CASE("Simeon's slider-crank with assumed modes matches the IVP test set at t = 0.1 s",
          "[loops][simeon][reference]") {
  using System = kanegen_models::simeon_crank::System;
  const int q1 = coordinate<System>("rod.mode1");
  const LoopRun run = run_loops<System>(0.1, 0.1, 1e-10);  // from the model's initial state
  INFO(run.result.message);
  REQUIRE(run.result.ok());
  CHECK(run.worst_residual < 1e-10);
  const std::vector<double>& x = run.states.back();
  const double phi1 = x[0], phi2 = x[0] + x[1], x3 = x[2];
  CHECK(relative(phi1, kCrankRef[0]) < 1e-12);
  CHECK(relative(phi2, kCrankRef[1]) < 1e-5);
  CHECK(relative(x3, kCrankRef[2]) < 1e-5);
  // Bending to 1e-3; the axial pair to a few per cent, as crank.f's axial
  // mass is 15 times the consistent one (docs/closed-loops.md).
  CHECK(relative(x[q1], kCrankRef[3]) < 1e-3);
  CHECK(relative(x[q1 + 1], kCrankRef[4]) < 1e-3);
  CHECK(relative(x[q1 + 2], kCrankRef[5]) < 3e-2);
  CHECK(relative(x[q1 + 3], kCrankRef[6]) < 3e-2);
  WARN("Simeon, assumed modes, relative errors: phi2 "
       << relative(phi2, kCrankRef[1]) << ", x3 " << relative(x3, kCrankRef[2]) << ", q1 "
       << relative(x[q1], kCrankRef[3]) << ", q2 " << relative(x[q1 + 1], kCrankRef[4]) << ", q3 "
       << relative(x[q1 + 2], kCrankRef[5]) << ", q4 " << relative(x[q1 + 3], kCrankRef[6]));
}

TEST_CASE("Simeon's slider-crank with a finite-element rod is close to the reference",
          "[loops][simeon][reference]") {
  using System = kanegen_models::simeon_crank_fe::System;
  const LoopRun run = run_loops<System>(0.1, 0.1, 1e-9);  // from the model's initial state
  INFO(run.result.message);
  REQUIRE(run.result.ok());
  CHECK(run.worst_residual < 1e-10);
  const std::vector<double>& x = run.states.back();
  const double phi2 = x[0] + x[1], x3 = x[2];
  // Midspan lateral deflection: q1 sin(pi/2) + q2 sin(pi) = q1 in Simeon's model.
  const double midspan = x[coordinate<System>("rod.n4.v")];
  WARN("Simeon, finite elements: phi2 " << phi2 << ", x3 " << x3 << ", midspan deflection " << midspan
                                        << " (reference q1 " << kCrankRef[3] << ")");
  CHECK(relative(phi2, kCrankRef[1]) < 1e-4);
  CHECK(relative(x3, kCrankRef[2]) < 1e-4);
  CHECK(relative(midspan, kCrankRef[3]) < 2e-2);
}
