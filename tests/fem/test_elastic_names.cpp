// SPDX-License-Identifier: GPL-2.0-or-later
// The model layer names a flexible body's elastic coordinates without the
// finite-element layer (to check a model file's initial values at load);
// the names must be the ones the reduced body gives them.
#include <catch2/catch.hpp>

#include "fem/elastic_model.hpp"
#include "model/elastic_coordinates.hpp"

namespace {

kanegen::model::Body beam_body(kanegen::model::BeamFormulation formulation,
                               kanegen::model::BeamSupport support, int modes) {
  kanegen::model::Body b;
  b.name = "beam";
  b.flexible = true;
  kanegen::model::ElasticPart& f = b.elastic;
  f.formulation = formulation;
  f.segments.push_back({{0.8, 0.0, 0.0}, 4, ""});
  f.A = 1e-4;
  f.Iy = f.Iz = 1e-9;
  f.J = 2e-9;
  f.E = 7e10;
  f.G = 2.6e10;
  f.density = 2700;
  f.support = support;
  f.modes = modes;
  return b;
}

}  // namespace

TEST_CASE("elastic coordinate names: the model layer's agree with the reduced body's", "[reduction][names]") {
  using kanegen::model::BeamFormulation;
  using kanegen::model::BeamSupport;
  const auto unused_sampler = [](const std::string&, const std::map<std::string, double>&,
                                 const std::vector<double>&, std::vector<double>&,
                                 std::vector<double>&) { FAIL("no assumed modes here"); };
  for (BeamFormulation formulation : {BeamFormulation::planar, BeamFormulation::spatial})
    for (BeamSupport support : {BeamSupport::clamped, BeamSupport::pinned_pinned})
      for (int modes : {0, 3}) {
        const kanegen::model::Body body = beam_body(formulation, support, modes);
        INFO("spatial " << (formulation == BeamFormulation::spatial) << ", pinned "
                        << (support == BeamSupport::pinned_pinned) << ", modes " << modes);
        const kanegen::fem::ElasticModel built = kanegen::fem::build_elastic_model(body, "", unused_sampler);
        CHECK(kanegen::model::elastic_coordinate_names(body.elastic) == built.reduced.names);
      }
  // Spot checks of the rule itself (docs/model-format.md).
  const auto planar_pinned = beam_body(BeamFormulation::planar, BeamSupport::pinned_pinned, 0);
  const std::vector<std::string> names = kanegen::model::elastic_coordinate_names(planar_pinned.elastic);
  REQUIRE(names.size() == 3 * 5 - 3);
  CHECK(names.front() == "n0.theta_z");
  CHECK(names[1] == "n1.u");
  CHECK(names.back() == "n4.theta_z");
  CHECK(names[names.size() - 2] == "n4.u");
}
