// SPDX-License-Identifier: GPL-2.0-or-later
// Conservative models keep T + V: Dormand-Prince at rtol 1e-10 over 10 s.
// Drift is max |E(t) - E(0)| relative to |E(0)|, where the initial state is
// chosen so that |E(0)| is of the order of the kinetic energy (no accidental
// near-zero denominator).
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

#include "arm7.hpp"
#include "double_pendulum.hpp"
#include "system_helpers.hpp"

namespace {

template <class System>
double energy_drift(const std::vector<double>& x0, double* initial_energy) {
  const kanegen_test::EnergyDrift d = kanegen_test::energy_drift<System>(x0, 10.0, 2000000);
  REQUIRE(d.result.ok());
  *initial_energy = d.initial_energy;
  return d.relative_drift;
}

}  // namespace

TEST_CASE("double pendulum conserves energy", "[regression][energy]") {
  using System = kanegen_models::double_pendulum::System;
  double e0 = 0;
  const double drift = energy_drift<System>({1.2, -0.7, 0.5, 2.0}, &e0);
  INFO("E0 = " << e0 << ", relative drift = " << drift);
  CHECK(std::abs(e0) > 1.0);
  CHECK(drift < 1e-8);
}

TEST_CASE("7-DOF arm conserves energy", "[regression][energy]") {
  using System = kanegen_models::arm7::System;
  double e0 = 0;
  const double drift =
      energy_drift<System>({0.3, -0.8, 0.5, 1.2, -0.4, 0.9, 0.2, 1.0, -0.5, 0.8, 1.5, -1.0, 2.0, 0.7}, &e0);
  INFO("E0 = " << e0 << ", relative drift = " << drift);
  CHECK(std::abs(e0) > 1.0);
  CHECK(drift < 1e-8);
}
