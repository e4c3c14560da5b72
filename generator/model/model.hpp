// SPDX-License-Identifier: GPL-2.0-or-later
// The mechanism as plain data: what the model file says, checked and
// normalised, with no algorithm attached (as Pinocchio's Model and MuJoCo's
// mjModel). Loaders fill it; the symbolic stages only read it.
#pragma once

#include <array>
#include <map>
#include <string>
#include <vector>

#include "model/joint_types.hpp"

namespace kanegen::model {

/// A scalar quantity of the model. Either a plain number (folded into the
/// generated code) or an expression over named parameters ("m1", "0.5*l1"),
/// which stays symbolic and can be changed at run time through Params.
struct Scalar {
  bool is_literal = true;
  double value = 0.0;  ///< the number when is_literal
  std::string text;    ///< the expression when !is_literal
  std::string where;   ///< JSON pointer or URDF element, for error messages

  static Scalar number(double v, std::string where_ = {}) {
    Scalar s;
    s.value = v;
    s.where = std::move(where_);
    return s;
  }
  static Scalar expression(std::string t, std::string where_ = {}) {
    Scalar s;
    s.is_literal = false;
    s.text = std::move(t);
    s.where = std::move(where_);
    return s;
  }
};

using Vec3 = std::array<Scalar, 3>;

/// A named parameter; its default value is what Params starts with.
struct Parameter {
  std::string name;
  double value = 0.0;
  std::string where;
};

enum class BeamFormulation { planar, spatial };
enum class BeamSupport { clamped, pinned_pinned, free };

/// A straight run of equal beam elements, from the end of the previous run
/// (the body frame's origin for the first) to `to`, in the body frame.
struct BeamSegment {
  std::array<double, 3> to{0.0, 0.0, 0.0};
  int elements = 0;
  std::string where;
};

/// An assumed mode of a flexible beam (Rayleigh-Ritz): the displacement of
/// the beam axis per unit amplitude, link-frame components, as expressions
/// in the beam coordinate x (0 to L, m), the beam length L, pi and the model
/// parameters. Planar beams have only u and v.
struct AssumedMode {
  std::string u = "0";      ///< along link x (axial)
  std::string v = "0";      ///< along link y (bending in x-y)
  std::string w = "0";      ///< along link z (bending in x-z; spatial)
  std::string theta = "0";  ///< the section's rotation about link x (torsion; spatial)
  std::string where;        ///< JSON pointer of the mode
};

/// The elements of the internal mesh that carries assumed modes when the
/// model gives none: the shapes are sampled at its nodes (docs/flexible-bodies.md).
inline constexpr int kAssumedModeElements = 100;

/// A node set of a mesh body that something attaches to: one averaging
/// interface, however many joints, loops, forces and outputs name it.
struct MeshInterface {
  std::string node_set;
  std::string where;  ///< the place that first named it
  /// The first place that needs its rotation (a joint frame, a hinge or a
  /// slider's line turning with it); empty if only its position is used
  /// (forces, displacements, spherical and planar hinges), which a set of
  /// one node (or of nodes on one line, in space) also has.
  std::string rotation_where;
};

/// K and M of a mesh body from a solver's files instead of the elements
/// (fem/ccx_matrices.hpp): CalculiX's *FREQUENCY, SOLVER=MATRIXSTORAGE output.
struct MeshMatrices {
  std::string stiffness, mass, dofs;  ///< resolved against the model file's directory
  std::string where;                  ///< JSON pointer of "matrices"

  bool present() const { return !stiffness.empty(); }
};

/// A flexible body meshed with plane or solid elements (a CalculiX/Abaqus
/// .inp file, e.g. from Gmsh) instead of a beam. The mesh's coordinates are
/// the body frame's. Read and reduced when code is generated
/// (fem/elastic_model.hpp); the model keeps only what the file says.
struct MeshSource {
  std::string file;         ///< as the model file gives it
  std::string path;         ///< resolved against the model file's directory
  std::string element_set;  ///< empty: every element of the mesh's highest dimension
  double thickness = 1.0;   ///< plane elements, m
  double poisson = 0.0;     ///< nu; E and density are ElasticPart's
  /// The node set held fixed in the body frame (support "clamped"): the
  /// body's joint acts on it. Empty with support "free".
  std::string clamped_set;
  /// The node sets that joints, loops, point forces and node outputs name
  /// ("parent_node_set", "node_set", "node_set2"), in the order check_model
  /// first meets them; their node (parent_node, node, node2) is the index
  /// here. Each is an averaging interface (fem/model_mesh.hpp).
  std::vector<MeshInterface> interfaces;
  /// Craig-Bampton: the coordinates are the static shapes of the interfaces'
  /// rigid motions, then the first `modes` fixed-interface modes.
  bool craig_bampton = false;
  /// Imported K and M; the mesh then gives the nodes, sets and inertia invariants.
  MeshMatrices matrices;
  std::string where;  ///< JSON pointer of "mesh"

