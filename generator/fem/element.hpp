// SPDX-License-Identifier: GPL-2.0-or-later
// The finite-element interface: what the assembly, the inertia invariants and
// the generator need from an element, without assuming beams. An element lives
// in its own frame (placed in the link frame by a constant rotation R^e and an
// origin, see body.hpp); its nodal dofs u^e are components in that frame, and
// every quantity is a function of natural coordinates xi (the seed's
// isoparametric elements: a point is r = N^e p^e, its displacement d = N^e u^e).
#pragma once

#include <Eigen/Dense>
#include <functional>
#include <utility>
#include <vector>

namespace kanegen::fem {

/// One nodal dof: a translation along, or a small rotation about, an axis of
/// the frame the dof is expressed in (element frame for u^e, link frame for a body).
enum class DofKind { kUx, kUy, kUz, kRx, kRy, kRz };

/// The dofs of one node, in order. Every node of an element has the same layout.
using DofLayout = std::vector<DofKind>;

/// Planar layout (u, v, theta_z): motion in the x-y plane of the element.
const DofLayout& planar_layout();
/// Spatial layout (u, v, w, theta_x, theta_y, theta_z).
const DofLayout& spatial_layout();
/// Plane continuum layout (u, v): plane-stress elements in the x-y plane, no rotations.
const DofLayout& plane_layout();
/// Solid continuum layout (u, v, w): solid elements, no rotations.
const DofLayout& solid_layout();

/// An element's kinematics at one point of natural coordinates xi.
struct ShapeSample {
  Eigen::Vector3d r;     ///< undeformed position, element frame (r = N^e p^e)
  Eigen::MatrixXd N;     ///< 3 x ndof: displacement d = N u^e, element frame
  Eigen::MatrixXd Nrot;  ///< 3 x ndof: small rotation of the material there, theta = Nrot u^e
};

/// A point of the element's mass quadrature: the integral of rho f over the
/// element is sum_p mass_p f(p) for every f of the degree the element needs.
/// A point may also carry rotary inertia J (a cross-section's polar or bending
/// inertia, or a rigid body on a node), which turns with Nrot; J = 0 for a
/// continuum point.
struct MassPoint {
  double mass = 0.0;     ///< kg
  Eigen::Vector3d r;     ///< undeformed position
  Eigen::MatrixXd N;     ///< 3 x ndof: displacement = N u
  Eigen::Matrix3d J;     ///< kg m^2, about the point, in the same frame as r
  Eigen::MatrixXd Nrot;  ///< 3 x ndof: rotation = Nrot u
};

/// The initial stress state that a geometric stiffness is formed for. Line
/// elements read the axial force N(xi) in newtons (tension positive).
/// Continuum elements read the stress tensor sigma(xi) in pascals (tension
/// positive, element-frame components; plane-stress elements read its x-y
/// block). For the small strains of a linear prestress the Cauchy and second
/// Piola-Kirchhoff stresses agree, so either may be given.
struct Prestress {
  Prestress() = default;
  /// A line element's axial force (implicit, so Prestress{force} still reads as a beam's prestress).
  Prestress(std::function<double(double xi)> force) : axial_force(std::move(force)) {}  // NOLINT
  std::function<double(double xi)> axial_force;
  std::function<Eigen::Matrix3d(const Eigen::Vector3d& xi)> stress;
};

class Element {
 public:
  virtual ~Element() = default;

  virtual int num_nodes() const = 0;
  /// Number of natural coordinates (1 for a line element, 3 for a solid).
  virtual int dimension() const = 0;
  virtual const DofLayout& node_layout() const = 0;
  int dofs_per_node() const { return static_cast<int>(node_layout().size()); }
  /// Nodal dofs are numbered node by node: dof = node * dofs_per_node() + k.
  int num_dofs() const { return num_nodes() * dofs_per_node(); }

  /// 3 x num_nodes: the nodes in the element frame.
  virtual Eigen::Matrix3Xd node_positions() const = 0;
  /// Shape functions at natural coordinates xi (the first dimension() entries are used).
  virtual ShapeSample shape(const Eigen::Vector3d& xi) const = 0;
  /// The mass quadrature, exact for the element's inertia integrals (see invariants.hpp).
  virtual std::vector<MassPoint> mass_points() const = 0;
  /// K_e: ndof x ndof, linear elastic stiffness, element frame.
  virtual Eigen::MatrixXd stiffness() const = 0;
  /// K_G: ndof x ndof, geometric stiffness of the given prestress, element frame.
  virtual Eigen::MatrixXd geometric_stiffness(const Prestress& prestress) const = 0;

  /// M: ndof x ndof, the consistent mass sum_p m_p N^T N + Nrot^T J Nrot.
  Eigen::MatrixXd mass() const;
};

/// 3 x 3 cross-product matrix: skew(a) b = a x b.
Eigen::Matrix3d skew(const Eigen::Vector3d& a);

}  // namespace kanegen::fem
