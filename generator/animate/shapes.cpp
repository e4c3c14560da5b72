// SPDX-License-Identifier: GPL-2.0-or-later
#include "animate/shapes.hpp"

#include <console_bridge/console.h>
#include <urdf_parser/urdf_parser.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "animate/scene.hpp"
#include "model/model_error.hpp"

namespace kanegen::animate {
namespace {

using numeric::Vec;

constexpr double pi = 3.14159265358979323846;

/// The shape moved by a <visual>'s <origin>: points p -> R p + x.
void place(Shape& shape, const urdf::Pose& origin) {
  const urdf::Rotation& r = origin.rotation;
  const Eigen::Matrix3d rotation = Eigen::Quaterniond(r.w, r.x, r.y, r.z).normalized().toRotationMatrix();
  const Eigen::Vector3d offset(origin.position.x, origin.position.y, origin.position.z);
  for (Vec<double>& p : shape.points) {
    const Eigen::Vector3d moved = rotation * Eigen::Vector3d(p[0], p[1], p[2]) + offset;
    p = {moved[0], moved[1], moved[2]};
  }
}

/// The URDF's robot, as urdfdom reads it (load_urdf_model has read it already and said its warnings).
urdf::ModelInterfaceSharedPtr read_robot(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  const console_bridge::LogLevel level = console_bridge::getLogLevel();
  console_bridge::setLogLevel(console_bridge::CONSOLE_BRIDGE_LOG_NONE);
  urdf::ModelInterfaceSharedPtr robot;
  try {
    robot = urdf::parseURDF(text.str());
  } catch (...) {
  }
  console_bridge::setLogLevel(level);
  return robot;
}

/// The shapes of one link's <visual> elements; a mesh's is the equivalent box, said on stderr.
std::vector<Shape> visual_shapes(const urdf::Link& link, const numeric::BodyData& body,
                                 const std::string& path) {
  std::vector<Shape> shapes;
  for (const urdf::VisualSharedPtr& visual : link.visual_array) {
    if (!visual || !visual->geometry) continue;
    Shape shape;
    const urdf::Geometry& g = *visual->geometry;
    if (g.type == urdf::Geometry::BOX) {
      const urdf::Vector3& d = static_cast<const urdf::Box&>(g).dim;
      shape = box_shape({d.x, d.y, d.z});
    } else if (g.type == urdf::Geometry::CYLINDER) {
      const auto& c = static_cast<const urdf::Cylinder&>(g);
      shape = cylinder_shape(c.radius, c.length);
    } else if (g.type == urdf::Geometry::SPHERE) {
      shape = sphere_shape(static_cast<const urdf::Sphere&>(g).radius);
    } else {
      bool drawn = false;
      const auto corners = equivalent_box(body, &drawn);
      std::fprintf(
          stderr, "note: %s: link '%s': a <visual> mesh ('%s') is drawn as %s (kanegen reads no meshes)\n",
          model::ModelError::printable(path).c_str(), model::ModelError::printable(link.name).c_str(),
          model::ModelError::printable(
              g.type == urdf::Geometry::MESH ? static_cast<const urdf::Mesh&>(g).filename : std::string("?"))
              .c_str(),
          drawn ? "the box of the link's mass and inertia" : "nothing (the link has no inertia)");
      if (!drawn) continue;
      shape = box_shape({0, 0, 0});
      shape.kind = "inertia";
      shape.points.assign(corners.begin(), corners.end());
      shape.name = visual->name;
      shapes.push_back(std::move(shape));
      continue;  // the box is the link's already: the visual's origin does not move it
    }
    shape.name = visual->name;
    place(shape, visual->origin);
    shapes.push_back(std::move(shape));
  }
  return shapes;
}

}  // namespace

Shape box_shape(const Vec<double>& size) {
  Shape s{"box",
          "",
          {},
          {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}},
          true};
  // VTK's hexahedron: the bottom face (z -) counter-clockwise, then the top.
  const int signs[8][3] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                           {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};
  for (const auto& c : signs)
    s.points.push_back({0.5 * c[0] * size[0], 0.5 * c[1] * size[1], 0.5 * c[2] * size[2]});
  return s;
}

Shape cylinder_shape(double radius, double length) {
  Shape s{"cylinder", "", {}, {}, false};
  for (int end = 0; end < 2; ++end)
    for (int k = 0; k < shape_sides; ++k) {
      const double w = 2 * pi * k / shape_sides;
      s.points.push_back({radius * std::cos(w), radius * std::sin(w), (end ? 0.5 : -0.5) * length});
    }
  std::vector<int> bottom, top;
  for (int k = 0; k < shape_sides; ++k) {
    const int next = (k + 1) % shape_sides;
    s.faces.push_back({k, next, shape_sides + next, shape_sides + k});
    bottom.push_back(shape_sides - 1 - k);  // seen from below: clockwise about z
    top.push_back(shape_sides + k);
  }
  s.faces.push_back(bottom);
  s.faces.push_back(top);
  return s;
}

Shape sphere_shape(double radius) {
  Shape s{"sphere", "", {{0, 0, -radius}}, {}, false};
  for (int ring = 1; ring <= sphere_rings; ++ring) {
    const double polar = pi * (1.0 - static_cast<double>(ring) / (sphere_rings + 1));  // from the +z axis
    for (int k = 0; k < shape_sides; ++k) {
      const double w = 2 * pi * k / shape_sides;
      s.points.push_back({radius * std::sin(polar) * std::cos(w), radius * std::sin(polar) * std::sin(w),
                          radius * std::cos(polar)});
    }
  }
  s.points.push_back({0, 0, radius});
  const int north = static_cast<int>(s.points.size()) - 1;
  const auto at = [](int ring, int k) { return 1 + (ring - 1) * shape_sides + (k % shape_sides); };
  for (int k = 0; k < shape_sides; ++k) {
    s.faces.push_back({0, at(1, k + 1), at(1, k)});
    for (int ring = 1; ring < sphere_rings; ++ring)
      s.faces.push_back({at(ring, k), at(ring, k + 1), at(ring + 1, k + 1), at(ring + 1, k)});
    s.faces.push_back({at(sphere_rings, k), at(sphere_rings, k + 1), north});
  }
  return s;
}

std::vector<std::vector<Shape>> body_shapes(const numeric::Instance& instance,
                                            const std::string& model_path) {
  std::vector<std::vector<Shape>> shapes(instance.bodies.size());
  std::map<std::string, urdf::LinkConstSharedPtr> links;
  if (std::filesystem::path(model_path).extension() == ".urdf")
    if (const urdf::ModelInterfaceSharedPtr robot = read_robot(model_path))
      for (const auto& [name, link] : robot->links_) links[name] = link;
  for (std::size_t b = 0; b < instance.bodies.size(); ++b) {
    const numeric::BodyData& body = instance.bodies[b];
    const auto link = links.find(body.name);
    if (link != links.end() && link->second && !link->second->visual_array.empty())
      shapes[b] = visual_shapes(*link->second, body, model_path);
    if (!shapes[b].empty()) continue;
    bool drawn = false;
    const auto corners = equivalent_box(body, &drawn);
    if (!drawn) continue;
    Shape box = box_shape({0, 0, 0});
    box.kind = "inertia";
    box.points.assign(corners.begin(), corners.end());
    shapes[b].push_back(std::move(box));
  }
  return shapes;
}

}  // namespace kanegen::animate
