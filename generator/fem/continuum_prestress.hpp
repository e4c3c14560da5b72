// SPDX-License-Identifier: GPL-2.0-or-later
// The stress state of a continuum body under a static load, for its geometric
// stiffness (issue 18): the linear static solve K u = f with some dofs held,
// each element's stress sigma = D B u_e, and the inertia loads of a spinning
// body, as rotating.hpp gives the axial force of a beam chain. The bodies are
// of ContinuumElements (mesh_body.hpp); other elements are refused.
#pragma once

#include <Eigen/Dense>
#include <functional>
#include <vector>

#include "fem/body.hpp"
#include "fem/boundary.hpp"
#include "fem/continuum_element.hpp"

namespace kanegen::fem {

/// Element e as a plane or solid element; throws std::invalid_argument for another element.
const ContinuumElement& continuum_element(const Body& body, int e);

/// u (num_dofs, zero on the held dofs) with K u = f on the free dofs. Throws
/// std::invalid_argument if the held dofs leave the body free to move rigidly.
Eigen::VectorXd static_displacement(const Body& body, const Constraint& held, const Eigen::VectorXd& f);
/// The same for every column of `loads` (num_dofs x m), with one factorisation.
Eigen::MatrixXd static_displacements(const Body& body, const Constraint& held, const Eigen::MatrixXd& loads);

/// The centrifugal load of a body spinning at omega about the link origin:
/// f = int rho N^T (-W^2 r) dV, W = skew(omega), r the undeformed position.
/// A hub radius is where the mesh puts the body in the link frame.
Eigen::VectorXd centrifugal_load(const Body& body, const Eigen::Vector3d& omega);

/// One element's stress at its Gauss points (those of K_e and K_sigma).
struct ElementStress {
  std::vector<Eigen::Vector3d> xi;     ///< natural coordinates
  std::vector<Eigen::Matrix3d> sigma;  ///< Pa, element frame, plane stress: z row and column zero
};
/// sigma = D B u_e at every Gauss point of every element, for body displacement u.
std::vector<ElementStress> gauss_point_stresses(const Body& body, const Eigen::VectorXd& u);

/// The stress field sigma(xi) = D B(xi) u_e of each element, for Body::geometric_stiffness.
std::function<Prestress(int element)> displacement_prestress(const Body& body, const Eigen::VectorXd& u);

/// K_sigma of the stress that the load f causes with the dofs `held` fixed:
/// num_dofs x num_dofs, linear in f.
Eigen::MatrixXd load_geometric_stiffness(const Body& body, const Constraint& held, const Eigen::VectorXd& f);

/// K_e + K_sigma(centrifugal stress for omega) (+ int rho N^T W^2 N, the spin
/// softening, if asked): num_dofs x num_dofs, the stiffness of small vibrations
/// about the steadily spinning body held by `held`.
Eigen::MatrixXd spinning_stiffness(const Body& body, const Constraint& held, const Eigen::Vector3d& omega,
                                   bool with_spin_softening);

}  // namespace kanegen::fem
