// SPDX-License-Identifier: GPL-2.0-or-later
// The outputs at a node of a flexible body: its elastic displacement in the
// link frame, and the section resultants of the adjoining element (axial
// force, bending moments) with the peak bending stress, all linear maps of
// the elastic coordinates (cubic beams: constant axial force, linear moment
// along an element).
#pragma once

#include <ginac/ginac.h>

#include <string>
#include <vector>

#include "fem/elastic_model.hpp"
#include "model/model.hpp"
#include "symbolic/program.hpp"

namespace kanegen::kane {

struct NodeOutputs {
  std::vector<GiNaC::ex> values;
  std::vector<std::string> names;
};

/// The node's displacement includes the beam's foreshortening.
NodeOutputs node_outputs(const model::Body& body, const fem::ElasticModel& beam, const model::Output& output,
                         const std::vector<GiNaC::ex>& eta, symbolic::Program& program);

}  // namespace kanegen::kane
