// SPDX-License-Identifier: GPL-2.0-or-later
// Two-node Euler-Bernoulli beam along the element's x axis, from node 0 at
// x = 0 to node 1 at x = L; natural coordinate xi = x / L in [0, 1].
//
// Planar (3 dofs per node: u, v, theta_z): axial u linear, in-plane bending v
// Hermite cubic, theta_z = dv/dx.
// Spatial (6 dofs per node: u, v, w, theta_x, theta_y, theta_z): axial and
// torsion linear, v and w Hermite cubics, right-handed rotations about the
// element axes, so theta_z = +dv/dx but theta_y = -dw/dx (a positive rotation
// about y turns the x axis towards -z).
// Node k's dofs are k * dofs_per_node + (0, 1, 2 | 0 .. 5) in the orders above.
#pragma once

#include <Eigen/Dense>

#include "fem/element.hpp"

namespace kanegen::fem {

struct BeamSection {
  double A = 0.0;   ///< m^2
  double Iy = 0.0;  ///< m^4, int z^2 dA: bending in the x-z plane (w)
  double Iz = 0.0;  ///< m^4, int y^2 dA: bending in the x-y plane (v)
  double J = 0.0;   ///< m^4, torsion constant (torsional stiffness G J)
  double Ip = 0.0;  ///< m^4, polar moment for the torsional inertia rho Ip; 0 means Iy + Iz
  double polar_moment() const { return Ip > 0.0 ? Ip : Iy + Iz; }
};

struct Material {
  double E = 0.0;    ///< Pa
  double G = 0.0;    ///< Pa
  double rho = 0.0;  ///< kg/m^3
  static Material isotropic(double E, double poisson, double rho) {
    return {E, E / (2.0 * (1.0 + poisson)), rho};
  }
};

enum class BeamKind { kPlanar, kSpatial };

class BeamElement final : public Element {
 public:
  /// bending_rotary_inertia adds rho I theta^2 / 2 of the bending slopes to the
  /// kinetic energy (Rayleigh beam); off by default (Euler-Bernoulli). The
  /// torsional inertia rho Ip is always kept, and every mass point carries the
  /// section's rigid rotary inertia L w diag(rho Ip, rho Iy, rho Iz).
  BeamElement(BeamKind kind, double length, const BeamSection& section, const Material& material,
              bool bending_rotary_inertia = false);

  int num_nodes() const override { return 2; }
  int dimension() const override { return 1; }
  const DofLayout& node_layout() const override;
  Eigen::Matrix3Xd node_positions() const override;
  ShapeSample shape(const Eigen::Vector3d& xi) const override;
  /// 4 Gauss points: exact for every inertia integral (degree <= 6 in xi).
  std::vector<MassPoint> mass_points() const override;
  /// K_e: ndof x ndof, closed form.
  Eigen::MatrixXd stiffness() const override;
  /// K_G = int N(x) (G_v^T G_v + G_w^T G_w) dx with G = dN_v/dx, dN_w/dx (ndof x ndof), by
  /// 6-point Gauss quadrature: exact when N(xi) is a polynomial of degree <= 7.
  Eigen::MatrixXd geometric_stiffness(const Prestress& prestress) const override;

  /// K_G: ndof x ndof, closed form for N varying linearly from n0 at node 0 to n1 at node 1.
  Eigen::MatrixXd geometric_stiffness_linear(double n0, double n1) const;
  /// M: ndof x ndof, the textbook consistent mass in closed form (equals mass()).
  Eigen::MatrixXd consistent_mass() const;

  BeamKind kind() const { return kind_; }
  double length() const { return length_; }
  const BeamSection& section() const { return section_; }
  const Material& material() const { return material_; }
  double mass_per_length() const { return material_.rho * section_.A; }

  /// Hermite cubics at xi: v = H0 v_0 + H1 theta_0 + H2 v_1 + H3 theta_1 (H1, H3 carry the factor L).
  static Eigen::Vector4d hermite(double xi, double length);
  /// d/dx of the Hermite cubics (x = xi L).
  static Eigen::Vector4d hermite_dx(double xi, double length);
  /// d^2/dx^2 of the Hermite cubics.
  static Eigen::Vector4d hermite_dxx(double xi, double length);

  /// Section resultants at xi as a linear map of u^e, element frame, from the
  /// displacement field (so piecewise linear moments, constant forces):
  /// planar 2 x ndof: (N, M_z); spatial 4 x ndof: (N, T, M_y, M_z), with
  /// N = E A u', T = G J theta_x', M_y = E Iy theta_y' = -E Iy w'', M_z = E Iz v''.
  /// Bending stress at (y, z) of the section: N / A - M_z y / Iz + M_y z / Iy.
  Eigen::MatrixXd resultant_matrix(double xi) const;

  /// Slopes of the transverse displacements at xi as a linear map of u^e,
  /// element frame: planar 1 x ndof (v'), spatial 2 x ndof (v', w'). Their
  /// squares are the Green-Lagrange strain's bending part, 1/2 (v'^2 + w'^2).
  Eigen::MatrixXd slope_matrix(double xi) const;

 private:
  struct Bending {
    int dof[4];  // (v0, theta0, v1, theta1) or (w0, theta_y0, w1, theta_y1)
    double sign[4];
    double EI, rhoI;
  };
  std::vector<Bending> bending_planes() const;
  int dof(int node, int k) const { return node * dofs_per_node() + k; }

  BeamKind kind_;
  double length_;
  BeamSection section_;
  Material material_;
  bool bending_rotary_inertia_;
};

}  // namespace kanegen::fem
