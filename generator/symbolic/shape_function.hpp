// SPDX-License-Identifier: GPL-2.0-or-later
// The generator's reading of assumed-mode shape functions (model
// ElasticPart::assumed_modes): GiNaC parses the text and differentiates it
// exactly. It is the fem::ShapeSampler the pipeline hands to
// fem::build_elastic_model; the finite-element layer itself has no GiNaC.
#pragma once

#include <map>
#include <string>
#include <vector>

namespace kanegen::symbolic {

/// Fills value[i] and slope[i] = d/dx of the shape `text` at x[i] (names: x,
/// pi and `parameters`). Throws std::exception if GiNaC cannot read the text;
/// a value at a pole is NaN.
void sample_shape(const std::string& text, const std::map<std::string, double>& parameters,
                  const std::vector<double>& x, std::vector<double>& value, std::vector<double>& slope);

}  // namespace kanegen::symbolic
