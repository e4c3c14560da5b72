// SPDX-License-Identifier: GPL-2.0-or-later
#include "animate/viewer_data.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>

#include "animate/scene.hpp"
#include "animate/script_text.hpp"
#include "animate/surface.hpp"
#include "animate/vtk_writer.hpp"
#include "kanegen/runtime/text.hpp"

namespace kanegen::animate {
namespace {

using numeric::Vec;

/// Nine digits: what float32 holds, and less text than a double's seventeen.
std::string short_number(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.9g", value);
  return buffer;
}

template <class T>
std::string number_list(const std::vector<T>& values) {
  std::string s = "[";
  for (std::size_t i = 0; i < values.size(); ++i) s += (i ? "," : "") + short_number(double(values[i]));
  return s + "]";
}

std::string point_list(const std::vector<Vec<double>>& points) {
  std::vector<double> flat;
  for (const auto& p : points) flat.insert(flat.end(), p.begin(), p.end());
  return number_list(flat);
}

/// The smallest box around every point drawn over the run, for the camera.
struct Bounds {
  Vec<double> low{std::numeric_limits<double>::max(), std::numeric_limits<double>::max(),
                  std::numeric_limits<double>::max()};
  Vec<double> high{-low[0], -low[1], -low[2]};
  void add(const Vec<double>& p) {
    for (int i = 0; i < 3; ++i) low[i] = std::min(low[i], p[i]), high[i] = std::max(high[i], p[i]);
  }
};

/// Per frame, per body its position and rotation as a quaternion (x, y, z,
/// w), kept on the side of the last frame's so the page interpolates the
/// short way; per frame, per elastic node its displacement.
struct Frames {
  std::vector<float> poses, moves;
  Bounds bounds;
};

void add_pose(Frames& frames, const numeric::Pose<double>& pose, Eigen::Quaterniond* last) {
  Eigen::Matrix3d rotation;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) rotation(i, j) = pose.rotation[3 * i + j];
  Eigen::Quaterniond q(rotation);
  if (q.dot(*last) < 0) q.coeffs() *= -1;
  *last = q;
  for (double x : {pose.origin[0], pose.origin[1], pose.origin[2], q.x(), q.y(), q.z(), q.w()})
    frames.poses.push_back(static_cast<float>(x));
}

Frames frames_of(const ViewerRun& run) {
  const numeric::Instance& instance = *run.instance;
  Frames frames;
  std::vector<Eigen::Quaterniond> last(instance.bodies.size(), Eigen::Quaterniond::Identity());
  std::vector<double> q(run.coordinate_columns.size());
  for (std::size_t row : run.rows) {
    for (std::size_t i = 0; i < q.size(); ++i) q[i] = run.table->rows[row][run.coordinate_columns[i]];
    const BodyStates states = body_states(instance, q);
    for (std::size_t b = 0; b < instance.bodies.size(); ++b) {
      const numeric::Pose<double>& pose = states.poses[b];
      add_pose(frames, pose, &last[b]);
      frames.bounds.add(pose.origin);
      const auto world = [&](const Vec<double>& p) {
        return numeric::add(pose.origin, numeric::mul(pose.rotation, p));
      };
      if (b < run.shapes.size())
        for (const Shape& shape : run.shapes[b])
          for (const auto& p : shape.points) frames.bounds.add(world(p));
      for (std::size_t n = 0; n < states.node_moves[b].size(); ++n) {
        const Vec<double>& move = states.node_moves[b][n];
        for (double x : move) frames.moves.push_back(static_cast<float>(x));
        frames.bounds.add(
            world(numeric::add(instance.bodies[b].elastic->nodes[n], numeric::scale(move, run.scale))));
      }
    }
  }
  return frames;
}

std::string elastic_json(const numeric::FlexibleData& f, int first_node) {
  std::string s = "{\"kind\":\"" + std::string(f.mesh ? "mesh" : "beam") +
                  "\",\"first\":" + std::to_string(first_node) + ",\"nodes\":" + point_list(f.nodes);
  if (f.mesh) {
    const Surface surface = mesh_surface(f);
    s += ",\"triangles\":" + number_list(surface.triangles) + ",\"edges\":" + number_list(surface.edges);
  }
  return s + "}";
}

/// The page's name of how a joint moves its child (templates/viewer.html.in
/// draws its glyph by it). No default: a new motion is a compile error here.
const char* motion_name(numeric::Motion motion) {
  switch (motion) {
    case numeric::Motion::none:
      return "fixed";
    case numeric::Motion::rotation:
      return "turn";
    case numeric::Motion::translation:
      return "slide";
    case numeric::Motion::ball:
      return "ball";
  }
  return "fixed";
}

/// A rigid part's shape: its kind, name (untrusted: a JSON string safe in a <script>), points (body
/// frame) and faces (a hexahedron's too: the page draws a box's 12 edges from its 8 points).
std::string shape_json(const Shape& shape) {
  std::string faces = "[";
  for (std::size_t f = 0; f < shape.faces.size(); ++f) faces += (f ? "," : "") + number_list(shape.faces[f]);
  return "{\"kind\":\"" + shape.kind + "\",\"name\":" + script_json_string(shape.name) +
         ",\"points\":" + point_list(shape.points) + ",\"faces\":" + faces +
         "],\"hexahedron\":" + (shape.hexahedron ? "true" : "false") + "}";
}

std::string body_json(const numeric::Instance& instance, std::size_t b, const std::vector<Shape>& shapes,
                      int first_node) {
  const numeric::BodyData& body = instance.bodies[b];
  static const numeric::JointData none{};  // a body no joint carries: drawn where it is, no glyph
  const numeric::JointData& joint = body.joint >= 0 ? instance.joints[body.joint] : none;
  std::string s = "{\"name\":" + script_json_string(body.name) +
                  ",\"joint\":" + script_json_string(joint.name) + ",\"motion\":\"" +
                  motion_name(joint.motion) + "\"" + ",\"axis\":" + point_list({joint.axis}) +
                  ",\"mass\":" + short_number(body.mass);
  s += ",\"shapes\":[";
  for (std::size_t k = 0; k < shapes.size(); ++k) s += (k ? "," : "") + shape_json(shapes[k]);
  s += "]";
  s += ",\"elastic\":" + (body.elastic ? elastic_json(*body.elastic, first_node) : std::string("null"));
  return s + "}";
}

std::string columns_json(const ViewerRun& run) {
  std::string names = "[", series = "[";
  for (std::size_t c = 0; c < run.table->columns.size(); ++c) {
    std::vector<double> values;
    for (std::size_t row : run.rows) values.push_back(run.table->rows[row][c]);
    names += (c ? "," : "") + script_json_string(run.table->columns[c]);
    series += (c ? "," : "") + number_list(values);
  }
  return "\"columns\":" + names + "],\"series\":" + series + "]";
}

}  // namespace

