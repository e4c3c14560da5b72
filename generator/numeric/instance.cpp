// SPDX-License-Identifier: GPL-2.0-or-later
#include "numeric/instance.hpp"

#include <cmath>
#include <functional>
#include <map>
#include <stdexcept>

// The one use of the finite-element layer: the basis B of the elastic
// coordinates (free dofs or modal shapes), a choice of coordinates. Mass,
// stiffness, geometric stiffness and every integral are computed here
// independently (docs/verify.md).
#include "fem/elastic_model.hpp"
#include "fem/model_mesh.hpp"
#include "numeric/shape_function.hpp"
#include "numeric/solid.hpp"

namespace kanegen::numeric {
namespace {

Vec<double> vector_value(const model::Vec3& v, const model::ParameterValues& p) {
  return {model::evaluate(v[0], p), model::evaluate(v[1], p), model::evaluate(v[2], p)};
}

/// Inertia entries ixx, iyy, izz, ixy, ixz, iyz as the symmetric tensor.
Mat<double> inertia_value(const std::array<model::Scalar, 6>& in, const model::ParameterValues& p) {
  double e[6];
  for (int i = 0; i < 6; ++i) e[i] = model::evaluate(in[i], p);
  return {e[0], e[3], e[4], e[3], e[1], e[5], e[4], e[5], e[2]};
}

Vec<double> normalized(const Vec<double>& v) {
  const double length = std::sqrt(dot(v, v));
  return scale(v, 1.0 / length);
}

/// The mesh of a mesh body: its nodes (in the order of the basis rows) and
/// elements, read with the finite-element layer's reader (a file format,
/// not a derivation); the quadrature is this path's own (numeric/solid.hpp).
void mesh_data(const model::Body& body, const std::string& file, FlexibleData& d) {
  const fem::InpMesh mesh = fem::read_model_mesh(body, file);
  const fem::MeshBody layout = fem::build_model_mesh_body(body, mesh, file);
  for (int id : layout.node_ids) {
    const Eigen::Vector3d& x = mesh.nodes[mesh.node_index(id)].position;
    d.nodes.push_back({x.x(), x.y(), x.z()});
  }
  std::map<int, const fem::MeshElement*> by_id;
  for (const fem::MeshElement& e : mesh.elements) by_id[e.id] = &e;
  for (int id : layout.element_ids) {
    const fem::MeshElement& me = *by_id.at(id);
    SolidElementData e;
    e.type = fem::ccx_type_name(me.family);
    std::vector<Vec<double>> x;
    for (int n : me.nodes) {
      e.nodes.push_back(layout.node_of.at(n));
      x.push_back(d.nodes[e.nodes.back()]);
    }
    set_up_solid(e, x, body.elastic.mesh.thickness);
    d.solids.push_back(std::move(e));
  }
  d.mesh = true;
  d.planar = false;
  d.dofs_per_node = d.solids.front().dimension;
  for (const model::MeshInterface& set : body.elastic.mesh.interfaces) {
    FlexibleData::Interface in;
    for (int id : mesh.node_set(set.node_set)) in.nodes.push_back(layout.node_of.at(id));
    in.centroid = {0, 0, 0};
    for (int n : in.nodes) in.centroid = add(in.centroid, d.nodes[n]);
    in.centroid = scale(in.centroid, 1.0 / static_cast<double>(in.nodes.size()));
    Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
    for (int n : in.nodes) {
      const Vec<double> r = sub(d.nodes[n], in.centroid);
      const Eigen::Vector3d v(r[0], r[1], r[2]);
      A += v.squaredNorm() * Eigen::Matrix3d::Identity() - v * v.transpose();
    }
    // A set without a rotation (one node; in space, nodes on one line) keeps
    // inverse_A zero: only its position may be used (model::MeshInterface).
    in.inverse_A = {};
    if (d.dofs_per_node == 2) {
      if (A(2, 2) > 0) in.inverse_A[8] = 1.0 / A(2, 2);
    } else if (const Eigen::FullPivLU<Eigen::Matrix3d> lu(A); lu.isInvertible()) {
      const Eigen::Matrix3d inverse = lu.inverse();
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) in.inverse_A[3 * r + c] = inverse(r, c);
    }
    d.interfaces.push_back(std::move(in));
  }
  d.poisson = body.elastic.mesh.poisson;
}

/// A column's nonzero entries as (row, value) pairs.
std::vector<std::pair<int, double>> nonzeros(const Eigen::VectorXd& column) {
  std::vector<std::pair<int, double>> out;
  for (Eigen::Index i = 0; i < column.size(); ++i)
    if (column[i] != 0.0) out.emplace_back(static_cast<int>(i), column[i]);
  return out;
}

/// The second-order fields of a mesh body (sparse, as the basis) and the
/// basis's least-squares inverse.
void second_order_data(const Eigen::MatrixXd& basis, const Eigen::MatrixXd& fields, FlexibleData& d) {
  const Eigen::Index n = basis.cols();
  if (fields.rows() != basis.rows() || fields.cols() != n * (n + 1) / 2)
    throw std::invalid_argument("the second-order fields of body '" + d.body + "' do not match its basis");
  for (Eigen::Index k = 0; k < fields.cols(); ++k) d.second_order.push_back(nonzeros(fields.col(k)));
  // (B^T B)^-1 B^T: exact on dofs = B eta, the only dofs the path forms.
  const Eigen::MatrixXd inverse = (basis.transpose() * basis).ldlt().solve(basis.transpose());
  for (Eigen::Index k = 0; k < n; ++k) {
    const Eigen::RowVectorXd row = inverse.row(k);
    d.left_inverse.emplace_back(row.data(), row.data() + row.size());
  }
}

/// The beam of a flexible body: nodes along the segments, element axes
/// (x along the run, y = z_link x x, z = x x y), numbers, and the basis.
std::shared_ptr<const FlexibleData> beam_data(const model::Body& body, const std::string& file) {
  const model::ElasticPart& f = body.elastic;
  auto d = std::make_shared<FlexibleData>();
  d->body = body.name;
  d->planar = f.formulation == model::BeamFormulation::planar;
  d->dofs_per_node = d->planar ? 3 : 6;
  if (f.mesh.present())
    mesh_data(body, file, *d);
  else
    d->nodes.push_back({0.0, 0.0, 0.0});
  for (const model::BeamSegment& s : f.segments) {
    const Vec<double> start = d->nodes.back(), end{s.to[0], s.to[1], s.to[2]};
    const Vec<double> step = scale(sub(end, start), 1.0 / s.elements);
    const Vec<double> x = normalized(step);
    const Vec<double> y = normalized(cross(Vec<double>{0.0, 0.0, 1.0}, x));
    const Vec<double> z = cross(x, y);
    for (int i = 1; i <= s.elements; ++i) {
      BeamElementData e;
      e.node = static_cast<int>(d->nodes.size()) - 1;
      e.length = std::sqrt(dot(step, step));
      e.axes = {x[0], y[0], z[0], x[1], y[1], z[1], x[2], y[2], z[2]};
      e.origin = d->nodes.back();
      d->elements.push_back(e);
      d->nodes.push_back(i == s.elements ? end : add(start, scale(step, i)));
    }
  }
  d->A = f.A;
  d->Iz = f.Iz;
  d->Iy = d->planar ? 0.0 : f.Iy;
  d->J = d->planar ? 0.0 : f.J;
  d->E = f.E;
  d->G = f.G;
  d->density = f.density;
  d->fibre_y = f.fibre_y;
  d->fibre_z = f.fibre_z;
  if (f.tip_mass > 0) {
    d->tip_mass = f.tip_mass;
    const auto& i = f.tip_inertia;
    d->tip_inertia = {i[0], i[3], i[4], i[3], i[1], i[5], i[4], i[5], i[2]};
  }
  // Assumed modes are amplitudes of whole-beam shapes too: named as modes.
  d->modal = f.modes > 0 || !f.assumed_modes.empty();
  if (d->modal && f.modal_damping > 0) {
    d->modal_ratio = f.modal_damping;
  } else {
    d->rayleigh_alpha = f.rayleigh_alpha;
    d->rayleigh_beta = f.rayleigh_beta;
  }
  d->stiffening = f.geometric_stiffening;

  const auto built = fem::build_elastic_model(body, file, sample_shape);
  const Eigen::MatrixXd& basis = built.reduced.basis;
  if (basis.rows() != d->num_dofs())
    throw std::invalid_argument("the basis of body '" + body.name + "' has " + std::to_string(basis.rows()) +
                                " rows for " + std::to_string(d->num_dofs()) + " dofs");
  static const char* planar_kinds[3] = {"u", "v", "theta_z"};
  static const char* spatial_kinds[6] = {"u", "v", "w", "theta_x", "theta_y", "theta_z"};
  for (Eigen::Index k = 0; k < basis.cols(); ++k) {
    std::vector<std::pair<int, double>> column = nonzeros(basis.col(k));
    if (d->modal) {
      d->names.push_back("mode" + std::to_string(k + 1));
    } else {
      // A nodal coordinate is one free dof.
      if (column.size() != 1 || column[0].second != 1.0)
        throw std::invalid_argument("nodal coordinate " + std::to_string(k) + " of body '" + body.name +
                                    "' is not a single dof");
      const int dof = column[0].first;
      d->names.push_back("n" + std::to_string(dof / d->dofs_per_node) + "." +
                         (d->planar ? planar_kinds : spatial_kinds)[dof % d->dofs_per_node]);
    }
    d->basis.push_back(std::move(column));
  }
  if (d->mesh && d->shortens()) second_order_data(basis, built.second_order, *d);
  return d;
}

}  // namespace