  bool present() const { return !file.empty(); }
};

/// The elastic part of a flexible body, in its link (body) frame (the
/// model file's "flexible"): a finite-element beam (segments and a
/// section), a beam of assumed modes, or a mesh of plane or solid elements
/// (`mesh`), with the material, damping, stiffening and initial values they
/// share. Its data are numbers: the element matrices and the modal basis are
/// computed when the code is generated. A beam's nodes are numbered from 0
/// at the frame's origin along the segments.
struct ElasticPart {
  BeamFormulation formulation = BeamFormulation::planar;
  std::vector<BeamSegment> segments;
  double A = 0.0, Iy = 0.0, Iz = 0.0, J = 0.0;  ///< section: m^2, m^4
  double fibre_y = 0.0, fibre_z = 0.0;          ///< distance to the extreme fibre (stress outputs), m
  double E = 0.0, G = 0.0, density = 0.0;       ///< Pa, Pa, kg/m^3
  BeamSupport support = BeamSupport::clamped;
  int modes = 0;  ///< 0: nodal coordinates; k: the first k modes
  /// Non-empty: the amplitudes of these shapes are the coordinates (no
  /// `modes`; `support` does not apply). The beam is one run along +x.
  std::vector<AssumedMode> assumed_modes;
  /// The parameters' default values, which the assumed modes are evaluated
  /// at (filled by check_model; the shapes are fixed when code is generated).
  std::map<std::string, double> shape_parameters;
  double tip_mass = 0.0;
  std::array<double, 6> tip_inertia{};  ///< about the last node, body axes: ixx, iyy, izz, ixy, ixz, iyz
  double rayleigh_alpha = 0.0, rayleigh_beta = 0.0;  ///< damping alpha M + beta K
  double modal_damping = 0.0;                        ///< damping ratio of every mode (modal coordinates)
  bool geometric_stiffening = true;
  /// Initial values of elastic coordinates, by their names without the body
  /// prefix (model/elastic_coordinates.hpp: "n3.v", "mode2"); the others start at 0.
  std::map<std::string, double> initial_q, initial_u;
  /// Present: the body is this mesh, not a beam (no segments, section or
  /// assumed modes; modal coordinates only).
  MeshSource mesh;
  std::string where;

  int num_elements() const {
    int n = 0;
    for (const BeamSegment& s : segments) n += s.elements;
    return n;
  }
  int num_nodes() const { return num_elements() + 1; }
};

/// A body. Frame: the body frame is the child frame of the joint that
/// carries it. Inertia is about the centre of mass, in body-frame axes. A
/// flexible body adds its elastic part (a beam or a mesh) to this rigid part
/// (which may be massless).
struct Body {
  std::string name;
  Scalar mass;
  Vec3 com;                       ///< centre of mass in the body frame
  std::array<Scalar, 6> inertia;  ///< ixx, iyy, izz, ixy, ixz, iyz
  bool flexible = false;
  ElasticPart elastic;  ///< when flexible
  std::string where;
};

/// A node index meaning a flexible body's last node ("tip" in a model file),
/// until check_model resolves it.
constexpr int kTipNode = -2;

/// One piece of a prescribed motion: q(t) = `q` while t < `until` (the last
/// piece has no end).
struct PrescribedPiece {
  std::string q;  ///< expression in t and the parameters
  bool has_until = false;
  double until = 0.0;
  std::string where;
};

/// A joint between a parent body (or the ground) and a child body.
/// The child frame is the parent frame moved by origin (xyz, then rpy as
/// URDF: R = Rz(yaw) Ry(pitch) Rx(roll)) and then by the joint motion
/// along or about `axis` (expressed in the joint frame, unit length).
struct Joint {
  std::string name;
  JointType type = JointType::revolute;
  std::string parent;  ///< body name, or Model::ground
  std::string child;   ///< body name
  Vec3 origin_xyz;
  Vec3 origin_rpy;
  std::array<double, 3> axis{0.0, 0.0, 1.0};
  Scalar spring_stiffness;  ///< generalized spring: -k (q - rest)
  Scalar spring_rest;
  Scalar damping;        ///< generalized damper: -c u
  bool actuated = true;  ///< has an input torque/force tau
  double q0 = 0.0;       ///< initial coordinate
  double u0 = 0.0;       ///< initial speed
  /// The initial coordinates and speeds of a joint of several coordinates
  /// (planar, spherical, free), in the order a model file gives them (a
  /// spherical joint's quaternion w, x, y, z), or empty for zeros (the
  /// identity quaternion); the expansion gives a compound joint's to its steps.
  std::vector<double> step_q0, step_u0;
  /// The node of a flexible parent the joint sits on (-1: the parent's
  /// frame). The joint frame then moves and turns with the node.
  int parent_node = -1;
  /// Or: the node set of a mesh parent it sits on (its averaged motion);
  /// check_model turns it into parent_node, an index of the parent's
  /// mesh.interfaces.
  std::string parent_node_set;
  /// A coordinate given as a function of time: it stays in the state, and
  /// its acceleration is imposed (the second derivative). Empty: a free
  /// coordinate.
  std::vector<PrescribedPiece> prescribed;
  /// Marked as an independent coordinate of a closed loop: assembly keeps it.
  bool independent = false;
  std::string where;