std::string float32_base64(const std::vector<float>& values) {
  std::vector<unsigned char> bytes(4 * values.size());
  for (std::size_t i = 0; i < values.size(); ++i) {
    std::uint32_t bits = 0;
    std::memcpy(&bits, &values[i], 4);
    for (int k = 0; k < 4; ++k) bytes[4 * i + k] = static_cast<unsigned char>(bits >> (8 * k));
  }
  return base64(bytes);
}

std::string viewer_json(const ViewerRun& run) {
  const numeric::Instance& instance = *run.instance;
  const Frames frames = frames_of(run);
  std::string times = "[";
  for (std::size_t f = 0; f < run.rows.size(); ++f)
    times += (f ? "," : "") + runtime::format_double(run.table->rows[run.rows[f]][0]);
  std::string s = "{\"format\":1,\"model\":" + script_json_string(run.model_name) +
                  ",\"scale\":" + runtime::format_double(run.scale) + ",\"times\":" + times + "]";
  s += ",\"gravity\":" + point_list({instance.gravity});
  s += ",\"low\":" + point_list({frames.bounds.low}) + ",\"high\":" + point_list({frames.bounds.high});
  s += ",\"bodies\":[";
  int first_node = 0;
  for (std::size_t b = 0; b < instance.bodies.size(); ++b) {
    static const std::vector<Shape> none;
    s += (b ? "," : "") + body_json(instance, b, b < run.shapes.size() ? run.shapes[b] : none, first_node);
    if (instance.bodies[b].elastic) first_node += static_cast<int>(instance.bodies[b].elastic->nodes.size());
  }
  s += "],\"nodes\":" + std::to_string(first_node) + "," + columns_json(run);
  s += ",\"poses\":\"" + float32_base64(frames.poses) + "\",\"moves\":\"" + float32_base64(frames.moves) +
       "\"}";
  return s;
}

}  // namespace kanegen::animate
