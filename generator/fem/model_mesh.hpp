// SPDX-License-Identifier: GPL-2.0-or-later
// A mesh body of the model (model::MeshSource) as the finite-element layer's
// reduced body: the .inp mesh read and assembled (fem/mesh_body.hpp), held
// on its clamped node set or free, and reduced to its first modes, so that
// the generator takes it as it takes a beam in modes.
#pragma once

#include <string>

#include "fem/elastic_model.hpp"
#include "fem/inp_mesh.hpp"
#include "fem/mesh_body.hpp"
#include "model/model.hpp"

namespace kanegen::fem {

/// The mesh of the body, read from its file; a missing file is a ModelError
/// naming the model file and the place of "mesh/file".
InpMesh read_model_mesh(const model::Body& body, const std::string& model_file);

/// The assembled mesh body of `body` (whose beam.mesh is present).
MeshBody build_model_mesh_body(const model::Body& body, const InpMesh& mesh, const std::string& model_file);

/// The reduced body; throws model::ModelError naming the model file and
/// place (a node or element set the mesh lacks, with the names it has).
ElasticModel build_model_mesh(const model::Body& body, const std::string& model_file);

}  // namespace kanegen::fem
