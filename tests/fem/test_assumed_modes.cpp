// SPDX-License-Identifier: GPL-2.0-or-later
// Assumed modes in the finite-element layer: the shapes arrive sampled (a
// ShapeSampler, GiNaC's or dual numbers' outside this layer); the basis puts
// values and slopes on the right dofs and refuses what is not finite.
#include <catch2/catch.hpp>
#include <cmath>
#include <stdexcept>

#include "fem/assumed_modes.hpp"
#include "fem_test_support.hpp"
#include "model/model_error.hpp"

using namespace kanegen::fem;
using Catch::Matchers::Contains;

namespace {

/// v = x^2 / L, by hand; every other component is "0".
void parabola(const std::string& text, const std::map<std::string, double>& parameters,
              const std::vector<double>& x, std::vector<double>& value, std::vector<double>& slope) {
  const double length = parameters.at("L");
  value.assign(x.size(), 0.0);
  slope.assign(x.size(), 0.0);
  if (text == "0") return;
  for (std::size_t i = 0; i < x.size(); ++i) {
    value[i] = x[i] * x[i] / length;
    slope[i] = 2 * x[i] / length;
  }
}

kanegen::model::ElasticPart one_mode() {
  kanegen::model::ElasticPart beam;
  kanegen::model::AssumedMode mode;
  mode.v = "x^2/L";
  mode.where = "/bodies/0/flexible/assumed_modes/0";
  beam.assumed_modes.push_back(mode);
  return beam;
}

}  // namespace

TEST_CASE("assumed modes: sampled values and slopes fill the basis column", "[assumed]") {
  const Body body = make_beam_chain(fem_test::steel_beam(BeamKind::kPlanar), 2.0, 4);
  const Eigen::MatrixXd basis = assumed_mode_basis(body, one_mode(), "m.json", parabola);
  REQUIRE(basis.rows() == body.num_dofs());
  REQUIRE(basis.cols() == 1);
  for (int n = 0; n < body.num_nodes(); ++n) {
    const double x = body.node_position(n).x();
    CHECK(basis(body.dof(n, DofKind::kUx), 0) == 0.0);
    CHECK(basis(body.dof(n, DofKind::kUy), 0) == Approx(x * x / 2.0));
    CHECK(basis(body.dof(n, DofKind::kRz), 0) == Approx(x));  // theta_z = dv/dx
  }
}

TEST_CASE("assumed modes: a shape that cannot be read or is not finite is the model's error", "[assumed]") {
  const Body body = make_beam_chain(fem_test::steel_beam(BeamKind::kPlanar), 2.0, 4);
  const ShapeSampler unreadable = [](const std::string& text, const std::map<std::string, double>&,
                                     const std::vector<double>& x, std::vector<double>& value,
                                     std::vector<double>& slope) {
    if (text != "0") throw std::invalid_argument("no such function");
    value.assign(x.size(), 0.0);
    slope.assign(x.size(), 0.0);
  };
  CHECK_THROWS_WITH(
      assumed_mode_basis(body, one_mode(), "m.json", unreadable),
      Contains("/assumed_modes/0/v") && Contains("cannot read shape function 'x^2/L' (no such function)"));
  const ShapeSampler pole = [](const std::string& text, const std::map<std::string, double>& parameters,
                               const std::vector<double>& x, std::vector<double>& value,
                               std::vector<double>& slope) {
    parabola(text, parameters, x, value, slope);
    if (text != "0") slope[0] = NAN;
  };
  CHECK_THROWS_AS(assumed_mode_basis(body, one_mode(), "m.json", pole), kanegen::model::ModelError);
  CHECK_THROWS_WITH(assumed_mode_basis(body, one_mode(), "m.json", pole),
                    Contains("the slope dv/dx is not finite at x = 0"));
}