  bool moves() const { return joint_type_info(type).coordinates > 0; }
  bool is_prescribed() const { return !prescribed.empty(); }
};

enum class ForceFrame { world, body };

/// A constant force applied at a point fixed in a body, or at a node of a
/// flexible body.
struct PointForce {
  std::string name;
  std::string body;
  Vec3 point;     ///< in the body frame
  int node = -1;  ///< or: at this node of a flexible body, moving with it
  /// Or: at this node set of a mesh body (check_model makes it `node`, an
  /// index of the body's mesh.interfaces).
  std::string node_set;
  Vec3 force;  ///< in `frame` axes
  ForceFrame frame = ForceFrame::world;
  std::string where;
};

/// A linear spring-damper between a point of `body` and a point of `body2`
/// (or of the ground). With l the distance between the points, it pulls
/// the first point towards the second with -(k (l - l0) + c l_dot) along
/// the line between them and the second with the opposite force; its
/// potential energy is k (l - l0)^2 / 2. Singular at l = 0, where the line
/// (the gradient of l) is undefined.
struct Spring {
  std::string name;
  std::string body;    ///< the first point's body (not the ground)
  Vec3 point;          ///< in `body`'s frame
  std::string body2;   ///< a body, or Model::ground
  Vec3 point2;         ///< in `body2`'s frame; world axes on the ground
  Scalar stiffness;    ///< k, N/m
  Scalar rest_length;  ///< l0, m
  Scalar damping;      ///< c, N s/m
  std::string where;
};

/// A generalized force (a torque on a revolute joint, a force on a
/// prismatic one) on the coordinate of a moving joint: a scalar, or an
/// expression in the parameters and the time t (so `value.text` may name t,
/// unlike other scalars).
struct JointEffort {
  std::string name;
  std::string joint;
  Scalar value;  ///< N m or N
  std::string where;
};

enum class OutputKind {
  point_position,
  joint_coordinate,
  joint_speed,
  node_displacement,  ///< NAME.x, .y, .z: the node's elastic displacement, body axes
  axial_force,        ///< N at the node (tension positive)
  bending_moment,     ///< planar: M_z; spatial: NAME.y, NAME.z (M_y, M_z)
  bending_stress,     ///< peak |N/A| + |M_z| fibre_y/Iz (+ |M_y| fibre_z/Iy) at the node
  reaction            ///< a loop's constraint force, one column per constraint equation
};

/// A named quantity written by `simulate`. A point position expands to the
/// three columns NAME.x, NAME.y, NAME.z (world frame).
struct Output {
  std::string name;
  OutputKind kind = OutputKind::point_position;
  std::string body;      ///< for point_position
  Vec3 point;            ///< for point_position, in the body frame
  std::string joint;     ///< for joint_coordinate / joint_speed
  int node = -1;         ///< for the node outputs of a flexible body
  std::string node_set;  ///< or a node set of a mesh body (check_model makes it `node`)
  std::string loop;      ///< for reaction
  std::string where;
};

enum class LoopType { revolute, spherical, slider };

/// A joint that closes a loop: it ties a point of `body` (or one of its
/// nodes) to a point of `body2` (or the ground) instead of adding a body to
/// the tree. Its equations Phi(q) = 0 are position differences in world
/// axes: planar loops keep the components normal to `axis` (world), a
/// spatial revolute adds the hinge alignment, a slider keeps the components
/// across its line.
struct Loop {
  std::string name;
  LoopType type = LoopType::revolute;
  bool planar = false;
  std::string body, body2;  ///< body2 may be Model::ground
  Vec3 point, point2;       ///< in the bodies' frames (world axes for the ground)
  int node = -1, node2 = -1;
  /// Or: node sets of mesh bodies (check_model makes them node and node2).
  std::string node_set, node_set2;
  std::array<double, 3> axis{0.0, 0.0, 1.0};  ///< unit; see the type
  std::string where;
};

struct Model {
  std::string name;               ///< a C++ identifier; names the namespace and files
  std::string source_file;        ///< the file it was loaded from
  std::string ground = "ground";  ///< the fixed body's name (URDF: the root link)

  std::vector<Parameter> parameters;
  std::vector<Body> bodies;
  std::vector<Joint> joints;  ///< file order; moving joints give the coordinates in this order
  Vec3 gravity;               ///< world frame, m/s^2
  /// The entries of a model file's "forces", by type (each keeps its
  /// /forces/N place); their names share one namespace.
  std::vector<PointForce> forces;
  std::vector<Spring> springs;
  std::vector<JointEffort> joint_efforts;
  std::vector<Loop> loops;  ///< loop-closing joints; empty for a tree
  std::vector<Output> outputs;
};

}  // namespace kanegen::model
