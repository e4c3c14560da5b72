// Conservative models keep T + V: Dormand-Prince at rtol 1e-10 over 10 s.
// Drift is max |E(t) - E(0)| relative to |E(0)|, where the initial state is
// chosen so that |E(0)| is of the order of the kinetic energy (no accidental
// near-zero denominator).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

#include "arm7.hpp"
#include "double_pendulum.hpp"
#include "system_helpers.hpp"

namespace {

template <class System>
double energy_drift(const std::vector<double>& x0, double* initial_energy) {
  typename System::Params p;
  std::vector<double> x = x0;
  const double e0 = kanegen_test::energy<System>(p, x.data());
  double worst = 0.0;
  kanegen::runtime::IntegrationOptions opt;
  opt.t_end = 10.0;
  opt.dt = 0.01;
  opt.rtol = 1e-10;
  opt.atol = 1e-12;
  opt.max_steps = 2000000;
  const auto result = kanegen::runtime::integrate(
      kanegen::runtime::Method::kDopri5, kanegen_test::rhs<System>(p), 0.0, x.data(), static_cast<int>(x.size()),
      opt, [&](double, const double* state) {
        worst = std::max(worst, std::abs(kanegen_test::energy<System>(p, state) - e0));
        return true;
      });
  REQUIRE(result.ok());
  *initial_energy = e0;
  return worst / std::abs(e0);
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
  const double drift = energy_drift<System>({0.3, -0.8, 0.5, 1.2, -0.4, 0.9, 0.2, 1.0, -0.5, 0.8, 1.5, -1.0, 2.0, 0.7}, &e0);
  INFO("E0 = " << e0 << ", relative drift = " << drift);
  CHECK(std::abs(e0) > 1.0);
  CHECK(drift < 1e-8);
}
