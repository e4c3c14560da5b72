// SPDX-License-Identifier: GPL-2.0-or-later
// Isoparametric continuum elements (issue 18) of the families of
// element_families.hpp: 4- and 8-node plane-stress quadrilaterals of
// thickness t, and 8- and 20-node (serendipity) hexahedra, isotropic and
// linear elastic. Their nodes carry translations only
// (plane_layout, solid_layout), numbered as CalculiX and Abaqus number CPS4,
// CPS8, C3D8 and C3D20, so that a mesh from those tools (or Gmsh) is used as
// written. The element frame is the link frame: nodes are given where they
// are, and a plane element lies in a plane z = const.
//
// Natural coordinates are in [-1, 1] (not the [0, 1] of the beams), the usual
// range of these families. Integration is full Gauss-Legendre, as CalculiX
// integrates C3D8 and C3D20: 2 points per direction for the linear families,
// 3 for the quadratic ones; both K_e and the mass points use it, so the mass
// and the inertia invariants are exact for elements of affine shape.
#pragma once

#include <Eigen/Dense>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "fem/element.hpp"
#include "fem/element_families.hpp"

namespace kanegen::fem {

/// The pairs of n modes i <= j: n (n + 1) / 2 of them, ordered (0, 0), (0, 1),
/// ..., (0, n - 1), (1, 1), ...; pair_index(i, j) = pair_index(j, i).
inline int pair_count(int n) { return n * (n + 1) / 2; }
inline int pair_index(int i, int j, int n) {
  if (i > j) std::swap(i, j);
  return i * n - i * (i - 1) / 2 + (j - i);
}

/// Isotropic linear elastic material: Young's modulus (Pa), Poisson's ratio, density (kg/m^3).
struct ContinuumMaterial {
  double E = 0.0;
  double nu = 0.0;
  double rho = 0.0;
};

/// Thrown for an element whose Jacobian determinant is not positive somewhere
/// (at a Gauss point or a node): its nodes are numbered the wrong way round, or
/// it is folded. The mesh layer adds which element of which file.
class InvertedElementError : public std::invalid_argument {
 public:
  InvertedElementError(double min_det_j, const std::string& where)
      : std::invalid_argument("inverted element: det J = " + std::to_string(min_det_j) + " at " + where),
        min_det_j_(min_det_j) {}
  double min_det_j() const { return min_det_j_; }

 private:
  double min_det_j_;
};

class ContinuumElement final : public Element {
 public:
  /// nodes: 3 x family_num_nodes, link frame, CalculiX order. thickness: plane elements only.
  /// Throws InvertedElementError for det J <= 0, std::invalid_argument for other bad input.
  ContinuumElement(ContinuumFamily family, const Eigen::Matrix3Xd& nodes, const ContinuumMaterial& material,
                   double thickness = 1.0);

  int num_nodes() const override { return family_num_nodes(family_); }
  int dimension() const override { return family_dimension(family_); }
  const DofLayout& node_layout() const override;
  Eigen::Matrix3Xd node_positions() const override { return nodes_; }
  /// xi in [-1, 1]^dimension. Nrot is the small rotation of the material, curl(d) / 2.
  ShapeSample shape(const Eigen::Vector3d& xi) const override;
  /// One point per Gauss point, mass rho det J w (times t for plane elements), J = 0.
  std::vector<MassPoint> mass_points() const override;
  /// K_e = int B^T D B dV (plane stress D times t for the quadrilaterals).
  Eigen::MatrixXd stiffness() const override;
  /// K_sigma = int G^T S G dV, the Green-Lagrange strain's nonlinear part under
  /// the prestress's stress field S = sigma(xi), G the shape-function gradients
  /// of each displacement component (S block-diagonal over the components), by
  /// the quadrature of K_e. Plane elements: the in-plane block of sigma, times t;
  /// their out-of-plane displacement is no dof, so K_sigma stiffens or softens
  /// in-plane motion only (no out-of-plane buckling of a plate). Throws
  /// std::invalid_argument if the prestress has no stress field.
  Eigen::MatrixXd geometric_stiffness(const Prestress& prestress) const override;
  /// sigma = D B u_e at xi (Pa, 3 x 3, symmetric): the linear elastic stress of
  /// the element displacement u_e; plane stress leaves the z row and column zero.
  Eigen::Matrix3d stress(const Eigen::VectorXd& u_e, const Eigen::Vector3d& xi) const;
  /// The second-order strain's forces of the element displacements u_e
  /// (ndof_e x n, one column per mode): the columns of pairs (i <= j, in the
  /// order of pair_index) g_ij = int B^T D q_ij dV, q_ij the Voigt form
  /// (engineering shears) of Q_ij = (G_i^T G_j + G_j^T G_i) / 2, G_i = grad u_i
  /// (G_cb = du_c/dx_b). The quadratic part of the Green-Lagrange strain of
  /// u = sum eta_i u_i is 1/2 sum_ij eta_i eta_j Q_ij. Quadrature of K_e.
  Eigen::MatrixXd quadratic_strain_forces(const Eigen::MatrixXd& u_e) const;
  /// The natural coordinates of the Gauss points that K_e and K_sigma use.
  std::vector<Eigen::Vector3d> gauss_points() const;

  ContinuumFamily family() const { return family_; }
  /// Volume (plane elements: area times thickness), by the element's quadrature.
  double volume() const;

 private:
  struct GaussSample {
    Eigen::Vector3d xi;
    Eigen::VectorXd N;     ///< num_nodes
    Eigen::MatrixXd dNdx;  ///< num_nodes x dimension, derivatives in the link frame
    double weight;         ///< det J times the Gauss weight (times t for plane elements)
  };
  /// dN/dx and det J at xi; throws InvertedElementError if det J <= 0.
  Eigen::MatrixXd physical_gradient(const NaturalShape& shape, const Eigen::Vector3d& xi,
                                    double& det_j) const;
  ShapeSample sample(const Eigen::VectorXd& N, const Eigen::MatrixXd& dNdx) const;

  ContinuumFamily family_;
  Eigen::Matrix3Xd nodes_;
  ContinuumMaterial material_;
  double thickness_;
  std::vector<GaussSample> gauss_;
};

}  // namespace kanegen::fem
