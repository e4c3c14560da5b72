// SPDX-License-Identifier: GPL-2.0-or-later
// The foreshortening of a beam body: the axial shortening, of second order
// in the deformation, that bending causes (formulation.md, "Stiffening in
// free motion"; Kane, Ryan and Banerjee 1987).
//
// An element whose transverse slopes are v', w' spans 1/2 int (v'^2 + w'^2) dx
// less along its axis than its axial dofs say, and everything beyond it on
// the way from the root (node 0, where the body is held) moves back along
// that axis by as much. A point p of the body is then at r + N q + f(q) in the
// link frame, with
//
//   f_a(p) = -1/2 q^T H_a(p) q,
//   H(p)   = sum over the elements e between the root and p of x_e int_e G^T G dx
//            + x_p int_0^x G^T G dx over the element that holds p, up to p,
//
// x_e the element's axis in the link frame and G the slope rows in q. Loaded
// by an axial force field, the work of f is -1/2 q^T K_G q: the geometric
// stiffness then comes out of the kinematics, with its reaction on the rigid
// motion, instead of being added to the elastic equations alone.
#pragma once

#include <Eigen/Dense>
#include <array>
#include <vector>

#include "fem/body.hpp"

namespace kanegen::fem {

struct Foreshortening {
  /// Per body node: H_a at the node (n x n each, a = x, y, z).
  std::vector<std::array<Eigen::MatrixXd, 3>> node;
  /// sum_p m_p H_a(p) over the body's mass points (elements and point masses).
  std::array<Eigen::MatrixXd, 3> mass;
  /// [3a+b]: sum_p m_p r_b H_a(p), r the undeformed position.
  std::array<Eigen::MatrixXd, 9> moment;
  /// Mesh bodies (add_second_order_mass): the elastic mass's terms of first
  /// and second order in eta, int rho (N + D)^T (N + D) - int rho N^T N, by
  /// the fields d_p of the pairs p = (i, j) (u2 = 1/2 sum_ij eta_i eta_j d_ij,
  /// D_k = sum_i eta_i d_ik). Empty for beams.
  Eigen::MatrixXd mode_pair;  ///< n x pairs: int rho (N phi_k) . (N d_p)
  Eigen::MatrixXd pair_pair;  ///< pairs x pairs: int rho (N d_p) . (N d_q)
};

/// The foreshortening in the coordinates eta of u = B eta (B: num_dofs x n).
/// Throws std::invalid_argument if an element is not a beam, or starts at a
/// node that no earlier element reaches from node 0.
Foreshortening foreshortening(const Body& body, const Eigen::MatrixXd& B);

}  // namespace kanegen::fem