int Instance::constraints() const {
  int rows = 0;
  for (const LoopData& l : loops) rows += static_cast<int>(l.rows.size());
  return rows;
}

bool Instance::has_prescribed() const {
  for (const JointData& j : joints)
    if (j.is_prescribed()) return true;
  return false;
}

std::array<double, 3> prescribed_motion(const JointData& joint, double t) {
  using D1 = Dual<double>;
  using D2 = Dual<D1>;
  for (const PrescribedData& piece : joint.prescribed) {
    if (piece.has_until && !(t < piece.until)) continue;
    const D2 q = piece.q(D2(D1(t, 1.0), D1(1.0, 0.0)));
    return {q.v.v, q.d.v, q.d.d};
  }
  return {0.0, 0.0, 0.0};
}

Mat<double> rotation_from_rpy(double roll, double pitch, double yaw) {
  const double cr = std::cos(roll), sr = std::sin(roll);
  const double cp = std::cos(pitch), sp = std::sin(pitch);
  const double cy = std::cos(yaw), sy = std::sin(yaw);
  const Mat<double> rx{1, 0, 0, 0, cr, -sr, 0, sr, cr};
  const Mat<double> ry{cp, 0, sp, 0, 1, 0, -sp, 0, cp};
  const Mat<double> rz{cy, -sy, 0, sy, cy, 0, 0, 0, 1};
  return mul(rz, mul(ry, rx));
}

