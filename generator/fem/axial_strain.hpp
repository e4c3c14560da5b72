// SPDX-License-Identifier: GPL-2.0-or-later
// The Green-Lagrange axial strain of a beam body's axis, to the order that
// couples bending with the axial force (formulation.md section 4):
//   eps = u' + 1/2 (v'^2 + w'^2).
// Each element takes its mean over the element,
//   eps_e = u' + phi_e,   phi_e = 1/(2 L) int_e (v'^2 + w'^2) dx,
// (u' is constant on a linear axial element; the pointwise strain would tie
// the cubic bending to it and stiffen a bent element spuriously: membrane
// locking). Its strain energy EA L / 2 eps_e^2 exceeds the linear EA L / 2 u'^2 by
//   U_nl = EA L (u' phi_e + phi_e^2 / 2).
// With the axial coordinates free, this is geometric stiffening that is
// conservative by construction: a tension N = EA eps_e stiffens the bending
// by N int G^T G (the geometric stiffness), and every load that stretches the
// beam (inertia, gravity, node forces, carried bodies) does so where it acts.
#pragma once

#include <Eigen/Dense>
#include <vector>

#include "fem/body.hpp"

namespace kanegen::fem {

/// One element: U_nl = stiffness (e phi + phi^2 / 2), e = axial eta,
/// phi = 1/2 sum_p weight_p |slopes_p eta|^2.
struct AxialStrainElement {
  double stiffness = 0.0;               ///< EA L
  Eigen::RowVectorXd axial;             ///< 1 x n: u' in eta
  std::vector<double> weight;           ///< per Gauss point: its share of the element length / L
  std::vector<Eigen::MatrixXd> slopes;  ///< per Gauss point: planar 1 x n (v'), spatial 2 x n (v', w')
};

/// 3 Gauss points per element (v'^2 is of degree 4 along it: exact), in the
/// coordinates eta of u = B eta. Throws std::invalid_argument if an element
/// is not a beam.
std::vector<AxialStrainElement> axial_strain_elements(const Body& body, const Eigen::MatrixXd& B);

}  // namespace kanegen::fem
