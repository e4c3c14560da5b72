// SPDX-License-Identifier: GPL-2.0-or-later
#include "numeric/dynamics.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "numeric/beam.hpp"
#include "numeric/dual.hpp"
#include "numeric/loops.hpp"
#include "numeric/poses.hpp"
#include "numeric/solid.hpp"

namespace kanegen::numeric {
namespace {

using D1 = Dual<double>;
using D2 = Dual<D1>;

/// Gauss points per beam element for the mass integrals: |velocity|^2 of a
/// cubic field is of degree 6, exact with 4 points.
const GaussRule& mass_rule() {
  static const GaussRule rule = gauss_rule(4);
  return rule;
}

void check_sizes(const Instance& m, const State& s) {
  const std::size_t n = static_cast<std::size_t>(m.coordinates());
  if (s.q.size() != n || s.u.size() != n || s.tau.size() != n)
    throw std::invalid_argument("numeric::evaluate: expected " + std::to_string(n) +
                                " coordinates, speeds and inputs");
}

Vec<double> derivative(const Vec<D1>& x) { return {x[0].d, x[1].d, x[2].d}; }
Mat<double> derivative(const Mat<D1>& x) {
  Mat<double> d;
  for (int i = 0; i < 9; ++i) d[i] = x[i].d;
  return d;
}
bool is_zero(const Vec<double>& x) { return x[0] == 0 && x[1] == 0 && x[2] == 0; }

/// One mass element (see dynamics.hpp), in the fixed order of visit_masses.
struct MassElement {
  int body = -1;
  double mass = 0;
  Mat<double> inertia{};  ///< about the point, link axes
};

Mat<double> diagonal_in(const Mat<double>& axes, double a, double b, double c) {
  const Mat<double> d{a, 0, 0, 0, b, 0, 0, 0, c};
  return mul(axes, mul(d, transpose(axes)));
}

std::vector<MassElement> mass_elements(const Instance& m) {
  std::vector<MassElement> out;
  const GaussRule& rule = mass_rule();
  for (std::size_t b = 0; b < m.bodies.size(); ++b) {
    const BodyData& body = m.bodies[b];
    out.push_back({static_cast<int>(b), body.mass, body.inertia});
    if (!body.elastic) continue;
    const FlexibleData& f = *body.elastic;
    for (const BeamElementData& e : f.elements)
      for (double w : rule.weights) {
        const double dx = w * e.length, rho = f.density;
        // The section's rotary inertia about its centre, element axes diag(Ip, Iy, Iz), Ip = Iy + Iz.
        out.push_back({static_cast<int>(b), rho * f.A * dx,
                       diagonal_in(e.axes, rho * (f.Iy + f.Iz) * dx, rho * f.Iy * dx, rho * f.Iz * dx)});
      }
    // A mesh body's Gauss points are point masses (no rotary inertia).
    for (const SolidElementData& e : f.solids)
      for (const SolidElementData::Point& p : e.points)
        out.push_back({static_cast<int>(b), f.density * p.weight, Mat<double>{}});
    if (f.tip_mass > 0) out.push_back({static_cast<int>(b), f.tip_mass, f.tip_inertia});
  }
  return out;
}

/// Which inputs of the position functions vary along a seed: each body's
/// pose, each node's dofs of a flexible body. Mass elements none of whose
/// inputs vary are skipped (their derivative is zero).
struct Touched {
  std::vector<char> pose;
  std::vector<std::vector<char>> node;
};

Touched touched_by(const Instance& m, const std::vector<Pose<D1>>& poses,
                   const std::vector<std::vector<D1>>& dofs) {
  Touched t;
  t.pose.assign(m.bodies.size(), 0);
  t.node.resize(m.bodies.size());
  for (std::size_t b = 0; b < m.bodies.size(); ++b) {
    for (int i = 0; i < 9; ++i) t.pose[b] = t.pose[b] || poses[b].rotation[i].d != 0;
    for (int i = 0; i < 3; ++i) t.pose[b] = t.pose[b] || poses[b].origin[i].d != 0;
    if (!m.bodies[b].elastic) continue;
    const FlexibleData& f = *m.bodies[b].elastic;
    t.node[b].assign(f.nodes.size(), 0);
    for (int d = 0; d < f.num_dofs(); ++d)
      if (dofs[b][d].d != 0) t.node[b][d / f.dofs_per_node] = 1;
    // The foreshortening moves every point with the dofs of the nodes before it.
    if (f.shortens() && !f.mesh)
      for (std::size_t i = 1; i < f.nodes.size(); ++i) t.node[b][i] = t.node[b][i] || t.node[b][i - 1];
    // A mesh body's second-order displacement moves every node with any dof.
    if (f.shortens() && f.mesh && std::find(t.node[b].begin(), t.node[b].end(), 1) != t.node[b].end())
      t.node[b].assign(f.nodes.size(), 1);
  }
  return t;
}

template <class S>
Vec<S> to_world(const Pose<S>& pose, const Vec<S>& local) {
  return add(pose.origin, mul(pose.rotation, local));
}

/// Calls visit(index, body, world position, small rotation (link frame)) for
/// every mass element in mass_elements order; with `touched`, only for the
/// elements whose inputs vary. A beam's own points are placed at its dofs
/// times `scale` (see truncation_samples).
template <class S, class Visit>
void visit_masses(const Instance& m, const std::vector<Pose<S>>& poses,
                  const std::vector<std::vector<S>>& dofs, const Touched* touched, Visit&& visit,
                  double scale = 1.0) {
  const GaussRule& rule = mass_rule();
  const int per_element = static_cast<int>(rule.points.size());
  const Vec<S> zero{S(0.0), S(0.0), S(0.0)};
  int index = 0;
  for (std::size_t b = 0; b < m.bodies.size(); ++b) {
    const BodyData& body = m.bodies[b];
    const Pose<S>& pose = poses[b];
    const int bi = static_cast<int>(b);
    if (!touched || touched->pose[b]) visit(index, bi, to_world(pose, cast<S>(body.com)), zero);
    ++index;
    if (!body.elastic) continue;
    const FlexibleData& f = *body.elastic;
    std::vector<S> own = dofs[b];
    if (scale != 1.0)
      for (S& x : own) x = x * scale;
    const std::vector<Vec<S>> shortening = node_shortening(f, own);
    const std::vector<S> second_order = second_order_displacement(f, own);
    for (const BeamElementData& e : f.elements) {
      if (touched && !touched->pose[b] && !touched->node[b][e.node] && !touched->node[b][e.node + 1]) {
        index += per_element;
        continue;
      }
      const LocalDofs<S> l = local_dofs(f, e, own);
      for (double xi : rule.points)
        visit(index++, bi,
              to_world(pose, add(beam_point(e, l, xi), shortening_at(f, e, l, xi, shortening[e.node]))),
              section_rotation(e, l, xi));
    }
    for (const SolidElementData& e : f.solids) {
      bool moves = !touched || touched->pose[b];
      for (int n : e.nodes) moves = moves || touched->node[b][n];
      if (!moves) {
        index += static_cast<int>(e.points.size());
        continue;
      }
      for (const SolidElementData::Point& p : e.points)
        visit(index++, bi, to_world(pose, solid_point(f, e, p, own, second_order)), zero);
    }
    if (f.tip_mass > 0) {
      const int last = static_cast<int>(f.nodes.size()) - 1;
      if (!touched || touched->pose[b] || touched->node[b][last])
        visit(index, bi,
              to_world(pose, add(f.nodes[last], add(node_translation(f, own, last), shortening[last]))),
              node_rotation(f, own, last));
      ++index;
    }
  }
}

/// The world position of a force's point (a body point, or a displaced node).
template <class S>
Vec<S> force_point(const Instance& m, const ForceData& force, const std::vector<Pose<S>>& poses,
                   const std::vector<std::vector<S>>& dofs, const std::vector<SecondOrder<S>>& second) {
  if (force.node < 0) return to_world(poses[force.body], cast<S>(force.point));
  const FlexibleData& f = *m.bodies[force.body].elastic;
  return to_world(poses[force.body], displaced_node(f, dofs[force.body], second[force.body], force.node));
}

/// A spring's vector from its second end to its first, world axes.
template <class S>
Vec<S> spring_vector(const SpringData& spring, const std::vector<Pose<S>>& poses) {
  return sub(point_position(poses, spring.body, spring.point),
             point_position(poses, spring.body2, spring.point2));
}

/// A spring along the motion: its length l and rate l_dot (the derivative of
/// l itself, not a formula for it), the tension k (l - l0) + c l_dot and the
/// unit vector from its second end to its first, world axes. Its force on
/// the first end is -tension * direction.
struct SpringState {
  double length = 0, rate = 0, tension = 0;
  Vec<double> direction;
};

SpringState spring_state(const SpringData& spring, const std::vector<Pose<D2>>& poses) {
  const Vec<D2> d = spring_vector(spring, poses);
  const D2 l = sqrt(dot(d, d));
  SpringState st;
  st.length = l.v.v;
  st.rate = l.v.d;
  st.tension = spring.stiffness * (st.length - spring.rest_length) + spring.damping * st.rate;
  st.direction = {d[0].v.v / st.length, d[1].v.v / st.length, d[2].v.v / st.length};
  return st;
}

/// Sums over the elements of a flexible body, of those touched (all if null).
template <class S, class Term>
S sum_elements(const FlexibleData& f, const std::vector<S>& dofs, const std::vector<char>* touched,
               Term&& term) {
  S sum(0.0);
  for (const BeamElementData& e : f.elements) {
    if (touched && !(*touched)[e.node] && !(*touched)[e.node + 1]) continue;
    sum += term(e, local_dofs(f, e, dofs));
  }
  return sum;
}

double joint_power(const Instance& m, const State& s) {
  double power = 0;
  for (int r = 0; r < m.joint_coordinates(); ++r) {
    const JointData& j = m.joints[m.coordinate_joint[r]];
    power -= j.damping * s.u[r] * s.u[r];
    if (j.actuated) power += s.tau[r] * s.u[r];
  }
  for (const EffortData& f : m.efforts) power += f.at(s.t) * s.u[f.coordinate];
  return power;
}

/// Section resultants at a node, from the element that starts there (the
/// last element for the last node): N (with the nonlinear strain's
/// EA phi when the beam has it), T, M_y, M_z.
std::array<double, 4> resultants(const FlexibleData& f, const std::vector<double>& dofs, int node) {
  const int count = static_cast<int>(f.elements.size());
  const int element = node < count ? node : count - 1;
  const double xi = node < count ? 0.0 : 1.0;
  const BeamElementData& e = f.elements[element];
  const LocalDofs<double> l = local_dofs(f, e, dofs);
  const double L = e.length;
  const std::array<double, 4> hxx = hermite_xx(xi, L);
  // The nonlinear axial strain of geometric stiffening adds its mean bending part.
  const double phi = f.nonlinear_strain() ? shortening_integral(f, e, l, 1.0) / L : 0.0;
  return {f.E * f.A * ((l.translation[1][0] - l.translation[0][0]) / L + phi),
          f.G * f.J * (l.rotation[1][0] - l.rotation[0][0]) / L, -f.E * f.Iy * combine(hxx, w_values(l)),
          f.E * f.Iz * combine(hxx, v_values(l))};
}

/// One output column's value (model/output_columns.hpp). `reaction`: the
/// loop forces at inputs of zero, every loop's rows in order.
double output_value(const Instance& m, const model::OutputColumn& column, const State& s,
                    const std::vector<Pose<double>>& poses, const std::vector<std::vector<double>>& dofs,
                    const std::vector<SecondOrder<double>>& second, const std::vector<double>& reaction) {
  const OutputData& o = m.outputs[column.output];
  switch (o.kind) {
    case model::OutputKind::point_position:
      return point_position(poses, o.body, o.point)[column.component];
    case model::OutputKind::joint_coordinate:
      return s.q[o.coordinate];
    case model::OutputKind::joint_speed:
      return s.u[o.coordinate];
    case model::OutputKind::reaction: {
      std::size_t first = 0;  // the loop's first row
      for (int k = 0; k < o.loop; ++k) first += m.loops[k].rows.size();
      return reaction[first + column.component];
    }
    case model::OutputKind::node_displacement: {
      const FlexibleData& f = *m.bodies[o.body].elastic;
      return sub(displaced_node(f, dofs[o.body], second[o.body], o.node),
                 rest_node(f, o.node))[column.component];
    }
    default:
      break;
  }
  const FlexibleData& f = *m.bodies[o.body].elastic;
  const std::array<double, 4> n4 = resultants(f, dofs[o.body], o.node);  // N, T, M_y, M_z
  if (o.kind == model::OutputKind::axial_force) return n4[0];
  if (o.kind == model::OutputKind::bending_moment) return n4[column.component + 1];  // about y (1), z (2)
  // The bending stress at the extreme fibres.
  double stress = std::abs(n4[0]) / f.A + std::abs(n4[3]) * f.fibre_y / f.Iz;
  if (!f.planar) stress += std::abs(n4[2]) * f.fibre_z / f.Iy;
  return stress;
}

/// The beam's strain energy; with `nonlinear` false, its linear part 1/2 u^T K u.
double strain_energy(const FlexibleData& f, const std::vector<double>& dofs, bool nonlinear = true) {
  double energy = sum_elements(f, dofs, nullptr, [&](const BeamElementData& e, const LocalDofs<double>& l) {
    return strain_energy(f, e, l, nonlinear);
  });
  for (const SolidElementData& e : f.solids) energy += solid_strain_energy(f, e, dofs);
  return energy;
}

/// The beam's kinetic energy at elastic rates `rate` with its link at rest:
/// 1/2 eta_dot^T M_e eta_dot, M_e its own (consistent) mass in eta.
double elastic_kinetic_energy(const FlexibleData& f, const std::vector<double>& rate) {
  std::vector<D1> x(rate.size());
  for (std::size_t k = 0; k < rate.size(); ++k) x[k] = D1(0.0, rate[k]);
  const std::vector<D1> dofs = beam_dofs(f, x.data());
  const GaussRule& rule = mass_rule();
  double energy = 0;
  for (const BeamElementData& e : f.elements) {
    const LocalDofs<D1> l = local_dofs(f, e, dofs);
    for (std::size_t g = 0; g < rule.points.size(); ++g) {
      const double dx = rule.weights[g] * e.length, rho = f.density;
      const Vec<double> v = derivative(beam_point(e, l, rule.points[g]));
      const Vec<double> w = derivative(section_rotation(e, l, rule.points[g]));
      const Mat<double> J = diagonal_in(e.axes, rho * (f.Iy + f.Iz) * dx, rho * f.Iy * dx, rho * f.Iz * dx);
      energy += 0.5 * (rho * f.A * dx * dot(v, v) + dot(w, mul(J, w)));
    }
  }
  for (const SolidElementData& e : f.solids)
    for (const SolidElementData::Point& p : e.points) {
      const Vec<double> v = derivative(solid_point(f, e, p, dofs));
      energy += 0.5 * f.density * p.weight * dot(v, v);
    }
  if (f.tip_mass > 0) {
    const int last = static_cast<int>(f.nodes.size()) - 1;
    const Vec<double> v = derivative(node_translation(f, dofs, last)),
                      w = derivative(node_rotation(f, dofs, last));
    energy += 0.5 * (f.tip_mass * dot(v, v) + dot(w, mul(f.tip_inertia, w)));
  }
  return energy;
}

/// Modal damping C_kk = 2 zeta omega_k M_kk, omega_k^2 = K_kk / M_kk (the
/// modes diagonalise both): 2 zeta sqrt(K_kk M_kk), from this path's own K and M.
std::vector<double> modal_damping(const FlexibleData& f) {
  std::vector<double> c(f.count(), 0.0);
  for (int k = 0; k < f.count(); ++k) {
    std::vector<double> unit(f.count(), 0.0);
    unit[k] = 1;
    const double stiffness = 2 * strain_energy(f, beam_dofs(f, unit.data()), false);
    const double mass = 2 * elastic_kinetic_energy(f, unit);
    c[k] = 2 * f.modal_ratio * std::sqrt(stiffness * mass);
  }
  return c;
}

/// A body's world motion along q(s) = q + s u + s^2/2 udot at s = 0.
struct BodyMotion {
  Mat<double> r, r1;
  Vec<double> p, p2, omega, alpha;  ///< world
};
/// A mass element's: position, velocity, acceleration, the rate and
/// acceleration of its elastic rotation (link frame).
struct ElementMotion {
  Vec<double> x, v, a, theta_rate, theta_accel;
};
struct PathMotion {
  std::vector<std::vector<D2>> dofs;
  std::vector<SecondOrder<D2>> second;  ///< of dofs
  std::vector<Pose<D2>> poses;
  std::vector<BodyMotion> body;
  std::vector<ElementMotion> element;  ///< when asked for
};

/// Along q(s) with both nesting levels seeded with u (the outer one's
/// derivative with udot, zero for the accelerations at u_dot = 0): positions,
/// their rates and accelerations (the inner-outer cross term).
PathMotion motion_along(const Instance& m, const State& s, const std::vector<double>* udot,
                        std::size_t elements, double scale = 1.0) {
  const int n = m.coordinates(), nb = static_cast<int>(m.bodies.size());
  std::vector<D2> x(n);
  for (int k = 0; k < n; ++k) x[k] = D2(D1(s.q[k], s.u[k]), D1(s.u[k], udot ? (*udot)[k] : 0.0));
  PathMotion out;
  out.dofs = all_beam_dofs(m, x.data());
  out.second = all_second_order(m, out.dofs);
  out.poses = body_poses(m, x.data(), out.dofs, out.second);
  out.body.resize(nb);
  for (int b = 0; b < nb; ++b) {
    BodyMotion& k = out.body[b];
    Mat<double> r2;
    for (int i = 0; i < 9; ++i) {
      const D2& e = out.poses[b].rotation[i];
      k.r[i] = e.v.v;
      k.r1[i] = e.d.v;
      r2[i] = e.d.d;
    }
    for (int i = 0; i < 3; ++i) {
      const D2& e = out.poses[b].origin[i];
      k.p[i] = e.v.v;
      k.p2[i] = e.d.d;
    }
    // R' = [w]x R, and R'' = [alpha]x R + [w]x R'.
    const Mat<double> rt = transpose(k.r), spin = mul(k.r1, rt);
    k.omega = vee(spin);
    k.alpha = vee(mul(sub(r2, mul(spin, k.r1)), rt));
  }
  if (elements == 0) return out;
  out.element.resize(elements);
  visit_masses(
      m, out.poses, out.dofs, nullptr,
      [&](int i, int, const Vec<D2>& p, const Vec<D2>& theta) {
        ElementMotion& e = out.element[i];
        for (int a = 0; a < 3; ++a) {
          e.x[a] = p[a].v.v;
          e.v[a] = p[a].d.v;
          e.a[a] = p[a].d.d;
          e.theta_rate[a] = theta[a].d.v;
          e.theta_accel[a] = theta[a].d.d;
        }
      },
      scale);
  return out;
}

/// The derivative of a sum over the (touched) elements of a flexible body,
/// and the sum of the magnitudes of its terms (the scale of its round-off).
template <class Term>
std::pair<double, double> element_gradient(const FlexibleData& f, const std::vector<D1>& dofs,
                                           const std::vector<char>* touched, Term&& term) {
  double sum = 0, magnitude = 0;
  for (const BeamElementData& e : f.elements) {
    if (touched && !(*touched)[e.node] && !(*touched)[e.node + 1]) continue;
    const double d = term(e, local_dofs(f, e, dofs)).d;
    sum += d;
    magnitude += std::abs(d);
  }
  return {sum, magnitude};
}

/// The same for the strain energy of a mesh body's elements.
std::pair<double, double> solid_gradient(const FlexibleData& f, const std::vector<D1>& dofs,
                                         const std::vector<char>* touched) {
  double sum = 0, magnitude = 0;
  for (const SolidElementData& e : f.solids) {
    bool moves = !touched;
    for (int n : e.nodes) moves = moves || (*touched)[n];
    if (!moves) continue;
    const double d = solid_strain_energy(f, e, dofs).d;
    sum += d;
    magnitude += std::abs(d);
  }
  return {sum, magnitude};
}

/// Partial velocities of mass elements (v_r; w_r of their link; W_r with
/// the elastic rotation) and of the forces' points for one coordinate.
struct Partial {
  int r;
  Vec<double> v, w, W;
};
struct Pass {
  std::vector<std::vector<D1>> dofs;
  std::vector<SecondOrder<D1>> second;  ///< of dofs
  Touched touched;
  /// Per spring: dl/dq_r (the spring's generalized force is -tension dl/dq_r),
  /// and |v_r| of its two ends summed (the scale of that term's round-off).
  std::vector<double> spring_slope, spring_reach;
};

/// `elements` may be null (no mass elements visited); `scale` as for visit_masses.
Pass partial_pass(const Instance& m, const State& s, int r, const std::vector<BodyMotion>& motion,
                  std::vector<std::vector<Partial>>* elements, std::vector<std::vector<Vec<double>>>& forces,
                  double scale = 1.0) {
  const int n = m.coordinates(), nb = static_cast<int>(m.bodies.size());
  std::vector<D1> x(n);
  for (int k = 0; k < n; ++k) x[k] = D1(s.q[k], k == r ? 1.0 : 0.0);
  Pass pass;
  pass.dofs = all_beam_dofs(m, x.data());
  pass.second = all_second_order(m, pass.dofs);
  const std::vector<Pose<D1>> poses = body_poses(m, x.data(), pass.dofs, pass.second);
  pass.touched = touched_by(m, poses, pass.dofs);
  const Touched& touched = pass.touched;
  std::vector<Vec<double>> link_rate(nb);  // w_r of each link
  for (int b = 0; b < nb; ++b)
    if (touched.pose[b]) link_rate[b] = vee(mul(derivative(poses[b].rotation), transpose(motion[b].r)));
  if (elements)
    visit_masses(
        m, poses, pass.dofs, &touched,
        [&](int i, int b, const Vec<D1>& p, const Vec<D1>& theta) {
          const Vec<double> v = derivative(p), w = touched.pose[b] ? link_rate[b] : Vec<double>{0, 0, 0};
          const Vec<double> W = add(w, mul(motion[b].r, derivative(theta)));
          if (is_zero(v) && is_zero(W)) return;
          (*elements)[i].push_back({r, v, w, W});
        },
        scale);
  for (std::size_t f = 0; f < m.forces.size(); ++f)
    forces[f][r] = derivative(force_point(m, m.forces[f], poses, pass.dofs, pass.second));
  for (const SpringData& spring : m.springs) {
    const Vec<D1> d = spring_vector(spring, poses);
    pass.spring_slope.push_back(sqrt(dot(d, d)).d);
    const Vec<double> v1 = derivative(point_position(poses, spring.body, spring.point));
    const Vec<double> v2 = derivative(point_position(poses, spring.body2, spring.point2));
    pass.spring_reach.push_back(std::sqrt(dot(v1, v1)) + std::sqrt(dot(v2, v2)));
  }
  return pass;
}

/// Kane's terms of one mass element, moving as `x` (accelerations at u_dot
/// = 0, or at a given udot), on the rows of its partial velocities: adds
/// v_r.m (g - a) - W_r.I (alpha + R theta'') - w_r.(omega x I Omega) to
/// forcing[r]; with `mass_matrix`, m v_r.v_s + W_r.I W_s to M.
void add_element(const Instance& m, const MassElement& el, const BodyMotion& k, const ElementMotion& x,
                 const std::vector<Partial>& p, std::vector<double>& forcing,
                 std::vector<double>* mass_matrix, Eigen::MatrixXd* own_mass,
                 std::vector<double>* magnitude = nullptr, std::vector<double>* gravity = nullptr,
                 std::vector<double>* gravity_magnitude = nullptr) {
  const int n = m.coordinates();
  const Mat<double> inertia = mul(k.r, mul(el.inertia, transpose(k.r)));  // world axes
  const Vec<double> spin = add(k.omega, mul(k.r, x.theta_rate));          // Omega
  const Vec<double> force = scale(sub(m.gravity, x.a), el.mass);
  const Vec<double> torque = mul(inertia, add(k.alpha, mul(k.r, x.theta_accel)));
  const Vec<double> gyroscopic = cross(k.omega, mul(inertia, spin));
  const auto norm = [](const Vec<double>& x) { return std::sqrt(dot(x, x)); };
  const Vec<double> weight = scale(m.gravity, el.mass);
  for (const Partial& a : p) {
    forcing[a.r] += dot(a.v, force) - dot(a.W, torque) - dot(a.w, gyroscopic);
    // The generalized gravity force's sign is that of M udot + C u + g = tau.
    if (gravity) (*gravity)[a.r] -= dot(a.v, weight);
    if (gravity_magnitude) (*gravity_magnitude)[a.r] += norm(a.v) * norm(weight);
    // |a||b| bounds the round-off of a.b however it is grouped (as moments r x F, say).
    if (magnitude)
      (*magnitude)[a.r] += norm(a.v) * norm(force) + norm(a.W) * norm(torque) + norm(a.w) * norm(gyroscopic);
  }
  if (!mass_matrix) return;
  const BodyData& body = m.bodies[el.body];
  const int first = body.elastic_first, count = body.elastic ? body.elastic->count() : 0;
  std::vector<Vec<double>> iw(p.size());
  for (std::size_t a = 0; a < p.size(); ++a) iw[a] = mul(inertia, p[a].W);
  for (std::size_t a = 0; a < p.size(); ++a)
    for (std::size_t c = 0; c < p.size(); ++c) {
      const double entry = el.mass * dot(p[a].v, p[c].v) + dot(p[a].W, iw[c]);
      (*mass_matrix)[p[a].r * n + p[c].r] += entry;
      const int ka = p[a].r - first, kc = p[c].r - first;
      if (own_mass && count && ka >= 0 && ka < count && kc >= 0 && kc < count) (*own_mass)(ka, kc) += entry;
    }
}

/// The joint terms of row r: spring, damper, input.
double joint_forcing(const Instance& m, const State& s, int r) {
  if (r >= m.joint_coordinates()) return 0;
  const JointData& j = m.joints[m.coordinate_joint[r]];
  double effort = 0;
  for (const EffortData& f : m.efforts)
    if (f.coordinate == r) effort += f.at(s.t);
  return -j.stiffness * (s.q[r] - j.rest) - j.damping * s.u[r] + (j.actuated ? s.tau[r] : 0.0) + effort;
}

/// The power of the beams' damping forces, -eta_dot^T C eta_dot.
double beam_power(const Instance& m, const State& s) {
  double power = 0;
  for (std::size_t b = 0; b < m.bodies.size(); ++b) {
    if (!m.bodies[b].elastic) continue;
    const FlexibleData& f = *m.bodies[b].elastic;
    const int first = m.bodies[b].elastic_first;
    const std::vector<double> rate(s.u.begin() + first, s.u.begin() + first + f.count());
    if (f.modal_ratio > 0) {
      const std::vector<double> c = modal_damping(f);
      for (int k = 0; k < f.count(); ++k) power -= c[k] * rate[k] * rate[k];
    } else {
      if (f.rayleigh_alpha != 0) power -= f.rayleigh_alpha * 2 * elastic_kinetic_energy(f, rate);
      if (f.rayleigh_beta != 0)
        power -= f.rayleigh_beta * 2 * strain_energy(f, beam_dofs(f, rate.data()), false);
    }
  }
  return power;
}

/// One value of the scale of the beams' own dofs, and its weight.
struct Sample {
  double scale, weight;
};

/// The mass elements of a beam enter Kane's sums to the order the generator
/// keeps (kane/flexible_body.cpp): the terms of the kinetic energy up to
/// second order in the beam's own elastic coordinates and rates, which give
/// the joint rows to second order and the elastic rows to first. With its
/// own dofs scaled by s, an element's share of M, f, T and V is a polynomial
/// in s; the sum of its coefficients of degree 0 to 2 is that share. Without
/// foreshortening the positions are linear in the dofs and the shares of
/// degree <= 2 already: one pass at s = 1. With it they are of degree <= 4,
/// and the kept sum is taken exactly from five values of s.
std::vector<Sample> truncation_samples(const Instance& m) {
  bool stiffening = false;
  for (const BodyData& b : m.bodies) stiffening = stiffening || (b.elastic && b.elastic->shortens());
  if (!stiffening) return {{1.0, 1.0}};
  static const std::vector<Sample> samples = [] {
    const double s[5] = {-1.0, -0.5, 0.0, 0.5, 1.0};
    Eigen::Matrix<double, 5, 5> vandermonde;  // share(s_i) = sum_d c_d s_i^d
    for (int i = 0; i < 5; ++i)
      for (int d = 0; d < 5; ++d) vandermonde(i, d) = std::pow(s[i], d);
    Eigen::Matrix<double, 5, 1> keep;
    keep << 1, 1, 1, 0, 0;
    // c0 + c1 + c2 = keep^T V^-1 shares = w^T shares with V^T w = keep.
    const Eigen::Matrix<double, 5, 1> w = vandermonde.transpose().fullPivLu().solve(keep);
    std::vector<Sample> out;
    for (int i = 0; i < 5; ++i) out.push_back({s[i], w[i]});
    return out;
  }();
  return samples;
}

/// Kane's sums over the mass elements, truncated as truncation_samples says:
/// the forcing (with the inertia forces at `udot`, or at u_dot = 0 if null)
/// of the rows `rows`, and with `all` also M, the beams' own elastic mass
/// blocks and the kinetic and potential energies.
struct ElementSums {
  std::vector<double> forcing, magnitude, mass_matrix, gravity, gravity_magnitude;
  std::vector<Eigen::MatrixXd> own_mass;
  double kinetic = 0, potential = 0;
};

ElementSums element_sums(const Instance& m, const State& s, const std::vector<MassElement>& elements,
                         const std::vector<int>& rows, const std::vector<double>* udot, bool all) {
  const int n = m.coordinates(), nb = static_cast<int>(m.bodies.size());
  ElementSums out;
  out.forcing.assign(n, 0.0);
  out.magnitude.assign(n, 0.0);
  out.gravity.assign(n, 0.0);
  out.gravity_magnitude.assign(n, 0.0);
  if (all) {
    out.mass_matrix.assign(static_cast<std::size_t>(n) * n, 0.0);
    out.own_mass.resize(nb);
    for (int b = 0; b < nb; ++b)
      if (m.bodies[b].elastic)
        out.own_mass[b] = Eigen::MatrixXd::Zero(m.bodies[b].elastic->count(), m.bodies[b].elastic->count());
  }
  for (const Sample& sample : truncation_samples(m)) {
    const PathMotion motion = motion_along(m, s, udot, elements.size(), sample.scale);
    std::vector<std::vector<Partial>> partials(elements.size());
    std::vector<std::vector<Vec<double>>> force_partials(m.forces.size(), std::vector<Vec<double>>(n));
    for (int r : rows) partial_pass(m, s, r, motion.body, &partials, force_partials, sample.scale);
    ElementSums share;
    share.forcing.assign(n, 0.0);
    share.magnitude.assign(n, 0.0);
    share.gravity.assign(n, 0.0);
    share.gravity_magnitude.assign(n, 0.0);
    if (all) share.mass_matrix.assign(static_cast<std::size_t>(n) * n, 0.0);
    std::vector<Eigen::MatrixXd> own = out.own_mass;
    for (auto& block : own) block.setZero();
    for (std::size_t i = 0; i < elements.size(); ++i) {
      const MassElement& el = elements[i];
      const BodyMotion& k = motion.body[el.body];
      const ElementMotion& x = motion.element[i];
      add_element(m, el, k, x, partials[i], share.forcing, all ? &share.mass_matrix : nullptr,
                  all && m.bodies[el.body].elastic ? &own[el.body] : nullptr, &share.magnitude,
                  &share.gravity, &share.gravity_magnitude);
      if (!all) continue;
      const Mat<double> inertia = mul(k.r, mul(el.inertia, transpose(k.r)));
      const Vec<double> spin = add(k.omega, mul(k.r, x.theta_rate));
      share.kinetic += 0.5 * (el.mass * dot(x.v, x.v) + dot(spin, mul(inertia, spin)));
      share.potential -= el.mass * dot(m.gravity, x.x);
    }
    const double w = sample.weight;
    for (int r = 0; r < n; ++r) {
      out.forcing[r] += w * share.forcing[r];
      out.magnitude[r] += std::abs(w) * share.magnitude[r];
      out.gravity[r] += w * share.gravity[r];
      out.gravity_magnitude[r] += std::abs(w) * share.gravity_magnitude[r];
    }
    if (!all) continue;
    for (std::size_t i = 0; i < out.mass_matrix.size(); ++i) out.mass_matrix[i] += w * share.mass_matrix[i];
    for (int b = 0; b < nb; ++b)
      if (own[b].size()) out.own_mass[b] += w * own[b];
    out.kinetic += w * share.kinetic;
    out.potential += w * share.potential;
  }
  return out;
}

/// The beams' dofs at q, the values of the motion's.
std::vector<std::vector<double>> dofs_at_q(const PathMotion& motion) {
  std::vector<std::vector<double>> dofs(motion.dofs.size());
  for (std::size_t b = 0; b < motion.dofs.size(); ++b)
    for (const D2& x : motion.dofs[b]) dofs[b].push_back(x.v.v);
  return dofs;
}

/// The flexible body of each elastic coordinate, -1 for a joint coordinate.
std::vector<int> elastic_owners(const Instance& m) {
  std::vector<int> owner(m.coordinates(), -1);
  for (std::size_t b = 0; b < m.bodies.size(); ++b)
    if (m.bodies[b].elastic)
      for (int k = 0; k < m.bodies[b].elastic->count(); ++k)
        owner[m.bodies[b].elastic_first + k] = static_cast<int>(b);
  return owner;
}

/// The partial velocities of the forces' points and the springs, from the
/// passes seeded with each coordinate's unit vector e_r.
struct CoordinatePartials {
  std::vector<std::vector<Vec<double>>> force;                  ///< per force, per coordinate
  std::vector<std::vector<double>> spring_slope, spring_reach;  ///< per coordinate, per spring (see Pass)
};

/// The elastic forces of coordinate r of body b from the gradients of the
/// beam's energies along e_r: -dU/deta_r into f, the Rayleigh stiffness
/// damping -beta (K eta_dot)_r into `nonconservative`.
void add_elastic_gradients(const Instance& m, const State& s, int r, int b, const Pass& pass, Evaluation& e,
                           std::vector<double>& nonconservative) {
  const FlexibleData& f = *m.bodies[b].elastic;
  const std::vector<char>* nodes = &pass.touched.node[b];
  const auto strain = element_gradient(
      f, pass.dofs[b], nodes,
      [&](const BeamElementData& el, const LocalDofs<D1>& l) { return strain_energy(f, el, l); });
  const auto solid = solid_gradient(f, pass.dofs[b], nodes);
  e.forcing[r] -= strain.first + solid.first;
  e.forcing_magnitude[r] += strain.second + solid.second;
  if (f.rayleigh_beta == 0) return;
  std::vector<D1> rate(f.count());
  const int first = m.bodies[b].elastic_first;
  for (int k = 0; k < f.count(); ++k) rate[k] = D1(s.u[first + k], first + k == r ? 1.0 : 0.0);
  const auto k_rate = element_gradient(
      f, beam_dofs(f, rate.data()), nodes,
      [&](const BeamElementData& el, const LocalDofs<D1>& l) { return strain_energy(f, el, l, false); });
  const auto solid_rate = solid_gradient(f, beam_dofs(f, rate.data()), nodes);
  nonconservative[r] -= f.rayleigh_beta * (k_rate.first + solid_rate.first);
  e.forcing_magnitude[r] += f.rayleigh_beta * (k_rate.second + solid_rate.second);
}

/// One pass per coordinate seeded with e_r: the forces' and springs'
/// partial velocities, and the elastic forces of an elastic coordinate.
CoordinatePartials coordinate_passes(const Instance& m, const State& s, const PathMotion& motion,
                                     Evaluation& e, std::vector<double>& nonconservative) {
  const int n = m.coordinates();
  CoordinatePartials out;
  out.force.assign(m.forces.size(), std::vector<Vec<double>>(n));
  out.spring_slope.resize(n);
  out.spring_reach.resize(n);
  const std::vector<int> owner = elastic_owners(m);
  for (int r = 0; r < n; ++r) {
    const Pass pass = partial_pass(m, s, r, motion.body, nullptr, out.force);
    out.spring_slope[r] = pass.spring_slope;
    out.spring_reach[r] = pass.spring_reach;
    if (owner[r] >= 0) add_elastic_gradients(m, s, r, owner[r], pass, e, nonconservative);
  }
  return out;
}

/// Kane's sums over the mass elements into M, f, T and V. Returns each
/// beam's own elastic mass block (for its Rayleigh damping alpha M).
std::vector<Eigen::MatrixXd> add_mass_elements(const Instance& m, const State& s, Evaluation& e) {
  const int n = m.coordinates();
  std::vector<int> rows(n);
  for (int r = 0; r < n; ++r) rows[r] = r;
  ElementSums sums = element_sums(m, s, mass_elements(m), rows, nullptr, true);
  for (int r = 0; r < n; ++r) {
    e.forcing[r] += sums.forcing[r];
    e.forcing_magnitude[r] += sums.magnitude[r];
  }
  e.mass_matrix = sums.mass_matrix;
  e.gravity = sums.gravity;
  e.gravity_magnitude = sums.gravity_magnitude;
  e.kinetic_energy += sums.kinetic;
  e.potential_energy += sums.potential;
  return std::move(sums.own_mass);
}

/// The solid points of a mesh body at its coordinates `eta`, link frame:
/// p(eta) = X + N (B eta + u2) (dual numbers carry derivatives along eta).
template <class S>
std::vector<Vec<S>> solid_points(const FlexibleData& f, const std::vector<S>& eta) {
  const std::vector<S> dofs = beam_dofs(f, eta.data());
  const std::vector<S> u2 = second_order_displacement(f, dofs);
  std::vector<Vec<S>> out;
  for (const SolidElementData& e : f.solids)
    for (const SolidElementData::Point& p : e.points) out.push_back(solid_point(f, e, p, dofs, u2));
  return out;
}

/// A mesh body's points moving relative to its link, past the second order
/// in (eta, eta_dot) that element_sums keeps. Their kinetic energy
/// T_rel = 1/2 sum m |dp/dt|^2 depends on eta and eta_dot alone; its
/// Lagrange equations are sum m p_k . (sum_l p_l eta_ddot_l + p''), p_k =
/// dp/deta_k and p'' the second derivative of p along eta_dot. element_sums
/// has its share of second order, sum m p_k(0) . p_l(0) in M and nothing
/// in f; this adds the rest: M_kl += sum m (p_k . p_l - p_k(0) . p_l(0)),
/// f_k -= sum m p_k . p'', T += 1/2 eta_dot^T (that change of M) eta_dot.
void add_relative_inertia(const Instance& m, const State& s, Evaluation& e) {
  const int n_all = m.coordinates();
  for (const BodyData& body : m.bodies) {
    if (!body.elastic || !body.elastic->mesh || !body.elastic->shortens()) continue;
    const FlexibleData& f = *body.elastic;
    const int n = f.count(), first = body.elastic_first;
    std::vector<double> masses;
    for (const SolidElementData& el : f.solids)
      for (const SolidElementData::Point& p : el.points) masses.push_back(f.density * p.weight);
    // p_k at eta and at 0, per point: [k][point].
    const auto partials = [&](bool at_rest) {
      std::vector<std::vector<Vec<double>>> out;
      for (int k = 0; k < n; ++k) {
        std::vector<D1> eta(n);
        for (int i = 0; i < n; ++i) eta[i] = D1(at_rest ? 0.0 : s.q[first + i], i == k ? 1.0 : 0.0);
        std::vector<Vec<double>> column;
        for (const Vec<D1>& x : solid_points(f, eta)) column.push_back(derivative(x));
        out.push_back(std::move(column));
      }
      return out;
    };
    const auto moving = partials(false), rest = partials(true);
    std::vector<D2> along(n);  // eta + t eta_dot, twice differentiated in t
    for (int i = 0; i < n; ++i) along[i] = D2(D1(s.q[first + i], s.u[first + i]), D1(s.u[first + i], 0.0));
    std::vector<Vec<double>> accel;
    for (const Vec<D2>& x : solid_points(f, along)) accel.push_back({x[0].d.d, x[1].d.d, x[2].d.d});
    Eigen::MatrixXd change = Eigen::MatrixXd::Zero(n, n);
    for (std::size_t p = 0; p < masses.size(); ++p) {
      for (int k = 0; k < n; ++k) {
        for (int l = 0; l < n; ++l)
          change(k, l) += masses[p] * (dot(moving[k][p], moving[l][p]) - dot(rest[k][p], rest[l][p]));
        const double term = masses[p] * dot(moving[k][p], accel[p]);
        e.forcing[first + k] -= term;
        e.forcing_magnitude[first + k] += std::abs(term);
      }
    }
    for (int k = 0; k < n; ++k)
      for (int l = 0; l < n; ++l) {
        e.mass_matrix[static_cast<std::size_t>(first + k) * n_all + first + l] += change(k, l);
        e.kinetic_energy += 0.5 * s.u[first + k] * change(k, l) * s.u[first + l];
      }
  }
}

/// The beams: strain energy into V; Rayleigh alpha M or modal damping into `nonconservative`.
void add_beams(const Instance& m, const State& s, const std::vector<std::vector<double>>& dofs,
               const std::vector<Eigen::MatrixXd>& own_mass, Evaluation& e,
               std::vector<double>& nonconservative) {
  for (std::size_t b = 0; b < m.bodies.size(); ++b) {
    if (!m.bodies[b].elastic) continue;
    const FlexibleData& f = *m.bodies[b].elastic;
    const int first = m.bodies[b].elastic_first;
    e.potential_energy += strain_energy(f, dofs[b]);
    const std::vector<double> modal = f.modal_ratio > 0 ? modal_damping(f) : std::vector<double>();
    for (int k = 0; k < f.count(); ++k) {
      double damping = modal.empty() ? 0.0 : modal[k] * s.u[first + k];
      double magnitude = std::abs(damping);
      if (f.rayleigh_alpha != 0)
        for (int c = 0; c < f.count(); ++c) {
          damping += f.rayleigh_alpha * own_mass[b](k, c) * s.u[first + c];
          magnitude += std::abs(f.rayleigh_alpha * own_mass[b](k, c) * s.u[first + c]);
        }
      nonconservative[first + k] -= damping;
      e.forcing_magnitude[first + k] += magnitude;
    }
  }
}

/// The beams' damping forces into f, and their power.
void add_beam_damping(const State& s, const std::vector<double>& nonconservative, Evaluation& e) {
  for (std::size_t r = 0; r < nonconservative.size(); ++r) {
    e.forcing[r] += nonconservative[r];
    e.nonconservative_power += nonconservative[r] * s.u[r];
  }
}

/// Point forces: F.v_r on each row; a world force's potential -F.p, a body force's power.
void add_point_forces(const Instance& m, const PathMotion& motion, const CoordinatePartials& partials,
                      Evaluation& e) {
  for (std::size_t i = 0; i < m.forces.size(); ++i) {
    const ForceData& f = m.forces[i];
    const std::vector<Vec<double>>& partial = partials.force[i];
    const Vec<double> force = f.body_frame ? mul(motion.body[f.body].r, f.force) : f.force;
    for (int r = 0; r < e.n; ++r) {
      e.forcing[r] += dot(force, partial[r]);
      e.forcing_magnitude[r] += std::sqrt(dot(force, force) * dot(partial[r], partial[r]));
    }
    const Vec<D2> at = force_point(m, f, motion.poses, motion.dofs, motion.second);
    if (f.body_frame) {
      e.nonconservative_power += dot(force, Vec<double>{at[0].d.v, at[1].d.v, at[2].d.v});
    } else {
      e.potential_energy -= dot(force, Vec<double>{at[0].v.v, at[1].v.v, at[2].v.v});
    }
  }
}

/// Springs: -tension dl/dq_r on each row; their energy; the damper's power -c l_dot^2.
void add_springs(const Instance& m, const PathMotion& motion, const CoordinatePartials& partials,
                 Evaluation& e) {
  for (std::size_t i = 0; i < m.springs.size(); ++i) {
    const SpringData& spring = m.springs[i];
    const SpringState st = spring_state(spring, motion.poses);
    for (int r = 0; r < e.n; ++r) {
      e.forcing[r] -= st.tension * partials.spring_slope[r][i];
      e.forcing_magnitude[r] += std::abs(st.tension) * partials.spring_reach[r][i];
    }
    const double stretch = st.length - spring.rest_length;
    e.potential_energy += 0.5 * spring.stiffness * stretch * stretch;
    e.nonconservative_power -= spring.damping * st.rate * st.rate;
  }
}

/// The joints: spring, damper, input and efforts on their rows, the springs'
/// energy and the power; the prescribed speeds and their accelerations at t.
void add_joints(const Instance& m, const State& s, Evaluation& e) {
  for (int r = 0; r < m.joint_coordinates(); ++r) {
    const JointData& j = m.joints[m.coordinate_joint[r]];
    const double stretch = s.q[r] - j.rest;
    e.forcing[r] += joint_forcing(m, s, r);
    e.forcing_magnitude[r] += std::abs(j.stiffness * stretch) + std::abs(j.damping * s.u[r]) +
                              (j.actuated ? std::abs(s.tau[r]) : 0.0);
    for (const EffortData& f : m.efforts)
      if (f.coordinate == r) e.forcing_magnitude[r] += std::abs(f.at(s.t));
    e.potential_energy += 0.5 * j.stiffness * stretch * stretch;
    if (j.is_prescribed()) {
      e.prescribed.push_back(r);
      e.prescribed_acceleration.push_back(prescribed_motion(j, s.t)[2]);
    }
  }
  e.nonconservative_power += joint_power(m, s);
}

/// The speeds that are solved for: all but the prescribed.
std::vector<int> free_speeds(const Evaluation& e) {
  std::vector<char> given(e.n, 0);
  for (int p : e.prescribed) given[p] = 1;
  std::vector<int> free;
  for (int r = 0; r < e.n; ++r)
    if (!given[r]) free.push_back(r);
  return free;
}

/// A tree's udot: the prescribed accelerations, the rest from
/// M_ff udot_f = f_f - M_fp udot_p; left empty if M_ff is not positive definite.
void solve_tree(Evaluation& e) {
  const int n = e.n;
  std::vector<double> udot(n, 0.0);
  for (std::size_t p = 0; p < e.prescribed.size(); ++p) udot[e.prescribed[p]] = e.prescribed_acceleration[p];
  const std::vector<int> free = free_speeds(e);
  const int nf = static_cast<int>(free.size());
  Eigen::MatrixXd mff(nf, nf);
  Eigen::VectorXd rhs(nf);
  for (int a = 0; a < nf; ++a) {
    rhs[a] = e.forcing[free[a]];
    for (int p : e.prescribed) rhs[a] -= e.mass_matrix[free[a] * n + p] * udot[p];
    for (int c = 0; c < nf; ++c) mff(a, c) = e.mass_matrix[free[a] * n + free[c]];
  }
  const Eigen::LLT<Eigen::MatrixXd> llt(mff);
  if (llt.info() != Eigen::Success) return;
  const Eigen::VectorXd x = llt.solve(rhs);
  for (int a = 0; a < nf; ++a) udot[free[a]] = x[a];
  e.udot = udot;
}

/// Closed loops: Phi, C, gamma; udot and lambda of the constrained system
/// and the loop forces' power. Returns the reactions, lambda at inputs of
/// zero (NaN where not solved), for the reaction outputs.
std::vector<double> solve_loops(const Instance& m, const State& s, Evaluation& e) {
  const int n = e.n;
  const LoopKinematics loops = loop_kinematics(m, s.q, s.u);
  e.phi = loops.phi;
  e.constraint_jacobian = loops.jacobian;
  e.constraint_bias = loops.bias;
  const ConstrainedSolution solved =
      solve_constrained(n, e.mass_matrix, e.forcing, loops, e.prescribed, e.prescribed_acceleration);
  if (solved.ok) {
    e.udot = solved.udot;
    e.lambda = solved.lambda;
    for (int r : free_speeds(e))
      for (std::size_t i = 0; i < e.lambda.size(); ++i)
        e.loop_power += e.lambda[i] * loops.jacobian[i * n + r] * s.u[r];
    e.nonconservative_power += e.loop_power;
  }
  std::vector<double> unforced = e.forcing;
  for (int r = 0; r < m.joint_coordinates(); ++r)
    if (m.joints[m.coordinate_joint[r]].actuated) unforced[r] -= s.tau[r];
  const ConstrainedSolution at_rest =
      solve_constrained(n, e.mass_matrix, unforced, loops, e.prescribed, e.prescribed_acceleration);
  return at_rest.ok ? at_rest.lambda : std::vector<double>(loops.phi.size(), std::nan(""));
}

/// The power of the constraint forces that hold the prescribed speeds on
/// their motion, lambda_p = (M udot - f)_p, with this udot.
void add_prescribed_power(const State& s, Evaluation& e) {
  if (e.udot.empty()) return;
  for (int p : e.prescribed) {
    double lambda = -e.forcing[p];
    for (int c = 0; c < e.n; ++c) lambda += e.mass_matrix[p * e.n + c] * e.udot[c];
    e.nonconservative_power += lambda * s.u[p];
  }
}

}  // namespace

Evaluation evaluate(const Instance& m, const State& s) {
  check_sizes(m, s);
  const int n = m.coordinates();
  Evaluation e;
  e.n = n;
  e.forcing.assign(n, 0.0);
  e.forcing_magnitude.assign(n, 0.0);
  const PathMotion motion = motion_along(m, s, nullptr, 0);
  const std::vector<std::vector<double>> dofs = dofs_at_q(motion);

  // Each step adds its terms to f (and its magnitude), the energies and the
  // power in turn; the order is that of the sums' round-off.
  std::vector<double> nonconservative(n, 0.0);  // the beams' damping forces
  const CoordinatePartials partials = coordinate_passes(m, s, motion, e, nonconservative);
  const std::vector<Eigen::MatrixXd> own_mass = add_mass_elements(m, s, e);
  add_relative_inertia(m, s, e);
  add_beams(m, s, dofs, own_mass, e, nonconservative);
  add_beam_damping(s, nonconservative, e);
  add_point_forces(m, motion, partials, e);
  add_springs(m, motion, partials, e);
  add_joints(m, s, e);

  std::vector<double> reaction;
  if (m.loops.empty())
    solve_tree(e);
  else
    reaction = solve_loops(m, s, e);
  add_prescribed_power(s, e);

  std::vector<Pose<double>> poses(m.bodies.size());
  for (std::size_t b = 0; b < poses.size(); ++b) poses[b] = {motion.body[b].r, motion.body[b].p};
  const std::vector<SecondOrder<double>> second = all_second_order(m, dofs);
  for (const model::OutputColumn& column : m.output_columns)
    e.outputs.push_back(output_value(m, column, s, poses, dofs, second, reaction));
  return e;
}

namespace {

/// The power of the applied non-conservative forces (joint dampers, inputs
/// and efforts, the beams' damping, body-frame forces, the dampers of
/// springs) along `motion`; its spring states for the caller.
double applied_power(const Instance& m, const State& s, const PathMotion& motion,
                     std::vector<SpringState>& springs) {
  double power = joint_power(m, s);
  if (m.has_flexible()) power += beam_power(m, s);
  for (const ForceData& f : m.forces) {
    if (!f.body_frame) continue;
    const Vec<D2> at = force_point(m, f, motion.poses, motion.dofs, motion.second);
    power += dot(mul(motion.body[f.body].r, f.force), Vec<double>{at[0].d.v, at[1].d.v, at[2].d.v});
  }
  for (const SpringData& spring : m.springs) {
    springs.push_back(spring_state(spring, motion.poses));
    power -= spring.damping * springs.back().rate * springs.back().rate;
  }
  return power;
}

}  // namespace

double applied_power(const Instance& m, const State& s) {
  check_sizes(m, s);
  std::vector<SpringState> springs;
  return applied_power(m, s, motion_along(m, s, nullptr, 0), springs);
}

double nonconservative_power(const Instance& m, const State& s, const std::vector<double>* udot) {
  check_sizes(m, s);
  if ((m.has_prescribed() || !m.loops.empty()) && !udot) return evaluate(m, s).nonconservative_power;
  const int n = m.coordinates();
  double power = 0;
  // The loop forces' power needs lambda, from the whole evaluation (loops are small models).
  if (!m.loops.empty()) power += evaluate(m, s).loop_power;
  // The motion at the given udot (for the prescribed speeds' constraint forces).
  const std::vector<double>* full = m.has_prescribed() ? udot : nullptr;
  const PathMotion motion = motion_along(m, s, full, 0);
  std::vector<SpringState> springs;
  power += applied_power(m, s, motion, springs);
  // A prescribed speed's constraint force: lambda_p = (M udot - f)_p, minus
  // the generalized force with the inertia forces at udot.
  std::vector<int> prescribed;
  for (int r = 0; r < m.joint_coordinates(); ++r)
    if (m.joints[m.coordinate_joint[r]].is_prescribed()) prescribed.push_back(r);
  if (prescribed.empty()) return power;
  const ElementSums inertia = element_sums(m, s, mass_elements(m), prescribed, full, false);
  for (int r : prescribed) {
    std::vector<std::vector<Vec<double>>> force_partials(m.forces.size(), std::vector<Vec<double>>(n));
    const Pass pass = partial_pass(m, s, r, motion.body, nullptr, force_partials);
    double forcing = inertia.forcing[r];
    for (std::size_t i = 0; i < m.springs.size(); ++i) forcing -= springs[i].tension * pass.spring_slope[i];
    for (std::size_t i = 0; i < m.forces.size(); ++i) {
      const ForceData& f = m.forces[i];
      forcing += dot(f.body_frame ? mul(motion.body[f.body].r, f.force) : f.force, force_partials[i][r]);
    }
    forcing += joint_forcing(m, s, r);
    power -= forcing * s.u[r];
  }
  return power;
}

}  // namespace kanegen::numeric
