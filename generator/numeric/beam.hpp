// SPDX-License-Identifier: GPL-2.0-or-later
// The finite-element beam of a flexible body, written for the numeric path
// over any scalar type: its nodal dofs from the elastic coordinates, the
// position and small rotation of its material points (with the
// foreshortening of geometric stiffening), and its strain energy. Euler-Bernoulli beams with their
// own shape functions here (axial displacement and torsion linear; bending
// by Hermite cubics, theta_z = v', theta_y = -w'), integrated by
// Gauss-Legendre rules computed here. Nothing is shared with generator/fem
// but the basis B of the coordinates (FlexibleData::basis).
#pragma once

#include <array>
#include <cmath>
#include <vector>

#include "numeric/instance.hpp"
#include "numeric/small_matrix.hpp"

namespace kanegen::numeric {

/// Gauss-Legendre points and weights on [0, 1] (exact to degree 2n - 1), by
/// Newton's method on the Legendre polynomial P_n.
struct GaussRule {
  std::vector<double> points, weights;
};

inline GaussRule gauss_rule(int n) {
  GaussRule rule;
  const double pi = 3.14159265358979323846;
  for (int i = 0; i < n; ++i) {
    double x = std::cos(pi * (i + 0.75) / (n + 0.5)), derivative = 1;
    for (int iteration = 0; iteration < 100; ++iteration) {
      double p0 = 1, p1 = x;  // P_0, P_1, then up to P_n by Bonnet's recursion
      for (int k = 2; k <= n; ++k) {
        const double p2 = ((2 * k - 1) * x * p1 - (k - 1) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      if (n == 1) p0 = 1;
      derivative = n * (x * p1 - p0) / (x * x - 1);
      const double step = p1 / derivative;
      x -= step;
      if (std::abs(step) < 1e-16) break;
    }
    rule.points.push_back(0.5 * (1 - x));
    rule.weights.push_back(1.0 / ((1 - x * x) * derivative * derivative));
  }
  return rule;
}

/// The body's nodal dofs (link-frame components) from its elastic coordinates: dofs = B eta.
template <class S>
std::vector<S> beam_dofs(const FlexibleData& f, const S* eta) {
  std::vector<S> dofs(f.num_dofs(), S(0.0));
  for (int k = 0; k < f.count(); ++k)
    for (const auto& [dof, value] : f.basis[k]) dofs[dof] += value * eta[k];
  return dofs;
}

/// A node's displacement and small rotation in the link frame.
template <class S>
Vec<S> node_translation(const FlexibleData& f, const std::vector<S>& dofs, int node) {
  Vec<S> t{S(0.0), S(0.0), S(0.0)};
  for (int a = 0; a < 3; ++a)
    if (const int k = f.dof(node, a); k >= 0) t[a] = dofs[static_cast<std::size_t>(k)];
  return t;
}
/// A mesh body's interface: its mean displacement and its least-squares rotation.
template <class S>
Vec<S> interface_translation(const FlexibleData& f, const std::vector<S>& dofs, int k) {
  const FlexibleData::Interface& in = f.interfaces.at(static_cast<std::size_t>(k));
  Vec<S> t{S(0.0), S(0.0), S(0.0)};
  for (int n : in.nodes) t = add(t, node_translation(f, dofs, n));
  return scale(t, 1.0 / static_cast<double>(in.nodes.size()));
}
template <class S>
Vec<S> interface_rotation(const FlexibleData& f, const std::vector<S>& dofs, int k) {
  const FlexibleData::Interface& in = f.interfaces.at(static_cast<std::size_t>(k));
  // sum r_i x (u_i - u_0), equal to sum r_i x u_i as sum r_i = 0: a rigid
  // translation turns the set by exactly 0, not by sum r_i's round-off.
  const Vec<S> u0 = node_translation(f, dofs, in.nodes.front());
  Vec<S> moment{S(0.0), S(0.0), S(0.0)};
  for (int n : in.nodes) {
    const Vec<double> r = sub(f.nodes[n], in.centroid);
    moment = add(moment, cross(cast<S>(r), sub(node_translation(f, dofs, n), u0)));
  }
  return mul(in.inverse_A, moment);
}

template <class S>
Vec<S> node_rotation(const FlexibleData& f, const std::vector<S>& dofs, int node) {
  if (f.mesh) return interface_rotation(f, dofs, node);
  Vec<S> r{S(0.0), S(0.0), S(0.0)};
  for (int a = 0; a < 3; ++a)
    if (const int k = f.dof(node, 3 + a); k >= 0) r[a] = dofs[static_cast<std::size_t>(k)];
  return r;
}

/// An element's dofs in its own axes, at its two nodes.
template <class S>
struct LocalDofs {
  Vec<S> translation[2], rotation[2];
};

template <class S>
LocalDofs<S> local_dofs(const FlexibleData& f, const BeamElementData& e, const std::vector<S>& dofs) {
  LocalDofs<S> l;
  const Mat<double> to_local = transpose(e.axes);
  for (int i = 0; i < 2; ++i) {
    l.translation[i] = mul(to_local, node_translation(f, dofs, e.node + i));
    l.rotation[i] = mul(to_local, node_rotation(f, dofs, e.node + i));
  }
  return l;
}

/// Hermite cubics of an element of length L at xi = x / L, and their first
/// and second derivatives in x.
inline std::array<double, 4> hermite(double xi, double L) {
  return {1 - 3 * xi * xi + 2 * xi * xi * xi, L * (xi - 2 * xi * xi + xi * xi * xi),
          3 * xi * xi - 2 * xi * xi * xi, L * (xi * xi * xi - xi * xi)};
}
inline std::array<double, 4> hermite_x(double xi, double L) {
  return {6 * (xi * xi - xi) / L, 1 - 4 * xi + 3 * xi * xi, 6 * (xi - xi * xi) / L, 3 * xi * xi - 2 * xi};
}
inline std::array<double, 4> hermite_xx(double xi, double L) {
  return {(12 * xi - 6) / (L * L), (6 * xi - 4) / L, (6 - 12 * xi) / (L * L), (6 * xi - 2) / L};
}

/// The bending fields' nodal values: v with slopes theta_z, w with slopes -theta_y.
template <class S>
std::array<S, 4> v_values(const LocalDofs<S>& l) {
  return {l.translation[0][1], l.rotation[0][2], l.translation[1][1], l.rotation[1][2]};
}
template <class S>
std::array<S, 4> w_values(const LocalDofs<S>& l) {
  return {l.translation[0][2], -l.rotation[0][1], l.translation[1][2], -l.rotation[1][1]};
}
template <class S>
S combine(const std::array<double, 4>& h, const std::array<S, 4>& x) {
  return h[0] * x[0] + h[1] * x[1] + h[2] * x[2] + h[3] * x[3];
}

/// The displaced position of the beam axis at xi, link frame.
template <class S>
Vec<S> beam_point(const BeamElementData& e, const LocalDofs<S>& l, double xi) {
  const std::array<double, 4> h = hermite(xi, e.length);
  const Vec<S> local{xi * e.length + (1 - xi) * l.translation[0][0] + xi * l.translation[1][0],
                     combine(h, v_values(l)), combine(h, w_values(l))};
  return add(e.origin, mul(e.axes, local));
}

/// The section's small rotation carried by its rotary inertia: the torsion
/// only (Euler-Bernoulli beams: the slopes carry none), link frame.
template <class S>
Vec<S> section_rotation(const BeamElementData& e, const LocalDofs<S>& l, double xi) {
  const S twist = (1 - xi) * l.rotation[0][0] + xi * l.rotation[1][0];
  return mul(e.axes, Vec<S>{twist, S(0.0), S(0.0)});
}

/// 1/2 int_0^(xi L) (v'^2 + w'^2) dx over an element: how much bending
/// shortens the projection of the element on its axis, up to xi (the
/// integrand is quartic: 3 Gauss points).
template <class S>
S shortening_integral(const FlexibleData& f, const BeamElementData& e, const LocalDofs<S>& l, double xi) {
  static const GaussRule rule = gauss_rule(3);
  const double L = e.length;
  S sum(0.0);
  for (std::size_t g = 0; g < rule.points.size(); ++g) {
    const std::array<double, 4> hx = hermite_x(xi * rule.points[g], L);
    const S v1 = combine(hx, v_values(l));
    S slope2 = v1 * v1;
    if (!f.planar) {
      const S w1 = combine(hx, w_values(l));
      slope2 += w1 * w1;
    }
    sum += 0.5 * xi * L * rule.weights[g] * slope2;
  }
  return sum;
}

/// Strain energy of the element: 1/2 int EA u'^2 + E Iz v''^2 + E Iy w''^2 + G J theta_x'^2 dx,
/// with the nonlinear axial strain when the beam has it and `nonlinear` (the
/// linear part alone is 1/2 u^T K u, for damping).
template <class S>
S strain_energy(const FlexibleData& f, const BeamElementData& e, const LocalDofs<S>& l,
                bool nonlinear = true) {
  static const GaussRule rule = gauss_rule(3);  // v''^2 is quadratic
  const double L = e.length;
  S energy(0.0);
  for (std::size_t g = 0; g < rule.points.size(); ++g) {
    const double xi = rule.points[g], dx = rule.weights[g] * L;
    const S axial = (l.translation[1][0] - l.translation[0][0]) / L;
    const std::array<double, 4> hxx = hermite_xx(xi, L);
    const S v2 = combine(hxx, v_values(l));
    S density = f.E * f.A * axial * axial + f.E * f.Iz * v2 * v2;
    if (!f.planar) {
      const S w2 = combine(hxx, w_values(l));
      const S twist = (l.rotation[1][0] - l.rotation[0][0]) / L;
      density += f.E * f.Iy * w2 * w2 + f.G * f.J * twist * twist;
    }
    energy += 0.5 * dx * density;
  }
  if (!nonlinear || !f.nonlinear_strain()) return energy;
  // Geometric stiffening in nodal coordinates: the Green-Lagrange axial
  // strain u' + 1/2 (v'^2 + w'^2), its bending part averaged over the element
  // (phi = 1/(2L) int v'^2 + w'^2): EA L / 2 ((u' + phi)^2 - u'^2).
  const S axial = (l.translation[1][0] - l.translation[0][0]) / L;
  const S phi = shortening_integral(f, e, l, 1.0) / L;
  energy += f.E * f.A * L * (axial * phi + 0.5 * phi * phi);
  return energy;
}

/// With geometric stiffening, the beam's foreshortening (second order in
/// the dofs): each element carries everything beyond it back along its axis
/// by its shortening_integral. The displacement at xi of an element whose
/// first node it moves by `start`, link frame.
template <class S>
Vec<S> shortening_at(const FlexibleData& f, const BeamElementData& e, const LocalDofs<S>& l, double xi,
                     const Vec<S>& start) {
  if (!f.shortens()) return start;
  const S s = shortening_integral(f, e, l, xi);
  return {start[0] - e.axes[0] * s, start[1] - e.axes[3] * s, start[2] - e.axes[6] * s};
}

/// The foreshortening's displacement of every node (zero without stiffening).
/// The elements run from node 0 on, each from its node to the next.
template <class S>
std::vector<Vec<S>> node_shortening(const FlexibleData& f, const std::vector<S>& dofs) {
  std::vector<Vec<S>> out(f.nodes.size(), Vec<S>{S(0.0), S(0.0), S(0.0)});
  if (!f.shortens()) return out;
  for (const BeamElementData& e : f.elements)
    out[e.node + 1] = shortening_at(f, e, local_dofs(f, e, dofs), 1.0, out[e.node]);
  return out;
}

/// A node of a beam, or an interface of a mesh body (its centroid): where it
/// is undeformed, link frame.
inline const Vec<double>& rest_node(const FlexibleData& f, int node) {
  return f.mesh ? f.interfaces.at(static_cast<std::size_t>(node)).centroid
                : f.nodes.at(static_cast<std::size_t>(node));
}

/// A mesh body's second-order displacement with geometric stiffening (its
/// foreshortening): u2 = 1/2 sum_ij eta_i eta_j d_ij over the body dofs,
/// eta = left_inverse dofs. Empty without stiffening.
template <class S>
std::vector<S> second_order_displacement(const FlexibleData& f, const std::vector<S>& dofs) {
  if (!f.mesh || !f.shortens()) return {};
  const int n = f.count();
  std::vector<S> eta(n, S(0.0)), u2(dofs.size(), S(0.0));
  for (int k = 0; k < n; ++k)
    for (std::size_t i = 0; i < dofs.size(); ++i)
      if (f.left_inverse[k][i] != 0.0) eta[k] += f.left_inverse[k][i] * dofs[i];
  std::size_t pair = 0;
  for (int i = 0; i < n; ++i)
    for (int j = i; j < n; ++j, ++pair) {
      const S c = (i == j ? 0.5 : 1.0) * eta[i] * eta[j];
      for (const auto& [dof, value] : f.second_order[pair]) u2[dof] += value * c;
    }
  return u2;
}

/// A flexible body's second-order displacement at one state (geometric
/// stiffening), computed once per state and then read at every node placed:
/// a beam's foreshortening of each node (node_shortening), or a mesh body's
/// u2 over its dofs (second_order_displacement); empty without stiffening.
template <class S>
struct SecondOrder {
  std::vector<Vec<S>> beam_nodes;
  std::vector<S> mesh_dofs;
};
template <class S>
SecondOrder<S> second_order(const FlexibleData& f, const std::vector<S>& dofs) {
  SecondOrder<S> out;
  if (f.mesh)
    out.mesh_dofs = second_order_displacement(f, dofs);
  else if (f.shortens())
    out.beam_nodes = node_shortening(f, dofs);
  return out;
}

/// A node's displaced position, link frame: undeformed + translation +
/// foreshortening (`second`: second_order of the same dofs).
template <class S>
Vec<S> displaced_node(const FlexibleData& f, const std::vector<S>& dofs, const SecondOrder<S>& second,
                      int node) {
  if (f.mesh) {
    const Vec<S> moved = add(rest_node(f, node), interface_translation(f, dofs, node));
    return second.mesh_dofs.empty() ? moved : add(moved, interface_translation(f, second.mesh_dofs, node));
  }
  const Vec<S> moved = add(f.nodes[node], node_translation(f, dofs, node));
  return second.beam_nodes.empty() ? moved : add(moved, second.beam_nodes[node]);
}

}  // namespace kanegen::numeric
