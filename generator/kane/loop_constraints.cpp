// SPDX-License-Identifier: GPL-2.0-or-later
#include "kane/loop_constraints.hpp"

#include <cmath>

#include "kane/beam_node.hpp"
#include "model/model_error.hpp"
#include "symbolic/vec3.hpp"

namespace kanegen::kane {
using namespace kanegen::symbolic;  // the vector algebra and its operators
namespace {

using GiNaC::ex;
using Direction = std::array<double, 3>;

/// e replaced by its definition in terms of the inputs (q, parameters),
/// each intermediate expanded once.
ex written_out(const ex& e, const Program& program, GiNaC::exmap& memo) {
  GiNaC::exmap substitutions;
  for (auto it = e.preorder_begin(); it != e.preorder_end(); ++it) {
    if (!GiNaC::is_a<GiNaC::symbol>(*it)) continue;
    const GiNaC::symbol& s = GiNaC::ex_to<GiNaC::symbol>(*it);
    const ex* definition = program.definition(s);
    if (!definition || substitutions.count(s)) continue;
    auto known = memo.find(s);
    if (known == memo.end()) known = memo.emplace(s, written_out(*definition, program, memo)).first;
    substitutions[s] = known->second;
  }
  return substitutions.empty() ? e : e.subs(substitutions);
}

Vec3 constant(const Direction& d) {
  return {symbolic::number(d[0]), symbolic::number(d[1]), symbolic::number(d[2])};
}

/// Two unit vectors that complete the unit n to a right-handed basis
/// (e1, e2, n); for n = z they are x and y.
std::array<Direction, 2> normal_plane(const Direction& n) {
  int helper = 0;  // the coordinate axis least aligned with n
  for (int k = 1; k < 3; ++k)
    if (std::abs(n[k]) < std::abs(n[helper])) helper = k;
  Direction e1{0, 0, 0};
  e1[helper] = 1.0;
  const double along = e1[0] * n[0] + e1[1] * n[1] + e1[2] * n[2];
  double norm = 0;
  for (int k = 0; k < 3; ++k) {
    e1[k] -= along * n[k];
    norm += e1[k] * e1[k];
  }
  for (double& v : e1) v /= std::sqrt(norm);
  const Direction e2{n[1] * e1[2] - n[2] * e1[1], n[2] * e1[0] - n[0] * e1[2], n[0] * e1[1] - n[1] * e1[0]};
  // Round-off of exact axes would leave 1e-17 entries in the generated code.
  std::array<Direction, 2> basis{e1, e2};
  for (Direction& e : basis)
    for (double& v : e)
      if (std::abs(v) < 1e-15) v = 0.0;
  return basis;
}

/// Where a loop attaches on one side: world position and rotation (body -> world).
struct Side {
  Vec3 position;
  Mat3 rotation;
};

class Builder {
 public:
  Builder(const model::Model& model, const Variables& vars, const Program& program,
          const kinematics::TreeKinematics& tree, const std::map<int, fem::ElasticModel>& flexible)
      : model_(model), vars_(vars), program_(program), tree_(tree), flexible_(flexible) {}

  LoopConstraints build() {
    for (const model::Loop& loop : model_.loops) add_loop(loop);
    const int n = static_cast<int>(vars_.u.size());
    for (std::size_t c = 0; c < out_.phi.size(); ++c) {
      ex velocity = 0;  // C u for this row
      for (int k = 0; k < n; ++k) {
        const ex d = out_.phi[c].diff(vars_.q[k]);
        out_.jacobian.push_back(d);
        velocity += d * vars_.u[k];
      }
      ex bias = 0;
      for (int k = 0; k < n; ++k) bias -= velocity.diff(vars_.q[k]) * vars_.u[k];
      out_.bias.push_back(bias);
    }
    return out_;
  }

