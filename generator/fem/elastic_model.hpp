// SPDX-License-Identifier: GPL-2.0-or-later
// The elastic part of a flexible body of the model (model::ElasticPart) as
// the finite-element layer's reduced body: for a beam, nodes along the
// segments, beam elements, the tip mass, the support, nodal or modal
// coordinates or assumed modes; for a mesh, the body fem/model_mesh.* builds;
// and the damping matrix. This is the bridge from the plain model data to
// the generator (and to the numeric path's basis).
#pragma once

#include <Eigen/Dense>
#include <optional>
#include <string>

#include "fem/assumed_modes.hpp"
#include "fem/axial_strain.hpp"
#include "fem/beam_element.hpp"
#include "fem/body.hpp"
#include "fem/foreshortening.hpp"
#include "fem/reduction.hpp"
#include "model/model.hpp"

namespace kanegen::fem {

/// A point that moves with a node set of a mesh body (an interface): the
/// least-squares rigid motion of the set's nodes (RBE3-like averaging), so
/// that it adds no stiffness; for a set that moves rigidly it is that motion.
struct InterfacePoint {
  std::string name;             ///< the node set
  Eigen::Vector3d position;     ///< the set's centroid, link frame
  Eigen::MatrixXd translation;  ///< 3 x n: displacement in the link frame = translation eta
  Eigen::MatrixXd rotation;     ///< 3 x n: small rotation
};

/// A flexible body's elastic part, built and reduced (beam or mesh).
struct ElasticModel {
  Body body;                ///< all nodal dofs, link frame
  ReducedBody reduced;      ///< the elastic coordinates eta: u = basis eta
  Eigen::MatrixXd damping;  ///< n x n: alpha M + beta K, or 2 zeta omega_i in modal coordinates
  /// The section and material of every element, for the stress outputs.
  BeamSection section;
  Material material;
  /// Geometric stiffening, in one of two forms. Nodal coordinates keep the
  /// axial displacements: the nonlinear axial strain energy
  /// (fem/axial_strain.hpp). Modes and assumed modes leave the stiff axial
  /// motion out: the foreshortening of the bending (fem/foreshortening.hpp)
  /// carries the axial force instead. Both are conservative. A mesh body's
  /// foreshortening is its second-order displacement field
  /// (fem/continuum_foreshortening.hpp), H at each interface.
  std::vector<AxialStrainElement> axial_strain;
  std::optional<Foreshortening> foreshortening;
  /// Mesh bodies: their points that joints attach to, by the index
  /// model::MeshSource::interfaces gives (a mesh body's "node" k is its interface k).
  std::vector<InterfacePoint> interfaces;
  bool is_mesh = false;
  /// A mesh body with geometric stiffening: the second-order fields d_ij
  /// (num_dofs x n (n + 1) / 2, pairs i <= j as fem::pair_index orders them):
  /// its points are at r + N (basis eta + 1/2 sum_ij eta_i eta_j d_ij).
  Eigen::MatrixXd second_order;

  /// A node of a beam, or an interface of a mesh body: undeformed position
  /// (link frame) and its displacement and small rotation in eta (3 x n).
  Eigen::Vector3d point_position(int node) const {
    return is_mesh ? interfaces.at(node).position : body.node_position(node);
  }
  Eigen::MatrixXd point_translation(int node) const {
    return is_mesh ? interfaces.at(node).translation : reduced.node_translation(body, node);
  }
  Eigen::MatrixXd point_rotation(int node) const {
    return is_mesh ? interfaces.at(node).rotation : reduced.node_rotation(body, node);
  }
};

/// The damping matrix of the reduced body: 2 zeta omega_k m_kk on the
/// diagonal with modal damping (`modal`: the body's coordinates are modes),
/// else alpha M + beta K.
Eigen::MatrixXd reduced_damping(const model::ElasticPart& f, const ReducedBody& reduced, bool modal);

/// Builds the body; throws model::ModelError (naming the body's place) when
/// the beam cannot be built. `shapes` samples the assumed modes, if any
/// (fem/assumed_modes.hpp: each derivation brings its own).
ElasticModel build_elastic_model(const model::Body& body, const std::string& file,
                                 const ShapeSampler& shapes);

}  // namespace kanegen::fem