namespace {

/// The model being instantiated, at parameter values p, and the bodies'
/// indices by name.
struct Instantiation {
  const model::Model& model;
  const model::ParameterValues& p;
  Instance& m;
  std::map<std::string, int> body_index;

  int body_of(const std::string& name, const std::string& what) const {
    if (name == model.ground) return -1;
    const auto found = body_index.find(name);
    if (found == body_index.end()) throw std::invalid_argument("unknown body '" + name + "' in " + what);
    return found->second;
  }
  /// Whether `node` (-1: none) is a node of `body`'s beam.
  bool has_node(int body, int node) const {
    if (node < 0) return true;
    if (body < 0 || !m.bodies[body].elastic) return false;
    const FlexibleData& f = *m.bodies[body].elastic;
    return node < static_cast<int>(f.mesh ? f.interfaces.size() : f.nodes.size());
  }
  int coordinate_of(const std::string& joint) const {
    for (const JointData& j : m.joints)
      if (j.name == joint) return j.coordinate;
    return -1;
  }
};

void add_bodies(Instantiation& in, const Instance* same_model) {
  for (std::size_t i = 0; i < in.model.bodies.size(); ++i) {
    const model::Body& b = in.model.bodies[i];
    in.body_index[b.name] = static_cast<int>(in.m.bodies.size());
    BodyData d{
        b.name,  -1, model::evaluate(b.mass, in.p), vector_value(b.com, in.p), inertia_value(b.inertia, in.p),
        nullptr, -1};
    if (b.flexible)
      d.elastic = same_model && i < same_model->bodies.size() && same_model->bodies[i].elastic
                      ? same_model->bodies[i].elastic
                      : beam_data(b, in.model.source_file);
    in.m.bodies.push_back(d);
  }
}

/// The numeric path's own joint table: how each type moves its child
/// (numeric/poses.hpp applies it). The symbolic stages have theirs
/// (kinematics/joint_model.*); keeping two is what lets `kanegen verify`
/// catch a mistake in either. No default: a new type is a compile error here.
Motion motion_of(model::JointType type) {
  switch (type) {
    case model::JointType::revolute:
    case model::JointType::continuous:
      return Motion::rotation;
    case model::JointType::prismatic:
      return Motion::translation;
    case model::JointType::fixed:
      return Motion::none;
    case model::JointType::planar:  // compound: the loaders made it primitive steps
    case model::JointType::free:
      throw std::logic_error("a compound joint type reached the numeric path (model/joint_expansion.hpp)");
    case model::JointType::spherical:
      return Motion::ball;
  }
  return Motion::none;
}

JointData joint_data(const Instantiation& in, const model::Joint& j) {
  const model::ParameterValues& p = in.p;
  JointData d;
  d.name = j.name;
  d.parent = in.body_of(j.parent, "joint '" + j.name + "'");
  d.parent_node = j.parent_node;
  if (d.parent_node >= 0 && (d.parent < 0 || !in.m.bodies[d.parent].elastic))
    throw std::invalid_argument("joint '" + j.name + "' sits on a node of a body that is not flexible");
  d.child = in.body_of(j.child, "joint '" + j.name + "'");
  if (d.child < 0) throw std::invalid_argument("joint '" + j.name + "' has the ground as its child");
  const Vec<double> rpy = vector_value(j.origin_rpy, p);
  d.origin_rotation = rotation_from_rpy(rpy[0], rpy[1], rpy[2]);
  d.origin_position = vector_value(j.origin_xyz, p);
  // Normalised here as well, so that the path does not rely on the loader having done it.
  const double length = std::sqrt(j.axis[0] * j.axis[0] + j.axis[1] * j.axis[1] + j.axis[2] * j.axis[2]);
  d.axis = {j.axis[0] / length, j.axis[1] / length, j.axis[2] / length};
  if (!j.moves()) return d;
  d.motion = motion_of(j.type);
  d.coordinate = in.m.coordinates();
  d.stiffness = model::evaluate(j.spring_stiffness, p);
  d.rest = model::evaluate(j.spring_rest, p);
  d.damping = model::evaluate(j.damping, p);
  d.actuated = j.actuated;
  for (const model::PrescribedPiece& piece : j.prescribed)
    d.prescribed.push_back({TimeFunction(piece.q, p), piece.has_until, piece.until});
  return d;
}

void add_joints(Instantiation& in) {
  Instance& m = in.m;
  for (const model::Joint& j : in.model.joints) {
    const JointData d = joint_data(in, j);
    if (d.motion == Motion::ball) {
      m.ball_joints.push_back(static_cast<int>(m.joints.size()));
      for (const char* axis : {"_qx", "_qy", "_qz"}) {
        m.coordinate_joint.push_back(static_cast<int>(m.joints.size()));
        m.coordinate_names.push_back(j.name + axis);
      }
    } else if (j.moves()) {
      m.coordinate_joint.push_back(static_cast<int>(m.joints.size()));
      m.coordinate_names.push_back(j.name);
    }
    m.bodies[d.child].joint = static_cast<int>(m.joints.size());
    m.joints.push_back(d);
  }
}

/// Parents first: a body after its parent (the tree has been checked for cycles).
void order_bodies(Instance& m) {
  std::vector<bool> placed(m.bodies.size(), false);
  const std::function<void(int)> place = [&](int b) {
    if (b < 0 || placed[b]) return;
    if (m.bodies[b].joint < 0)
      throw std::invalid_argument("body '" + m.bodies[b].name + "' hangs from no joint");
    placed[b] = true;  // set before recursing, so a cycle cannot recurse forever
    place(m.joints[m.bodies[b].joint].parent);
    m.order.push_back(b);
  };
  for (std::size_t b = 0; b < m.bodies.size(); ++b) place(static_cast<int>(b));
}

/// The elastic coordinates follow the joints', body by body.
void add_elastic_coordinates(Instance& m) {
  for (BodyData& b : m.bodies) {
    if (!b.elastic) continue;
    b.elastic_first = m.coordinates();
    for (const std::string& name : b.elastic->names) m.coordinate_names.push_back(b.name + "." + name);
  }
}

void add_force_elements(Instantiation& in) {
  const model::ParameterValues& p = in.p;
  Instance& m = in.m;
  for (const model::PointForce& f : in.model.forces) {
    m.forces.push_back({f.name, in.body_of(f.body, "force '" + f.name + "'"), vector_value(f.point, p),
                        f.node, vector_value(f.force, p), f.frame == model::ForceFrame::body});
    const ForceData& d = m.forces.back();
    if (d.node >= 0 && !(d.body >= 0 && in.has_node(d.body, d.node)))
      throw std::invalid_argument("force '" + f.name + "' is at a node the body does not have");
  }
  for (const model::Spring& s : in.model.springs)
    m.springs.push_back({s.name, in.body_of(s.body, "spring '" + s.name + "'"), vector_value(s.point, p),
                         in.body_of(s.body2, "spring '" + s.name + "'"), vector_value(s.point2, p),
                         model::evaluate(s.stiffness, p), model::evaluate(s.rest_length, p),
                         model::evaluate(s.damping, p)});
  for (const model::JointEffort& f : in.model.joint_efforts) {
    EffortData d;
    d.name = f.name;
    d.coordinate = in.coordinate_of(f.joint);
    if (d.coordinate < 0) throw std::invalid_argument("joint effort '" + f.name + "' names no moving joint");
    d.varies = !f.value.is_literal;
    if (d.varies)
      d.function = TimeFunction(f.value.text, p);
    else
      d.value = f.value.value;
    m.efforts.push_back(d);
  }
}

void add_loops(Instantiation& in) {
  for (const model::Loop& l : in.model.loops) {
    LoopData d;
    d.name = l.name;
    d.type = l.type;
    d.planar = l.planar;
    d.body = in.body_of(l.body, "loop '" + l.name + "'");
    d.node = l.node;
    d.point = vector_value(l.point, in.p);
    d.body2 = in.body_of(l.body2, "loop '" + l.name + "'");
    d.node2 = l.node2;
    d.point2 = vector_value(l.point2, in.p);
    d.axis = normalized(Vec<double>{l.axis[0], l.axis[1], l.axis[2]});
    d.rows = model::loop_rows(l);
    if (!in.has_node(d.body, d.node) || !in.has_node(d.body2, d.node2))
      throw std::invalid_argument("loop '" + l.name + "' is at a node its body does not have");
    in.m.loops.push_back(d);
  }
}

OutputData output_data(const Instantiation& in, const model::Output& o) {
  OutputData d;
  d.name = o.name;
  d.kind = o.kind;
  if (o.kind == model::OutputKind::reaction) {
    for (std::size_t k = 0; k < in.m.loops.size(); ++k)
      if (in.m.loops[k].name == o.loop) d.loop = static_cast<int>(k);
    if (d.loop < 0) throw std::invalid_argument("output '" + o.name + "' names no loop");
  } else if (o.kind == model::OutputKind::point_position) {
    d.body = in.body_of(o.body, "output '" + o.name + "'");
    d.point = vector_value(o.point, in.p);
  } else if (o.kind != model::OutputKind::joint_coordinate && o.kind != model::OutputKind::joint_speed) {
    d.body = in.body_of(o.body, "output '" + o.name + "'");
    d.node = o.node;
    if (d.body < 0 || d.node < 0 || !in.has_node(d.body, d.node))
      throw std::invalid_argument("output '" + o.name + "' names no node of a flexible body");
  } else {
    d.coordinate = in.coordinate_of(o.joint);
    if (d.coordinate < 0) throw std::invalid_argument("output '" + o.name + "' names no moving joint");
  }
  return d;
}

}  // namespace

Instance instantiate(const model::Model& model, const model::ParameterValues& p, const Instance* same_model) {
  Instance m;
  Instantiation in{model, p, m, {}};
  add_bodies(in, same_model);
  add_joints(in);
  order_bodies(m);
  add_elastic_coordinates(m);
  m.gravity = vector_value(model.gravity, p);
  add_force_elements(in);
  add_loops(in);
  for (const model::Output& o : model.outputs) m.outputs.push_back(output_data(in, o));
  m.output_columns = model::output_columns(model);
  return m;
}

}  // namespace kanegen::numeric
