// SPDX-License-Identifier: GPL-2.0-or-later
// Joints on the nodes of spatial beams (issue 12): the child frame turns with
// the node's three small rotations, made exact (Rx Ry Rz), so the model is
// conservative; and as the beams stiffen the arm becomes its rigid twin.
#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

#include "flexible_helpers.hpp"
#include "spatial_arm2.hpp"
#include "spatial_arm2_rigid.hpp"
#include "spatial_arm2_stiff.hpp"

namespace {

using kanegen_test::initial_state;

/// The payload's position every 10 ms over [0, t_end] (DOPRI5 at rtol 1e-11).
template <class System>
std::vector<std::vector<double>> payload_path(double t_end) {
  typename System::Params p;
  std::vector<double> x = initial_state<System>();
  const int k = kanegen_test::output_index<System>("payload.x");
  std::vector<std::vector<double>> path;
  kanegen::runtime::IntegrationOptions opt;
  opt.t_end = t_end;
  opt.dt = 0.01;
  opt.rtol = 1e-11;
  opt.atol = 1e-13;
  opt.max_steps = 20000000;
  opt.h0 = 1e-7;  // the stiff twin's modes near 1e5 rad/s: start below their stability limit
  const auto result = kanegen::runtime::integrate(
      kanegen::runtime::Method::kDopri5, kanegen_test::rhs<System>(p), 0.0, x.data(),
      static_cast<int>(x.size()), opt, [&](double t, const double* state) {
        double y[System::ny];
        System::outputs(p, t, state, state + System::nq, y);
        path.push_back({y[k], y[k + 1], y[k + 2]});
        return true;
      });
  INFO(result.message);
  REQUIRE(result.ok());
  return path;
}

}  // namespace

TEST_CASE("a spatial arm with links a million times stiffer follows its rigid twin to 1e-6",
          "[flexible][spatial][rigid-limit]") {
  const auto stiff = payload_path<kanegen_models::spatial_arm2_stiff::System>(0.5);
  const auto rigid = payload_path<kanegen_models::spatial_arm2_rigid::System>(0.5);
  REQUIRE(stiff.size() == rigid.size());
  double worst = 0, travel = 0;
  for (std::size_t i = 0; i < stiff.size(); ++i)
    for (int a = 0; a < 3; ++a) {
      worst = std::max(worst, std::abs(stiff[i][a] - rigid[i][a]));
      travel = std::max(travel, std::abs(rigid[i][a] - rigid[0][a]));
    }
  INFO("largest payload difference " << worst << " m; the payload travels " << travel << " m");
  CHECK(travel > 0.3);
  CHECK(worst < 1e-6);
  WARN("spatial arm, E x 1e6 against rigid links, 0.5 s: payload within " << worst << " m (travel " << travel
                                                                          << " m)");
}

TEST_CASE("the free spatial flexible arm conserves energy", "[flexible][spatial][energy]") {
  using System = kanegen_models::spatial_arm2::System;
  const kanegen_test::EnergyDrift d =
      kanegen_test::energy_drift<System>(initial_state<System>(), 2.0, 20000000);
  INFO(d.result.message);
  REQUIRE(d.result.ok());
  INFO("E0 = " << d.initial_energy << ", relative drift " << d.relative_drift);
  CHECK(d.relative_drift < 1e-7);
}
