// SPDX-License-Identifier: GPL-2.0-or-later
// MuJoCo as an independent reference for the generated equations of motion.
//
// MuJoCo 2.2.2 loads a URDF file directly (mj_loadXML). What its importer
// does, checked on this version (see docs/benchmarks.md, "MuJoCo and URDF"):
//  - the root link is welded to the world (no free joint); revolute and
//    continuous joints become hinges, prismatic joints slides, fixed joints
//    no joint; the joint axis is in the child link frame, as in URDF;
//  - the <inertial> element is used as is (mass, COM, full inertia, rpy of
//    the inertial frame); with fusestatic="true", the URDF default, links on
//    fixed joints are merged into their parent (the root link into the world)
//    — same dynamics, but fewer bodies; the shipped URDFs carry a
//    <mujoco><compiler fusestatic="false" .../></mujoco> element (ignored by
//    urdfdom) so that every link stays a body and masses can be compared;
//  - revolute joints with <limit> are "limited" (continuous ones are not);
//    limits act only through the constraint solver, i.e. on qacc, never on
//    qacc_smooth; damping and friction come from <dynamics> (none in the
//    shipped models), armature and stiffness are 0;
//  - DOFs are numbered depth-first over the body tree, which need not be the
//    URDF file order: this class maps them by joint name;
//  - a full inertia tensor (non-zero ixy, ixz, iyz) is diagonalised at load
//    time by a Jacobi iteration that stops once the rotation angle of a sweep
//    is below ~1.4e-6 rad (mjuu_eig3: cos > 1 - 1e-12), so MuJoCo's body
//    inertia is only accurate to ~1e-7 relative. With refine_inertia (the
//    default), this class recomputes the principal moments and axes of every
//    URDF link (Eigen's SelfAdjointEigenSolver) and writes them into
//    body_inertia / body_iquat; it checks that this moves MuJoCo's tensors by
//    less than 1e-5 relative, so it only removes the round-off and would catch
//    a misreading of the URDF (e.g. the rpy convention).
// Contacts and the whole constraint stage are disabled here, so qacc equals
// qacc_smooth = M^-1 (qfrc_passive - qfrc_bias).
#pragma once

#include <mujoco/mujoco.h>

#include <Eigen/Dense>
#include <map>
#include <string>
#include <vector>

namespace kanegen_consistency {

/// Names of the moving joints (revolute, continuous, prismatic) of a URDF
/// file, in the order the file lists them: the coordinate order of the
/// generated model. Throws std::runtime_error on a file it cannot read.
std::vector<std::string> urdf_moving_joints(const std::string& path);

/// Mass of every link that has an <inertial> element, by link name.
std::map<std::string, double> urdf_link_masses(const std::string& path);

/// What MuJoCo computes at one state, in the coordinate order given to the
/// MujocoReference (URDF file order by default).
struct MujocoDynamics {
  Eigen::MatrixXd M;             ///< joint-space inertia (mj_fullM of qM)
  Eigen::VectorXd qfrc_bias;     ///< gravity + Coriolis/centrifugal, M qacc + bias = applied
  Eigen::VectorXd qfrc_passive;  ///< springs and dampers (zero for the shipped URDFs)
  Eigen::VectorXd qacc_smooth;   ///< M^-1 (qfrc_passive - qfrc_bias)
  Eigen::VectorXd forcing() const { return qfrc_passive - qfrc_bias; }
  double kinetic_energy = 0.0;    ///< MuJoCo's energy[1] (mjENBL_ENERGY)
  double potential_energy = 0.0;  ///< MuJoCo's energy[0]: sum of m g.z over all bodies
};

class MujocoReference {
 public:
  /// Loads a URDF (or MJCF) file; throws std::runtime_error with MuJoCo's
  /// message if it fails. Coordinates are the URDF's moving joints in file
  /// order; every model joint must be a hinge or slide found by name.
  explicit MujocoReference(const std::string& urdf_path, bool refine_inertia = true);
  /// Same, with the coordinate order given explicitly by joint names.
  MujocoReference(const std::string& urdf_path, const std::vector<std::string>& coordinate_joints,
                  bool refine_inertia = true);
  ~MujocoReference();
  MujocoReference(const MujocoReference&) = delete;
  MujocoReference& operator=(const MujocoReference&) = delete;

  int nv() const;
  const std::vector<std::string>& coordinate_joints() const { return names_; }
  /// MuJoCo DOF index of coordinate i.
  const std::vector<int>& dof_of_coordinate() const { return dof_; }
  /// Mass of the MuJoCo body of that name; a negative value if there is none.
  double body_mass(const std::string& name) const;
  const mjModel* model() const { return m_; }
  /// Largest relative change of a body inertia tensor (body frame) made by
  /// refine_inertia: max|I_new - I_mujoco| / max|I_new| over the links; 0 if
  /// not refined.
  double inertia_refinement() const { return refinement_; }

  /// Runs mj_forward at (q, u) (coordinate order), nothing applied, and
  /// returns the results permuted to coordinate order.
  MujocoDynamics evaluate(const Eigen::VectorXd& q, const Eigen::VectorXd& u);

 private:
  void init(const std::string& path, const std::vector<std::string>& coordinate_joints, bool refine);
  void refine_inertias(const std::string& path);
  void release();

  mjModel* m_ = nullptr;
  mjData* d_ = nullptr;
  std::vector<std::string> names_;
  std::vector<int> qpos_;  ///< qpos address of coordinate i
  std::vector<int> dof_;   ///< dof address of coordinate i
  double refinement_ = 0.0;
};

}  // namespace kanegen_consistency
