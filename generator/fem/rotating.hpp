// SPDX-License-Identifier: GPL-2.0-or-later
// Motion-induced prestress of a beam chain (the geometric stiffening of a
// rotating beam) and the spin-softening term of a body in a spinning frame.
//
// The chain lies on the link x axis (every element a BeamElement with its x
// axis along link x, nodes in order of x), free at its outboard end. An axial
// body load per unit mass a(x) = a_const + a_lin x acts on the beams and on
// point masses, plus an axial force at the tip; the axial force is then
//   N(x) = tip_force + int_x^tip rho A a(s) ds + sum over point masses beyond x of m a(x_m).
// For the inertia loads of a link turning at omega with origin acceleration a0
// (link components): a_lin = omega_y^2 + omega_z^2, a_const = -a0_x (+ g_x for
// gravity); for a hub of radius 0 spinning at Omega about z this is
// N(x) = rho A Omega^2 (L^2 - x^2) / 2.
#pragma once

#include <Eigen/Dense>
#include <functional>

#include "fem/body.hpp"
#include "fem/invariants.hpp"

namespace kanegen::fem {

/// Whether every element is a beam on the link x axis pointing along +x (a chain as above).
bool is_beam_chain(const Body& body);

/// The axial force of each element (tension positive), for Body::geometric_stiffness.
std::function<Prestress(int element)> chain_axial_force(const Body& body, double a_const, double a_lin,
                                                        double tip_force = 0.0);

/// K_G is linear in the loads: K_G = a_const * uniform + a_lin * linear + tip_force * tip.
/// Each is num_dofs x num_dofs; the generator can keep the three factors symbolic.
struct GeometricStiffnessBasis {
  Eigen::MatrixXd uniform;  ///< K_G for a(x) = 1
  Eigen::MatrixXd linear;   ///< K_G for a(x) = x
  Eigen::MatrixXd tip;      ///< K_G for a unit axial tip force
};
GeometricStiffnessBasis geometric_stiffness_basis(const Body& body);

/// K_G for a unit axial force (+x, tension) applied at `node` of the chain:
/// N = 1 in the elements between the joint and the node, 0 beyond. A body
/// carried on that node loads the chain so.
Eigen::MatrixXd node_force_geometric_stiffness(const Body& body, int node);

/// int rho N^T W^2 N: n x n, W = skew(omega), negative semidefinite (rotary
/// inertias add nothing, see floating_frame.hpp). Added to K it gives the stiffness of small vibrations in a
/// frame spinning at omega (centrifugal force on the elastic displacement).
Eigen::MatrixXd spin_softening(const InertiaInvariants& inv, const Eigen::Vector3d& omega);

/// K_e + K_G(centrifugal N for omega) (+ spin_softening if asked): num_dofs x num_dofs.
/// For a hub spinning about z and a beam along x, the flapwise (w, out of the
/// plane of rotation) modes need no softening term; the in-plane (v) modes
/// have it, and without Coriolis coupling omega_inplane^2 = omega_flap^2 - Omega^2
/// for equal bending stiffness.
Eigen::MatrixXd rotating_stiffness(const Body& body, const Eigen::Vector3d& omega, bool with_spin_softening);

}  // namespace kanegen::fem
