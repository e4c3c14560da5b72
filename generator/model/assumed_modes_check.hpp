// SPDX-License-Identifier: GPL-2.0-or-later
// Load-time checks of a flexible beam's assumed modes (ElasticPart::
// assumed_modes), without GiNaC: every expression reads, is finite on the
// beam, and the shapes, sampled as the generator samples them (values and
// slopes at the nodes of the internal mesh), are strains rather than rigid
// motions and linearly independent. A set that passes gives a positive
// definite mass matrix in the amplitudes.
#pragma once

#include "model/model.hpp"

namespace kanegen::model {

/// The most assumed modes a beam may have.
inline constexpr int kMaxAssumedModes = 30;

/// Checks the assumed modes of `body` (flexible, with assumed modes) and
/// fills its beam's shape_parameters with the parameters' defaults. Errors
/// name model.source_file and the mode's place. Throws ModelError.
void check_assumed_modes(const Model& model, Body& body);

}  // namespace kanegen::model
