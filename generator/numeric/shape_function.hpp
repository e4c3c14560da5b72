// SPDX-License-Identifier: GPL-2.0-or-later
// The numeric path's own reading of assumed-mode shape functions, without
// GiNaC: the text parsed by TimeFunction (in x) and evaluated over dual
// numbers, so the slopes are exact. It is the shape sampler
// numeric/instance.cpp hands to the finite-element layer for the basis.
#pragma once

#include <map>
#include <string>
#include <vector>

namespace kanegen::numeric {

/// Fills value[i] and slope[i] = d/dx of the shape `text` at x[i] (names: x,
/// pi and `parameters`). Throws std::invalid_argument on a text it cannot
/// read; a value at a pole is not finite.
void sample_shape(const std::string& text, const std::map<std::string, double>& parameters,
                  const std::vector<double>& x, std::vector<double>& value, std::vector<double>& slope);

}  // namespace kanegen::numeric
