// SPDX-License-Identifier: GPL-2.0-or-later
// A model with its parameters given values: every scalar evaluated, names
// resolved to indices, bodies put in an order where parents come first. The
// numeric derivation works on this plain-number form only.
#pragma once

#include <array>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "model/expression_eval.hpp"
#include "model/model.hpp"
#include "model/output_columns.hpp"
#include "numeric/small_matrix.hpp"
#include "numeric/time_function.hpp"

namespace kanegen::numeric {

/// How a joint moves its child. A ball (spherical joint) has three
/// coordinates: a rotation vector phi from the joint's base quaternion
/// (JointData::base), R = R(base) exp([phi]x). The numeric path evaluates
/// at phi = 0 with the state's quaternion as the base, where q_dot = u holds
/// for the rotation vector to the second order its derivations take
/// (numeric/spherical.hpp).
enum class Motion { none, rotation, translation, ball };

/// One piece of a prescribed motion: q(t) while t < until (the last piece: always).
struct PrescribedData {
  TimeFunction q;
  bool has_until = false;
  double until = 0;
};

struct JointData {
  std::string name;
  int parent = -1;       ///< body index; -1 for the ground
  int parent_node = -1;  ///< the node of a flexible parent the joint frame sits on (-1: the parent frame)
  int child = -1;        ///< body index
  Motion motion = Motion::none;
  Mat<double> origin_rotation;  ///< joint frame in parent axes (URDF rpy)
  Vec<double> origin_position;  ///< joint frame origin in the parent frame
  Vec<double> axis;             ///< unit, joint-frame axes
  int coordinate = -1;          ///< index in q and u (a ball's first of three); -1 for a fixed joint
  std::array<double, 4> base{1.0, 0.0, 0.0, 0.0};  ///< a ball's base quaternion w, x, y, z (unit)
  double stiffness = 0, rest = 0, damping = 0;
  bool actuated = false;
  std::vector<PrescribedData> prescribed;  ///< empty: a free coordinate

  bool is_prescribed() const { return !prescribed.empty(); }
};

/// One beam element of a flexible body: from node `node` to node + 1.
struct BeamElementData {
  int node = 0;
  double length = 0;
  Mat<double> axes;    ///< columns: the element's x, y, z axes in the link frame
  Vec<double> origin;  ///< its first node, link frame
};

/// One plane or solid element of a mesh body (numeric/solid.hpp), with its
/// quadrature precomputed in the undeformed link frame.
struct SolidElementData {
  std::string type;        ///< CalculiX element type (numeric/solid.hpp's families)
  int dimension = 2;       ///< 2: plane stress, 3: solid (set with the quadrature)
  std::vector<int> nodes;  ///< FlexibleData nodes, CalculiX order
  /// Full Gauss-Legendre points: shape values, physical gradients dN/dX
  /// (nodes x dimension, row-major), undeformed position and the weight
  /// det J w (times the thickness in the plane).
  struct Point {
    std::vector<double> N, dN;
    Vec<double> X;
    double weight = 0;
  };
  std::vector<Point> points;
};

/// A finite-element beam as the numeric path sees it: geometry, section and
/// material numbers from the model, and the elastic coordinates. The body's
/// dofs are link-frame nodal components, node by node (planar: u_x, u_y,
/// theta_z; spatial: u_x, u_y, u_z, theta_x, theta_y, theta_z), and
/// dofs = B eta. B is the one thing taken from the finite-element layer
/// (build_elastic_model of generator/fem): a choice of coordinates (which dofs the support
/// leaves free, the modal shapes, or the assumed modes sampled at the nodes), not a
/// derivation (docs/verify.md).
struct FlexibleData {
  std::string body;
  bool planar = true;
  int dofs_per_node = 3;
  std::vector<Vec<double>> nodes;  ///< undeformed, link frame
  std::vector<BeamElementData> elements;
  double A = 0, Iy = 0, Iz = 0, J = 0, E = 0, G = 0, density = 0, fibre_y = 0, fibre_z = 0;
  double tip_mass = 0;
  Mat<double> tip_inertia{};  ///< about the last node, link axes
  bool modal = false;
  double rayleigh_alpha = 0, rayleigh_beta = 0, modal_ratio = 0;
  /// Geometric stiffening asked for (the model's flag). In nodal
  /// coordinates it is the nonlinear axial strain energy; in modes and
  /// assumed modes, the foreshortening of the points (beam.hpp).
  bool stiffening = false;
  bool shortens() const { return stiffening && modal; }
  bool nonlinear_strain() const { return stiffening && !modal; }
  /// B by columns: (dof, value) pairs of the nonzero entries of column k.
  std::vector<std::vector<std::pair<int, double>>> basis;
  std::vector<std::string> names;  ///< per elastic coordinate: "n3.v", "mode2", ...
  /// A mesh body (model::MeshSource): no beam elements, but plane (u_x,
  /// u_y per node) or solid (u_x, u_y, u_z) elements of this material.
  bool mesh = false;
  std::vector<SolidElementData> solids;
  /// A mesh body's interfaces (a joint's "node" k is interface k): the
  /// least-squares rigid motion of a node set, t = mean u_i and
  /// theta = A^-1 sum r_i x u_i (r_i from the centroid).
  struct Interface {
    std::vector<int> nodes;
    Vec<double> centroid;
    Mat<double> inverse_A;  ///< in the plane: only (2, 2), 1 / sum |r_i|^2
  };
  std::vector<Interface> interfaces;
  double poisson = 0;
  /// A mesh body with geometric stiffening: the second-order fields d_ij
  /// of its points' displacement u2 = 1/2 sum_ij eta_i eta_j d_ij, taken with
  /// the basis from the finite-element layer (model data, as the mode
  /// shapes are), as (dof, value) pairs by mode pairs i <= j: (0, 0), (0, 1),
  /// ..., (1, 1), ...; and the basis's least-squares inverse (this path's
  /// own), eta = left_inverse dofs, so that u2 is a function of the dofs.
  std::vector<std::vector<std::pair<int, double>>> second_order;
  std::vector<std::vector<double>> left_inverse;

