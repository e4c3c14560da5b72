#include "numeric/dynamics.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <stdexcept>

#include "numeric/dual.hpp"
#include "numeric/poses.hpp"

namespace kanegen::numeric {
namespace {

using D1 = Dual<double>;
using D2 = Dual<D1>;

void check_sizes(const Instance& m, const State& s) {
  const std::size_t n = static_cast<std::size_t>(m.coordinates());
  if (s.q.size() != n || s.u.size() != n || s.tau.size() != n)
    throw std::invalid_argument("numeric::evaluate: expected " + std::to_string(n) +
                                " coordinates, speeds and inputs");
}

/// Pose derivatives with respect to one coordinate.
struct PoseRate {
  std::vector<Mat<double>> rotation;
  std::vector<Vec<double>> origin;
};

/// d(pose)/dq_r of every body.
PoseRate partial(const Instance& m, const std::vector<double>& q, int r) {
  std::vector<D1> x(q.size());
  for (std::size_t k = 0; k < q.size(); ++k) x[k] = D1(q[k], static_cast<int>(k) == r ? 1.0 : 0.0);
  const std::vector<Pose<D1>> poses = body_poses(m, x.data());
  PoseRate rate;
  for (const Pose<D1>& p : poses) {
    Mat<double> dr;
    Vec<double> dp;
    for (int i = 0; i < 9; ++i) dr[i] = p.rotation[i].d;
    for (int i = 0; i < 3; ++i) dp[i] = p.origin[i].d;
    rate.rotation.push_back(dr);
    rate.origin.push_back(dp);
  }
  return rate;
}

/// A pose with its first and second derivatives along q(s) = q + s u at s = 0:
/// the velocity and the acceleration at u_dot = 0.
struct Motion2 {
  Mat<double> r, r1, r2;
  Vec<double> p, p1, p2;
};

std::vector<Motion2> motion_along_u(const Instance& m, const State& s) {
  // Seeding both nesting levels with u makes the inner-outer cross term the second derivative.
  std::vector<D2> x(s.q.size());
  for (std::size_t k = 0; k < s.q.size(); ++k) x[k] = D2(D1(s.q[k], s.u[k]), D1(s.u[k], 0.0));
  const std::vector<Pose<D2>> poses = body_poses(m, x.data());
  std::vector<Motion2> out(poses.size());
  for (std::size_t b = 0; b < poses.size(); ++b) {
    for (int i = 0; i < 9; ++i) {
      const D2& e = poses[b].rotation[i];
      out[b].r[i] = e.v.v;
      out[b].r1[i] = e.d.v;
      out[b].r2[i] = e.d.d;
    }
    for (int i = 0; i < 3; ++i) {
      const D2& e = poses[b].origin[i];
      out[b].p[i] = e.v.v;
      out[b].p1[i] = e.d.v;
      out[b].p2[i] = e.d.d;
    }
  }
  return out;
}

/// Velocity of a body point along q + s u (first derivative only).
std::vector<Pose<D1>> poses_along_u(const Instance& m, const State& s) {
  std::vector<D1> x(s.q.size());
  for (std::size_t k = 0; k < s.q.size(); ++k) x[k] = D1(s.q[k], s.u[k]);
  return body_poses(m, x.data());
}

Vec<double> point_velocity(const Pose<D1>& pose, const Vec<double>& local) {
  const Vec<D1> x = add(pose.origin, mul(pose.rotation, local));
  return {x[0].d, x[1].d, x[2].d};
}

double joint_power(const Instance& m, const State& s) {
  double power = 0;
  for (int r = 0; r < m.coordinates(); ++r) {
    const JointData& j = m.joints[m.coordinate_joint[r]];
    power -= j.damping * s.u[r] * s.u[r];
    if (j.actuated) power += s.tau[r] * s.u[r];
  }
  return power;
}

}  // namespace

Evaluation evaluate(const Instance& m, const State& s) {
  check_sizes(m, s);
  const int n = m.coordinates();
  Evaluation e;
  e.n = n;
  e.mass_matrix.assign(static_cast<std::size_t>(n) * n, 0.0);
  e.forcing.assign(n, 0.0);

  std::vector<PoseRate> rates;
  for (int r = 0; r < n; ++r) rates.push_back(partial(m, s.q, r));
  const std::vector<Motion2> motion = motion_along_u(m, s);

  std::vector<Vec<double>> v(n), w(n), iw(n);  // per body: partial velocities of the COM, I w_r
  for (std::size_t b = 0; b < m.bodies.size(); ++b) {
    const BodyData& body = m.bodies[b];
    const Motion2& k = motion[b];
    const Mat<double> rt = transpose(k.r);
    const Mat<double> inertia = mul(k.r, mul(body.inertia, rt));  // world axes
    const Vec<double> com = add(k.p, mul(k.r, body.com));
    const Vec<double> com_velocity = add(k.p1, mul(k.r1, body.com));
    const Vec<double> com_accel = add(k.p2, mul(k.r2, body.com));
    // R' = [w]x R, and R'' = [alpha]x R + [w]x R'.
    const Mat<double> spin = mul(k.r1, rt);
    const Vec<double> omega = vee(spin);
    const Vec<double> alpha = vee(mul(sub(k.r2, mul(spin, k.r1)), rt));
    const Vec<double> momentum = mul(inertia, omega);

    const Vec<double> force = scale(sub(m.gravity, com_accel), body.mass);
    const Vec<double> torque = sub(scale(mul(inertia, alpha), -1.0), cross(omega, momentum));
    for (int r = 0; r < n; ++r) {
      v[r] = add(rates[r].origin[b], mul(rates[r].rotation[b], body.com));
      w[r] = vee(mul(rates[r].rotation[b], rt));
      iw[r] = mul(inertia, w[r]);
      e.forcing[r] += dot(v[r], force) + dot(w[r], torque);
    }
    for (int r = 0; r < n; ++r)
      for (int c = 0; c < n; ++c) e.mass_matrix[r * n + c] += body.mass * dot(v[r], v[c]) + dot(w[r], iw[c]);

    e.kinetic_energy += 0.5 * (body.mass * dot(com_velocity, com_velocity) + dot(omega, momentum));
    e.potential_energy -= body.mass * dot(m.gravity, com);
  }

  for (const ForceData& f : m.forces) {
    const Motion2& k = motion[f.body];
    const Vec<double> at = add(k.p, mul(k.r, f.point));
    const Vec<double> force = f.body_frame ? mul(k.r, f.force) : f.force;
    for (int r = 0; r < n; ++r)
      e.forcing[r] += dot(force, add(rates[r].origin[f.body], mul(rates[r].rotation[f.body], f.point)));
    if (f.body_frame) {
      e.nonconservative_power += dot(force, add(k.p1, mul(k.r1, f.point)));
    } else {
      e.potential_energy -= dot(force, at);
    }
  }

  for (int r = 0; r < n; ++r) {
    const JointData& j = m.joints[m.coordinate_joint[r]];
    const double stretch = s.q[r] - j.rest;
    e.forcing[r] += -j.stiffness * stretch - j.damping * s.u[r] + (j.actuated ? s.tau[r] : 0.0);
    e.potential_energy += 0.5 * j.stiffness * stretch * stretch;
  }
  e.nonconservative_power += joint_power(m, s);

  const Eigen::Map<const Eigen::MatrixXd> mass(e.mass_matrix.data(), n, n);
  const Eigen::LLT<Eigen::MatrixXd> llt(mass);
  if (llt.info() == Eigen::Success) {
    const Eigen::VectorXd x = llt.solve(Eigen::Map<const Eigen::VectorXd>(e.forcing.data(), n));
    e.udot.assign(x.data(), x.data() + n);
  }

  std::vector<Pose<double>> poses(motion.size());
  for (std::size_t b = 0; b < motion.size(); ++b) poses[b] = {motion[b].r, motion[b].p};
  for (const OutputData& o : m.outputs) {
    if (o.kind == model::OutputKind::point_position) {
      const Vec<double> x = point_position(poses, o.body, o.point);
      e.outputs.insert(e.outputs.end(), x.begin(), x.end());
    } else {
      e.outputs.push_back(o.kind == model::OutputKind::joint_coordinate ? s.q[o.coordinate]
                                                                        : s.u[o.coordinate]);
    }
  }
  return e;
}

double nonconservative_power(const Instance& m, const State& s) {
  check_sizes(m, s);
  double power = joint_power(m, s);
  bool any = false;
  for (const ForceData& f : m.forces) any = any || f.body_frame;
  if (!any) return power;
  const std::vector<Pose<D1>> poses = poses_along_u(m, s);
  for (const ForceData& f : m.forces) {
    if (!f.body_frame) continue;
    Mat<double> r;
    for (int i = 0; i < 9; ++i) r[i] = poses[f.body].rotation[i].v;
    power += dot(mul(r, f.force), point_velocity(poses[f.body], f.point));
  }
  return power;
}

}  // namespace kanegen::numeric
