// SPDX-License-Identifier: GPL-2.0-or-later
// The foreshortening of a mesh body (issue 18): the second-order displacement
// field that geometric stiffening puts in the kinematics of plane and solid
// bodies, as fem/foreshortening.hpp does for beams (formulation.md,
// "Stiffening in free motion").
//
// The Green-Lagrange strain of u = Phi eta + u2 is, to second order in eta,
// eps(Phi eta) + eps(u2) + 1/2 sum_ij eta_i eta_j Q_ij
// (ContinuumElement::quadratic_strain_forces). With u2 = 1/2 sum_ij eta_i
// eta_j d_ij, the d_ij that minimise the strain energy of the second-order
// part, the body held on `held`, solve K d_ij = -g_ij, g_ij = int B^T D q_ij.
// A point p is then at r + N (Phi eta + u2) = r + N Phi eta + f(p), with
// f_a(p) = -1/2 eta^T H_a(p) eta, (H_a)_ij = -(N d_ij)_a: the Foreshortening
// struct of the beams, with mass and moment by the element quadrature.
//
// By reciprocity, a load f works through u2 as
// f . u2 = -1/2 eta^T Phi^T K_sigma(f) Phi eta, K_sigma(f) the geometric
// stiffness of the static stress of f: the stiffening of every load, with its
// reaction on the rigid motion. For a beam, u2 is its foreshortening.
#pragma once

#include <Eigen/Dense>
#include <vector>

#include "fem/body.hpp"
#include "fem/boundary.hpp"
#include "fem/foreshortening.hpp"

namespace kanegen::fem {

/// The fields d_ij (num_dofs x pair_count(n), column pair_index(i, j), zero
/// on the held dofs) of the modes `basis` (num_dofs x n) of a body of plane or
/// solid elements. Throws std::invalid_argument for other elements, or if
/// `held` leaves the body free to move rigidly (u2 needs a held reference).
Eigen::MatrixXd second_order_fields(const Body& body, const Constraint& held, const Eigen::MatrixXd& basis);

/// The Foreshortening of the fields d (second_order_fields, n modes): H at
/// each point of `points` (3 x num_dofs each: a point's displacement in the
/// body dofs, such as an interface's mean translation), and the mass and
/// moment integrals over the body's mass points.
Foreshortening continuum_foreshortening(const Body& body, const Eigen::MatrixXd& d, int n,
                                        const std::vector<Eigen::MatrixXd>& points);

/// The integrals of the elastic mass to second order in eta (mode_pair,
/// pair_pair) over the body's mass points, of the modes `basis` and their
/// fields d: the elastic block int rho (N + D)^T (N + D) that keeps the mass
/// matrix positive definite when a mode moves points along u2 (a
/// Craig-Bampton interface's axial shape).
void add_second_order_mass(const Body& body, const Eigen::MatrixXd& basis, const Eigen::MatrixXd& d,
                           Foreshortening& f);

}  // namespace kanegen::fem
