// SPDX-License-Identifier: GPL-2.0-or-later
// Pinocchio's side of bench_pinocchio (see pinocchio_peer.hpp).
#include "pinocchio_peer.hpp"

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>
#include <map>
#include <pinocchio/algorithm/aba-derivatives.hpp>
#include <pinocchio/algorithm/aba.hpp>
#include <pinocchio/algorithm/crba.hpp>
#include <pinocchio/algorithm/rnea.hpp>
#include <pinocchio/multibody/data.hpp>
#include <pinocchio/multibody/model.hpp>
#include <stdexcept>

namespace kanegen_bench {

namespace km = kanegen::model;
using Eigen::MatrixXd;
using Eigen::Vector3d;
using Eigen::VectorXd;

namespace {

[[noreturn]] void fail(const std::string& msg) { throw std::runtime_error("pinocchio_peer: " + msg); }

double number(const km::Scalar& s, const std::string& what) {
  if (!s.is_literal) fail(what + " is an expression (" + s.text + "); only numbers are modelled");
  return s.value;
}

Vector3d vec(const km::Vec3& v, const std::string& what) {
  return {number(v[0], what), number(v[1], what), number(v[2], what)};
}

// URDF: R = Rz(yaw) Ry(pitch) Rx(roll).
pinocchio::SE3 origin(const km::Joint& j) {
  const Vector3d rpy = vec(j.origin_rpy, j.name + " origin rpy");
  const Eigen::Matrix3d R =
      (Eigen::AngleAxisd(rpy[2], Vector3d::UnitZ()) * Eigen::AngleAxisd(rpy[1], Vector3d::UnitY()) *
       Eigen::AngleAxisd(rpy[0], Vector3d::UnitX()))
          .toRotationMatrix();
  return pinocchio::SE3(R, vec(j.origin_xyz, j.name + " origin xyz"));
}

// As Pinocchio's URDF parser: a joint about (along) a unit axis of its frame
// is the specialised RX/RY/RZ (PX/PY/PZ), any other axis the unaligned one.
pinocchio::JointModel joint_model(const km::Joint& j) {
  const Vector3d axis = Vector3d(j.axis[0], j.axis[1], j.axis[2]).normalized();
  const bool revolute = j.type == km::JointType::revolute || j.type == km::JointType::continuous;
  if (axis.isApprox(Vector3d::UnitX()))
    return revolute ? pinocchio::JointModel(pinocchio::JointModelRX())
                    : pinocchio::JointModel(pinocchio::JointModelPX());
  if (axis.isApprox(Vector3d::UnitY()))
    return revolute ? pinocchio::JointModel(pinocchio::JointModelRY())
                    : pinocchio::JointModel(pinocchio::JointModelPY());
  if (axis.isApprox(Vector3d::UnitZ()))
    return revolute ? pinocchio::JointModel(pinocchio::JointModelRZ())
                    : pinocchio::JointModel(pinocchio::JointModelPZ());
  if (revolute) return pinocchio::JointModel(pinocchio::JointModelRevoluteUnaligned(axis));
  return pinocchio::JointModel(pinocchio::JointModelPrismaticUnaligned(axis));
}

void check_supported(const km::Model& m) {
  if (!m.loops.empty() || !m.springs.empty() || !m.forces.empty() || !m.joint_efforts.empty())
    fail("loops, springs, point forces and joint efforts are not modelled");
  for (const km::Joint& j : m.joints) {
    if (j.type == km::JointType::planar || j.is_prescribed() || j.parent_node >= 0 ||
        !j.parent_node_set.empty())
      fail("joint " + j.name + ": only revolute, continuous, prismatic and fixed joints are modelled");
    if (number(j.damping, j.name + " damping") != 0.0 ||
        number(j.spring_stiffness, j.name + " spring") != 0.0)
      fail("joint " + j.name + ": joint springs and dampers are not modelled");
  }
  for (const km::Body& b : m.bodies)
    if (b.flexible) fail("body " + b.name + " is flexible");
}

pinocchio::Inertia inertia(const km::Body& b) {
  const auto& I = b.inertia;  // ixx, iyy, izz, ixy, ixz, iyz
  const std::string w = b.name + " inertia";
  Eigen::Matrix3d J;
  J << number(I[0], w), number(I[3], w), number(I[4], w), number(I[3], w), number(I[1], w), number(I[5], w),
      number(I[4], w), number(I[5], w), number(I[2], w);
  return pinocchio::Inertia(number(b.mass, b.name + " mass"), vec(b.com, b.name + " com"), J);
}

// Where a body's frame is: on a Pinocchio joint, at a placement in its frame.
struct Attachment {
  pinocchio::JointIndex joint = 0;
  pinocchio::SE3 placement = pinocchio::SE3::Identity();
};

pinocchio::Model build(const km::Model& m) {
  check_supported(m);
  pinocchio::Model model;
  model.gravity.linear(vec(m.gravity, "gravity"));
  std::map<std::string, Attachment> at{{m.ground, Attachment{}}};
  std::vector<bool> done(m.joints.size(), false);
  // Parents before children (file order need not be): sweep until no joint is added.
  for (bool added = true; added;) {
    added = false;
    for (std::size_t i = 0; i < m.joints.size(); ++i) {
      const km::Joint& j = m.joints[i];
      const auto parent = at.find(j.parent);
      if (done[i] || parent == at.end()) continue;
      const pinocchio::SE3 placement = parent->second.placement * origin(j);
      if (j.type == km::JointType::fixed) {
        at[j.child] = Attachment{parent->second.joint, placement};
      } else {
        const auto id = model.addJoint(parent->second.joint, joint_model(j), placement, j.name);
        at[j.child] = Attachment{id, pinocchio::SE3::Identity()};
      }
      done[i] = added = true;
    }
  }
  for (const km::Body& b : m.bodies) {
    const auto a = at.find(b.name);
    if (a == at.end()) fail("body " + b.name + " is not connected to the ground");
    model.appendBodyToJoint(a->second.joint, inertia(b), a->second.placement);
  }
  return model;
}

}  // namespace

struct PinocchioPeer::Impl {
  pinocchio::Model model;
  pinocchio::Data data;
  std::vector<int> perm;  // kanegen coordinate i -> Pinocchio idx_v
  std::vector<VectorXd> q, v, a, tau;
  VectorXd x, y, z;  // scratch in Pinocchio's order