 private:
  Side side(const std::string& body, const model::Vec3& point, int node) {
    if (body == model_.ground)
      return {{vars_.scalar(point[0]), vars_.scalar(point[1]), vars_.scalar(point[2])}, identity_mat()};
    const int state = tree_.state_of(body);
    const kinematics::BodyState& b = tree_.bodies()[state];
    Vec3 local{vars_.scalar(point[0]), vars_.scalar(point[1]), vars_.scalar(point[2])};
    Mat3 rotation = b.rotation;
    if (node >= 0) {
      // The node: displaced (with the foreshortening), and turned by its small rotation, exactly.
      const fem::ElasticModel& beam = flexible_.at(b.body);
      const int first = vars_.elastic_first[b.body];
      const std::vector<ex> eta(vars_.q.begin() + first,
                                vars_.q.begin() + first + vars_.elastic_count[b.body]);
      const NodePoint at = node_point(beam, node, eta, nullptr);
      local = at.position;
      rotation = mul(b.rotation, kinematics::node_turn(at.rotation));
    }
    Side s{tree_.world_point(b, local), rotation};
    for (ex& e : s.position) e = written_out(e, program_, memo_);
    for (ex& e : s.rotation) e = written_out(e, program_, memo_);
    return s;
  }

  void row(const model::Loop& loop, const ex& phi, const std::string& suffix) {
    out_.phi.push_back(phi);
    out_.names.push_back(loop.name + "." + suffix);
    out_.loops.push_back(loop.name);
  }

  void add_loop(const model::Loop& loop) {
    const Side a = side(loop.body, loop.point, loop.node);
    const Side b = side(loop.body2, loop.point2, loop.node2);
    const Vec3 gap = a.position - b.position;
    const bool z_plane = loop.axis == Direction{0.0, 0.0, 1.0};
    switch (loop.type) {
      case model::LoopType::spherical:
        row(loop, gap[0], "x");
        row(loop, gap[1], "y");
        row(loop, gap[2], "z");
        return;
      case model::LoopType::revolute:
        if (loop.planar) {
          const auto plane = normal_plane(loop.axis);
          row(loop, dot(constant(plane[0]), gap), z_plane ? "x" : "f1");
          row(loop, dot(constant(plane[1]), gap), z_plane ? "y" : "f2");
          return;
        } else {
          row(loop, gap[0], "x");
          row(loop, gap[1], "y");
          row(loop, gap[2], "z");
          // The hinge axis, the same components in both frames, stays aligned.
          const Vec3 hinge = mul(a.rotation, constant(loop.axis));
          const auto across = normal_plane(loop.axis);
          row(loop, dot(hinge, mul(b.rotation, constant(across[0]))), "m1");
          row(loop, dot(hinge, mul(b.rotation, constant(across[1]))), "m2");
          return;
        }
      case model::LoopType::slider: {
        // The second point stays on the line through the first along the
        // axis (first body's frame): the offset across the line is zero.
        if (loop.planar) {
          const Direction& d = loop.axis;
          Direction e{-d[1], d[0], 0.0};  // z x d, in the plane of the first body's x-y axes
          const double norm = std::sqrt(e[0] * e[0] + e[1] * e[1]);
          if (!(norm > 1e-9))
            throw model::ModelError(
                model_.source_file, loop.where + "/axis",
                "a planar slider's axis must lie in the x-y plane of body '" + loop.body + "'",
                "give an axis with a nonzero x or y component");
          for (double& v : e) v /= norm;
          row(loop, dot(mul(a.rotation, constant(e)), gap), "n");
          return;
        }
        const auto across = normal_plane(loop.axis);
        row(loop, dot(mul(a.rotation, constant(across[0])), gap), "f1");
        row(loop, dot(mul(a.rotation, constant(across[1])), gap), "f2");
        return;
      }
    }
  }

  const model::Model& model_;
  const Variables& vars_;
  const Program& program_;
  const kinematics::TreeKinematics& tree_;
  const std::map<int, fem::ElasticModel>& flexible_;
  GiNaC::exmap memo_;
  LoopConstraints out_;
};

}  // namespace

LoopConstraints derive_loop_constraints(const model::Model& model, const Variables& vars,
                                        const Program& program, const kinematics::TreeKinematics& tree,
                                        const std::map<int, fem::ElasticModel>& flexible) {
  return Builder(model, vars, program, tree, flexible).build();
}

}  // namespace kanegen::kane
