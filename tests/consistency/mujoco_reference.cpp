// SPDX-License-Identifier: GPL-2.0-or-later
#include "mujoco_reference.hpp"

#include <tinyxml2.h>

#include <algorithm>
#include <sstream>
#include <stdexcept>

namespace kanegen_consistency {

namespace {

const tinyxml2::XMLElement* load_robot(tinyxml2::XMLDocument& doc, const std::string& path) {
  if (doc.LoadFile(path.c_str()) != tinyxml2::XML_SUCCESS) {
    throw std::runtime_error(path + ": cannot read as XML: " + doc.ErrorStr());
  }
  const tinyxml2::XMLElement* robot = doc.FirstChildElement("robot");
  if (robot == nullptr) {
    throw std::runtime_error(path + ": no <robot> element");
  }
  return robot;
}

}  // namespace

std::vector<std::string> urdf_moving_joints(const std::string& path) {
  tinyxml2::XMLDocument doc;
  const tinyxml2::XMLElement* robot = load_robot(doc, path);
  std::vector<std::string> names;
  for (const auto* j = robot->FirstChildElement("joint"); j != nullptr; j = j->NextSiblingElement("joint")) {
    const char* name = j->Attribute("name");
    const char* type = j->Attribute("type");
    if (name == nullptr || type == nullptr) {
      throw std::runtime_error(path + ": a <joint> without name or type");
    }
    const std::string t = type;
    if (t == "revolute" || t == "continuous" || t == "prismatic") {
      names.emplace_back(name);
    } else if (t != "fixed") {
      throw std::runtime_error(path + ": joint " + name + " has unsupported type " + t);
    }
  }
  return names;
}

std::map<std::string, double> urdf_link_masses(const std::string& path) {
  tinyxml2::XMLDocument doc;
  const tinyxml2::XMLElement* robot = load_robot(doc, path);
  std::map<std::string, double> masses;
  for (const auto* l = robot->FirstChildElement("link"); l != nullptr; l = l->NextSiblingElement("link")) {
    const auto* inertial = l->FirstChildElement("inertial");
    if (inertial == nullptr) continue;
    const auto* mass = inertial->FirstChildElement("mass");
    if (mass == nullptr || l->Attribute("name") == nullptr) {
      throw std::runtime_error(path + ": an <inertial> without <mass> or a link without name");
    }
    masses[l->Attribute("name")] = mass->DoubleAttribute("value", -1.0);
  }
  return masses;
}

MujocoReference::MujocoReference(const std::string& urdf_path, bool refine_inertia) {
  init(urdf_path, urdf_moving_joints(urdf_path), refine_inertia);
}

MujocoReference::MujocoReference(const std::string& urdf_path,
                                 const std::vector<std::string>& coordinate_joints, bool refine_inertia) {
  init(urdf_path, coordinate_joints, refine_inertia);
}

void MujocoReference::init(const std::string& path, const std::vector<std::string>& coordinate_joints,
                           bool refine) {
  char error[1000] = "";
  m_ = mj_loadXML(path.c_str(), nullptr, error, sizeof error);
  if (m_ == nullptr) {
    throw std::runtime_error(path + ": MuJoCo cannot load it: " + error);
  }
  // No contacts and no constraint stage at all (joint limits, equality,
  // friction loss): qacc is then qacc_smooth. Energy for the energy checks.
  m_->opt.disableflags |= mjDSBL_CONTACT | mjDSBL_CONSTRAINT;
  m_->opt.enableflags |= mjENBL_ENERGY;
  d_ = mj_makeData(m_);

  names_ = coordinate_joints;
  if (static_cast<int>(names_.size()) != m_->nv || m_->nq != m_->nv) {
    const std::string msg = path + ": MuJoCo has nq = " + std::to_string(m_->nq) +
                            ", nv = " + std::to_string(m_->nv) + " but " + std::to_string(names_.size()) +
                            " coordinates were given";
    release();
    throw std::runtime_error(msg);
  }
  std::vector<bool> used(m_->nv, false);
  for (const std::string& name : names_) {
    const int j = mj_name2id(m_, mjOBJ_JOINT, name.c_str());
    std::string problem;
    if (j < 0) {
      problem = "MuJoCo has no joint named " + name;
    } else if (m_->jnt_type[j] != mjJNT_HINGE && m_->jnt_type[j] != mjJNT_SLIDE) {
      problem = "MuJoCo joint " + name + " is not a hinge or a slide";
    } else if (used[m_->jnt_dofadr[j]]) {
      problem = "joint " + name + " given twice";
    }
    if (!problem.empty()) {
      release();
      throw std::runtime_error(path + ": " + problem);
    }
    used[m_->jnt_dofadr[j]] = true;
    qpos_.push_back(m_->jnt_qposadr[j]);
    dof_.push_back(m_->jnt_dofadr[j]);
  }
  if (refine) {
    try {
      refine_inertias(path);
    } catch (...) {
      release();
      throw;
    }
  }
}

void MujocoReference::refine_inertias(const std::string& path) {
  tinyxml2::XMLDocument doc;
  const tinyxml2::XMLElement* robot = load_robot(doc, path);
  for (const auto* l = robot->FirstChildElement("link"); l != nullptr; l = l->NextSiblingElement("link")) {
    const auto* inertial = l->FirstChildElement("inertial");
    if (inertial == nullptr) continue;
    const std::string name = l->Attribute("name");
    const int b = mj_name2id(m_, mjOBJ_BODY, name.c_str());
    const auto* in = inertial->FirstChildElement("inertia");
    if (b < 0 || in == nullptr) {
      throw std::runtime_error(
          path + ": link " + name +
          " is no MuJoCo body (fusestatic?) or has no <inertia>: cannot refine its inertia");
    }
    // the tensor as the file gives it, in the inertial frame
    Eigen::Matrix3d F;
    F << in->DoubleAttribute("ixx"), in->DoubleAttribute("ixy"), in->DoubleAttribute("ixz"),  //
        in->DoubleAttribute("ixy"), in->DoubleAttribute("iyy"), in->DoubleAttribute("iyz"),   //
        in->DoubleAttribute("ixz"), in->DoubleAttribute("iyz"), in->DoubleAttribute("izz");
    // inertial frame -> link (= MuJoCo body) frame: URDF rpy, R = Rz(yaw) Ry(pitch) Rx(roll)
    Eigen::Vector3d rpy = Eigen::Vector3d::Zero();
    if (const auto* origin = inertial->FirstChildElement("origin")) {
      if (const char* text = origin->Attribute("rpy")) {
        std::istringstream is(text);
        if (!(is >> rpy[0] >> rpy[1] >> rpy[2])) throw std::runtime_error(path + ": bad rpy of link " + name);
      }
    }
    const Eigen::Matrix3d R = (Eigen::AngleAxisd(rpy[2], Eigen::Vector3d::UnitZ()) *
                               Eigen::AngleAxisd(rpy[1], Eigen::Vector3d::UnitY()) *
                               Eigen::AngleAxisd(rpy[0], Eigen::Vector3d::UnitX()))
                                  .toRotationMatrix();
    const Eigen::Matrix3d I = R * F * R.transpose();

    // what MuJoCo made of it
    const mjtNum* iq = m_->body_iquat + 4 * b;
    const Eigen::Matrix3d Rm = Eigen::Quaterniond(iq[0], iq[1], iq[2], iq[3]).normalized().toRotationMatrix();
    const Eigen::Matrix3d Im = Rm * Eigen::Vector3d(m_->body_inertia + 3 * b).asDiagonal() * Rm.transpose();

    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(I);
    if (eig.info() != Eigen::Success || eig.eigenvalues().minCoeff() <= 0.0) {
      throw std::runtime_error(path + ": inertia of link " + name + " is not positive definite");
    }
    Eigen::Matrix3d V = eig.eigenvectors();
    if (V.determinant() < 0.0) V.col(0) = -V.col(0);  // a rotation
    const Eigen::Quaterniond qv(V);
    for (int k = 0; k < 3; ++k) m_->body_inertia[3 * b + k] = eig.eigenvalues()[k];
    m_->body_iquat[4 * b + 0] = qv.w();
    m_->body_iquat[4 * b + 1] = qv.x();
    m_->body_iquat[4 * b + 2] = qv.y();
    m_->body_iquat[4 * b + 3] = qv.z();

    const double change = (I - Im).cwiseAbs().maxCoeff() / I.cwiseAbs().maxCoeff();
    refinement_ = std::max(refinement_, change);
    if (change > 1e-5) {
      throw std::runtime_error(path + ": MuJoCo's inertia of link " + name + " differs from the file's by " +
                               std::to_string(change) + " (relative): not round-off, refusing to refine");
    }
  }
}

MujocoReference::~MujocoReference() { release(); }

void MujocoReference::release() {
  if (d_ != nullptr) mj_deleteData(d_);
  if (m_ != nullptr) mj_deleteModel(m_);
  d_ = nullptr;
  m_ = nullptr;
}

int MujocoReference::nv() const { return m_->nv; }

double MujocoReference::body_mass(const std::string& name) const {
  const int b = mj_name2id(m_, mjOBJ_BODY, name.c_str());
  return b < 0 ? -1.0 : m_->body_mass[b];
}

MujocoDynamics MujocoReference::evaluate(const Eigen::VectorXd& q, const Eigen::VectorXd& u) {
  const int n = m_->nv;
  if (q.size() != n || u.size() != n) {
    throw std::invalid_argument("MujocoReference::evaluate: q and u must have nv entries");
  }
  mj_resetData(m_, d_);  // zero ctrl, qfrc_applied, xfrc_applied, warm start
  for (int i = 0; i < n; ++i) {
    d_->qpos[qpos_[i]] = q[i];
    d_->qvel[dof_[i]] = u[i];
  }
  mj_forward(m_, d_);

  Eigen::Matrix<mjtNum, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> full(n, n);
  mj_fullM(m_, full.data(), d_->qM);
  MujocoDynamics r;
  r.M.resize(n, n);
  r.qfrc_bias.resize(n);
  r.qfrc_passive.resize(n);
  r.qacc_smooth.resize(n);
  for (int i = 0; i < n; ++i) {
    for (int k = 0; k < n; ++k) r.M(i, k) = full(dof_[i], dof_[k]);
    r.qfrc_bias[i] = d_->qfrc_bias[dof_[i]];
    r.qfrc_passive[i] = d_->qfrc_passive[dof_[i]];
    r.qacc_smooth[i] = d_->qacc_smooth[dof_[i]];
  }
  r.potential_energy = d_->energy[0];
  r.kinetic_energy = d_->energy[1];
  return r;
}

}  // namespace kanegen_consistency
