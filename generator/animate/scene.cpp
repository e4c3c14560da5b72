// SPDX-License-Identifier: GPL-2.0-or-later
#include "animate/scene.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

#include "fem/element_families.hpp"
#include "numeric/spherical.hpp"

namespace kanegen::animate {
namespace {

using numeric::Pose;
using numeric::Vec;

std::array<double, 3> world_point(const Pose<double>& pose, const Vec<double>& local) {
  return numeric::add(pose.origin, numeric::mul(pose.rotation, local));
}

std::int32_t add_point(Scene& scene, const std::array<double, 3>& at, int body, PointKind kind) {
  scene.points.push_back(at);
  scene.displacement.push_back({0, 0, 0});
  scene.joint_axis.push_back({0, 0, 0});
  scene.point_body.push_back(body);
  scene.point_kind.push_back(static_cast<std::int32_t>(kind));
  return static_cast<std::int32_t>(scene.points.size() - 1);
}

}  // namespace

std::array<std::array<double, 3>, 8> equivalent_box(const numeric::BodyData& b, bool* drawn) {
  std::array<std::array<double, 3>, 8> corners{};
  Eigen::Matrix3d inertia;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) inertia(i, j) = b.inertia[3 * i + j];
  *drawn = b.mass > 0 && inertia.trace() > 0;
  if (!*drawn) return corners;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> principal(inertia);
  const Eigen::Vector3d moments = principal.eigenvalues();
  Eigen::Matrix3d axes = principal.eigenvectors();
  if (axes.determinant() < 0) axes.col(2) *= -1;  // right-handed, so that the cell is not inside out
  Eigen::Vector3d half;
  const double floor = 1e-3 * std::sqrt(6 * moments.maxCoeff() / b.mass);  // a thin side stays visible
  for (int i = 0; i < 3; ++i) {
    const double sum = moments.sum() - 2 * moments[i];  // I_j + I_k - I_i
    half[i] = 0.5 * std::max(std::sqrt(std::max(6 * sum / b.mass, 0.0)), floor);
  }
  // VTK's hexahedron: the bottom face (z -) counter-clockwise, then the top.
  const int signs[8][3] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                           {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};
  for (int c = 0; c < 8; ++c) {
    Eigen::Vector3d p(b.com[0], b.com[1], b.com[2]);
    for (int i = 0; i < 3; ++i) p += signs[c][i] * half[i] * axes.col(i);
    corners[c] = {p[0], p[1], p[2]};
  }
  return corners;
}

BodyStates body_states(const numeric::Instance& model, const std::vector<double>& kernel_q) {
  // A spherical joint's quaternion becomes its base, at a rotation vector 0.
  numeric::Instance instance = model;
  const std::vector<double> q = numeric::take_kernel_coordinates(instance, kernel_q.data());
  const std::vector<std::vector<double>> dofs = numeric::all_beam_dofs(instance, q.data());
  const std::vector<numeric::SecondOrder<double>> second = numeric::all_second_order(instance, dofs);
  BodyStates states{numeric::body_poses(instance, q.data(), dofs, second), {}};
  states.node_moves.resize(instance.bodies.size());
  for (std::size_t b = 0; b < instance.bodies.size(); ++b) {
    if (!instance.bodies[b].elastic) continue;
    const numeric::FlexibleData& f = *instance.bodies[b].elastic;
    for (int n = 0; n < static_cast<int>(f.nodes.size()); ++n) {
      Vec<double> moved = numeric::node_translation(f, dofs[b], n);
      if (f.mesh && !second[b].mesh_dofs.empty())
        moved = numeric::add(moved, numeric::node_translation(f, second[b].mesh_dofs, n));
      else if (!f.mesh)
        moved = numeric::sub(numeric::displaced_node(f, dofs[b], second[b], n), f.nodes[n]);
      states.node_moves[b].push_back(moved);
    }
  }
  return states;
}