  explicit Impl(pinocchio::Model m) : model(std::move(m)), data(model) {}

  void to_pin(const double* in, VectorXd& out) const {
    out.resize(model.nv);
    for (std::size_t i = 0; i < perm.size(); ++i) out[perm[i]] = in[i];
  }
  void from_pin(const VectorXd& in, double* out) const {
    for (std::size_t i = 0; i < perm.size(); ++i) out[i] = in[perm[i]];
  }
  void matrix_from_pin(const MatrixXd& in, double* out) const {
    const std::size_t n = perm.size();
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = 0; j < n; ++j) out[i * n + j] = in(perm[i], perm[j]);
  }
};

PinocchioPeer::PinocchioPeer(const km::Model& model, const std::vector<std::string>& coordinates)
    : impl_(std::make_unique<Impl>(build(model))) {
  if (impl_->model.nq != impl_->model.nv || impl_->model.nv != static_cast<int>(coordinates.size()))
    fail("Pinocchio has nv = " + std::to_string(impl_->model.nv) + ", kanegen " +
         std::to_string(coordinates.size()) + " coordinates");
  for (const std::string& name : coordinates) {
    if (!impl_->model.existJointName(name)) fail("Pinocchio has no joint " + name);
    impl_->perm.push_back(impl_->model.joints[impl_->model.getJointId(name)].idx_v());
  }
}

PinocchioPeer::~PinocchioPeer() = default;

int PinocchioPeer::nv() const { return impl_->model.nv; }

void PinocchioPeer::aba(const double* q, const double* v, const double* tau, double* ddq) {
  Impl& s = *impl_;
  VectorXd qq, vv, tt;
  s.to_pin(q, qq);
  s.to_pin(v, vv);
  s.to_pin(tau, tt);
  s.from_pin(pinocchio::aba(s.model, s.data, qq, vv, tt), ddq);
}

void PinocchioPeer::rnea(const double* q, const double* v, const double* a, double* tau) {
  Impl& s = *impl_;
  VectorXd qq, vv, aa;
  s.to_pin(q, qq);
  s.to_pin(v, vv);
  s.to_pin(a, aa);
  s.from_pin(pinocchio::rnea(s.model, s.data, qq, vv, aa), tau);
}

void PinocchioPeer::crba(const double* q, double* M) {
  Impl& s = *impl_;
  VectorXd qq;
  s.to_pin(q, qq);
  pinocchio::crba(s.model, s.data, qq);
  MatrixXd full = s.data.M;
  full.triangularView<Eigen::StrictlyLower>() = full.transpose().triangularView<Eigen::StrictlyLower>();
  s.matrix_from_pin(full, M);
}

void PinocchioPeer::aba_derivatives(const double* q, const double* v, const double* tau, double* ddq_dq,
                                    double* ddq_dv, double* Minv) {
  Impl& s = *impl_;
  VectorXd qq, vv, tt;
  s.to_pin(q, qq);
  s.to_pin(v, vv);
  s.to_pin(tau, tt);
  pinocchio::computeABADerivatives(s.model, s.data, qq, vv, tt);
  s.matrix_from_pin(s.data.ddq_dq, ddq_dq);
  s.matrix_from_pin(s.data.ddq_dv, ddq_dv);
  MatrixXd full = s.data.Minv;
  full.triangularView<Eigen::StrictlyLower>() = full.transpose().triangularView<Eigen::StrictlyLower>();
  s.matrix_from_pin(full, Minv);
}

void PinocchioPeer::store_states(int count, const double* q, const double* v, const double* a,
                                 const double* tau) {
  Impl& s = *impl_;
  const int n = s.model.nv;
  s.q.assign(count, VectorXd());
  s.v.assign(count, VectorXd());
  s.a.assign(count, VectorXd());
  s.tau.assign(count, VectorXd());
  for (int k = 0; k < count; ++k) {
    s.to_pin(q + k * n, s.q[k]);
    s.to_pin(v + k * n, s.v[k]);
    s.to_pin(a + k * n, s.a[k]);
    s.to_pin(tau + k * n, s.tau[k]);
  }
}

void PinocchioPeer::aba_state(int k) {
  Impl& s = *impl_;
  pinocchio::aba(s.model, s.data, s.q[k], s.v[k], s.tau[k]);
}

void PinocchioPeer::rnea_state(int k) {
  Impl& s = *impl_;
  pinocchio::rnea(s.model, s.data, s.q[k], s.v[k], s.a[k]);
}

void PinocchioPeer::crba_state(int k) {
  Impl& s = *impl_;
  pinocchio::crba(s.model, s.data, s.q[k]);
}

void PinocchioPeer::aba_derivatives_state(int k) {
  Impl& s = *impl_;
  pinocchio::computeABADerivatives(s.model, s.data, s.q[k], s.v[k], s.tau[k]);
}

double PinocchioPeer::sink() const {
  const pinocchio::Data& d = impl_->data;
  return d.ddq[0] + d.tau[0] + d.M(0, 0) + d.ddq_dq(0, 0);
}

}  // namespace kanegen_bench