  int count() const { return static_cast<int>(basis.size()); }
  int num_dofs() const { return static_cast<int>(nodes.size()) * dofs_per_node; }
  /// Index of a node's translation (axis 0..2) or rotation (3..5) dof; -1 if the layout has none.
  int dof(int node, int kind) const {
    if (mesh) return kind < dofs_per_node ? node * dofs_per_node + kind : -1;
    if (dofs_per_node == 6) return node * 6 + kind;
    static const int planar_index[6] = {0, 1, -1, -1, -1, 2};
    return planar_index[kind] < 0 ? -1 : node * 3 + planar_index[kind];
  }
};

struct BodyData {
  std::string name;
  int joint = -1;  ///< index of the joint that carries it
  double mass = 0;
  Vec<double> com;      ///< body frame
  Mat<double> inertia;  ///< about the centre of mass, body axes
  /// A flexible body's beam (shared by every instance of the model), else null.
  std::shared_ptr<const FlexibleData> elastic;
  int elastic_first = -1;  ///< index in q and u of its first elastic coordinate
};

struct ForceData {
  std::string name;
  int body = -1;
  Vec<double> point;  ///< body frame
  int node = -1;      ///< or at this node of a flexible body, moving with it
  Vec<double> force;  ///< world or body axes
  bool body_frame = false;
};

/// A spring-damper between a point of `body` and one of `body2` (-1: the ground, point in world axes).
struct SpringData {
  std::string name;
  int body = -1;
  Vec<double> point;  ///< body frame
  int body2 = -1;
  Vec<double> point2;  ///< body2's frame, or world
  double stiffness = 0, rest_length = 0, damping = 0;
};

/// A generalized force on a joint coordinate: a constant, or a function of t.
struct EffortData {
  std::string name;
  int coordinate = -1;
  bool varies = false;  ///< use `function`, else `value`
  double value = 0;
  TimeFunction function;

  double at(double t) const { return varies ? function(t) : value; }
};

struct OutputData {
  std::string name;
  model::OutputKind kind = model::OutputKind::point_position;
  int body = -1;  ///< -1 for the ground
  Vec<double> point;
  int coordinate = -1;
  int node = -1;  ///< node outputs of a flexible body
  int loop = -1;  ///< reaction outputs: index in Instance::loops
};

/// A joint that closes a loop (docs/closed-loops.md): a point of `body` (or
/// one of its nodes) tied to a point of `body2` (-1: the ground, point in
/// world axes). Its rows are computed in numeric/loops.hpp.
struct LoopData {
  std::string name;
  model::LoopType type = model::LoopType::revolute;
  bool planar = false;
  int body = -1, node = -1;  ///< node: a node of a flexible body instead of `point`
  Vec<double> point;
  int body2 = -1, node2 = -1;
  Vec<double> point2;
  Vec<double> axis;  ///< unit
  /// The row names' suffixes ("x", "y", "f1", "m1", "n", ...), one per equation (model::loop_rows).
  std::vector<std::string> rows;
};

struct Instance {
  std::vector<BodyData> bodies;
  std::vector<JointData> joints;              ///< model order
  std::vector<int> order;                     ///< body indices, every parent before its children
  std::vector<int> coordinate_joint;          ///< joint index of each joint coordinate (they come first in q)
  std::vector<int> ball_joints;               ///< the joints that move as a ball, model order
  std::vector<std::string> coordinate_names;  ///< every coordinate: joints, then "<body>.<name>" elastic ones
  Vec<double> gravity;
  std::vector<ForceData> forces;
  std::vector<SpringData> springs;
  std::vector<EffortData> efforts;
  std::vector<OutputData> outputs;
  std::vector<model::OutputColumn> output_columns;  ///< what Evaluation::outputs holds, column by column
  std::vector<LoopData> loops;

  /// The number of loop equations (rows of Phi) over all loops.
  int constraints() const;
  /// Joint coordinates, then the elastic coordinates of the flexible bodies in body order.
  int coordinates() const { return static_cast<int>(coordinate_names.size()); }
  int joint_coordinates() const { return static_cast<int>(coordinate_joint.size()); }
  bool has_flexible() const { return coordinates() > joint_coordinates(); }
  bool has_prescribed() const;
};

/// Evaluates the model at the given parameter values. Throws
/// std::invalid_argument if a name cannot be resolved or an expression
/// cannot be evaluated (a loaded model has been checked, so only on misuse),
/// model::ModelError if a beam cannot be built. `same_model`: an instance of
/// the same model whose beams are reused (they do not depend on parameters).
Instance instantiate(const model::Model& model, const model::ParameterValues& parameters,
                     const Instance* same_model = nullptr);

/// The prescribed q(t), q'(t), q''(t) of a joint (the piece in effect at t;
/// zero after the last piece if that has an end).
std::array<double, 3> prescribed_motion(const JointData& joint, double t);

/// URDF's fixed-axis roll-pitch-yaw: R = Rz(yaw) Ry(pitch) Rx(roll).
Mat<double> rotation_from_rpy(double roll, double pitch, double yaw);

}  // namespace kanegen::numeric
