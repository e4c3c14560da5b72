#include "numeric/instance.hpp"

#include <cmath>
#include <functional>
#include <map>
#include <stdexcept>

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

}  // namespace

Mat<double> rotation_from_rpy(double roll, double pitch, double yaw) {
  const double cr = std::cos(roll), sr = std::sin(roll);
  const double cp = std::cos(pitch), sp = std::sin(pitch);
  const double cy = std::cos(yaw), sy = std::sin(yaw);
  const Mat<double> rx{1, 0, 0, 0, cr, -sr, 0, sr, cr};
  const Mat<double> ry{cp, 0, sp, 0, 1, 0, -sp, 0, cp};
  const Mat<double> rz{cy, -sy, 0, sy, cy, 0, 0, 0, 1};
  return mul(rz, mul(ry, rx));
}

Instance instantiate(const model::Model& model, const model::ParameterValues& p) {
  Instance m;
  std::map<std::string, int> body_index;
  for (const model::Body& b : model.bodies) {
    body_index[b.name] = static_cast<int>(m.bodies.size());
    m.bodies.push_back(
        {b.name, -1, model::evaluate(b.mass, p), vector_value(b.com, p), inertia_value(b.inertia, p)});
  }
  const auto body_of = [&](const std::string& name, const std::string& what) {
    if (name == model.ground) return -1;
    const auto found = body_index.find(name);
    if (found == body_index.end()) throw std::invalid_argument("unknown body '" + name + "' in " + what);
    return found->second;
  };

  for (const model::Joint& j : model.joints) {
    JointData d;
    d.name = j.name;
    d.parent = body_of(j.parent, "joint '" + j.name + "'");
    d.child = body_of(j.child, "joint '" + j.name + "'");
    if (d.child < 0) throw std::invalid_argument("joint '" + j.name + "' has the ground as its child");
    const Vec<double> rpy = vector_value(j.origin_rpy, p);
    d.origin_rotation = rotation_from_rpy(rpy[0], rpy[1], rpy[2]);
    d.origin_position = vector_value(j.origin_xyz, p);
    // Normalised here as well, so that the path does not rely on the loader having done it.
    const double length = std::sqrt(j.axis[0] * j.axis[0] + j.axis[1] * j.axis[1] + j.axis[2] * j.axis[2]);
    d.axis = {j.axis[0] / length, j.axis[1] / length, j.axis[2] / length};
    if (j.moves()) {
      d.motion = j.type == model::JointType::prismatic ? Motion::translation : Motion::rotation;
      d.coordinate = m.coordinates();
      m.coordinate_joint.push_back(static_cast<int>(m.joints.size()));
      d.stiffness = model::evaluate(j.spring_stiffness, p);
      d.rest = model::evaluate(j.spring_rest, p);
      d.damping = model::evaluate(j.damping, p);
      d.actuated = j.actuated;
    }
    m.bodies[d.child].joint = static_cast<int>(m.joints.size());
    m.joints.push_back(d);
  }

  // Parents first: place a body after placing its parent (the tree has been checked for cycles).
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

  m.gravity = vector_value(model.gravity, p);
  for (const model::PointForce& f : model.forces)
    m.forces.push_back({f.name, body_of(f.body, "force '" + f.name + "'"), vector_value(f.point, p),
                        vector_value(f.force, p), f.frame == model::ForceFrame::body});
  for (const model::Output& o : model.outputs) {
    OutputData d;
    d.name = o.name;
    d.kind = o.kind;
    if (o.kind == model::OutputKind::point_position) {
      d.body = body_of(o.body, "output '" + o.name + "'");
      d.point = vector_value(o.point, p);
    } else {
      for (const JointData& j : m.joints)
        if (j.name == o.joint) d.coordinate = j.coordinate;
      if (d.coordinate < 0) throw std::invalid_argument("output '" + o.name + "' names no moving joint");
    }
    m.outputs.push_back(d);
  }
  return m;
}

}  // namespace kanegen::numeric