bool vtk_cell_of(const std::string& calculix_type, CellType* type, std::vector<int>* order) {
  // The family's row (fem/element_families.cpp) knows its VTK cell and node order.
  fem::ContinuumFamily family;
  if (!fem::family_from_ccx_name(calculix_type, family)) return false;
  const fem::FamilyRow& row = fem::family_row(family);
  *type = static_cast<CellType>(row.vtk_cell);
  *order = row.vtk_nodes;
  return true;
}

SceneBuilder::SceneBuilder(const numeric::Instance& instance, double scale,
                           std::vector<std::vector<Shape>> shapes)
    : instance_(instance), scale_(scale), shapes_(std::move(shapes)) {
  shapes_.resize(instance.bodies.size());
}

void SceneBuilder::add_rigid(Scene& scene, int body, const Pose<double>& pose) const {
  const std::int32_t origin = add_point(scene, pose.origin, body, PointKind::frame_origin);
  const numeric::JointData& joint = instance_.joints[instance_.bodies[body].joint];
  // The axis in the joint frame is the child's too: a turn about it or a slide along it leaves it
  // (a ball has none).
  if (joint.motion == numeric::Motion::rotation || joint.motion == numeric::Motion::translation)
    scene.joint_axis[origin] = numeric::mul(pose.rotation, joint.axis);
  scene.cells.push_back({CellType::vertex, {origin}, body});
  for (const Shape& shape : shapes_[body]) {
    const std::int32_t first = static_cast<std::int32_t>(scene.points.size());
    for (const auto& p : shape.points) add_point(scene, world_point(pose, p), body, PointKind::shape_point);
    if (shape.hexahedron) {
      scene.cells.push_back(
          {CellType::hexahedron,
           {first, first + 1, first + 2, first + 3, first + 4, first + 5, first + 6, first + 7},
           body});
      continue;
    }
    for (const std::vector<int>& face : shape.faces) {
      Scene::Cell cell{face.size() == 3   ? CellType::triangle
                       : face.size() == 4 ? CellType::quad
                                          : CellType::polygon,
                       {},
                       body};
      for (int p : face) cell.points.push_back(first + p);
      scene.cells.push_back(std::move(cell));
    }
  }
}

void SceneBuilder::add_elastic(Scene& scene, int body, const Pose<double>& pose,
                               const std::vector<Vec<double>>& moves) const {
  const numeric::FlexibleData& f = *instance_.bodies[body].elastic;
  const std::int32_t first = static_cast<std::int32_t>(scene.points.size());
  for (int n = 0; n < static_cast<int>(f.nodes.size()); ++n) {
    const Vec<double>& moved = moves[n];
    const std::int32_t p =
        add_point(scene, world_point(pose, numeric::add(f.nodes[n], numeric::scale(moved, scale_))), body,
                  PointKind::elastic_node);
    scene.displacement[p] = numeric::mul(pose.rotation, moved);
  }
  if (!f.mesh) {
    Scene::Cell line{CellType::poly_line, {}, body};
    for (int n = 0; n < static_cast<int>(f.nodes.size()); ++n) line.points.push_back(first + n);
    scene.cells.push_back(std::move(line));
    return;
  }
  for (const numeric::SolidElementData& e : f.solids) {
    CellType type;
    std::vector<int> order;
    if (!vtk_cell_of(e.type, &type, &order)) continue;
    Scene::Cell cell{type, {}, body};
    if (order.empty())
      for (int n : e.nodes) cell.points.push_back(first + n);
    else
      for (int k : order) cell.points.push_back(first + e.nodes[k]);
    scene.cells.push_back(std::move(cell));
  }
}

Scene SceneBuilder::at(const std::vector<double>& kernel_q) const {
  const BodyStates states = body_states(instance_, kernel_q);
  Scene scene;
  for (int b = 0; b < static_cast<int>(instance_.bodies.size()); ++b) {
    add_rigid(scene, b, states.poses[b]);
    if (instance_.bodies[b].elastic) add_elastic(scene, b, states.poses[b], states.node_moves[b]);
  }
  return scene;
}

}  // namespace kanegen::animate
