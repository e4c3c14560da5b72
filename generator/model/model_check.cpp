// SPDX-License-Identifier: GPL-2.0-or-later
#include "model/model_check.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <map>
#include <set>
#include <sstream>

#include "model/assumed_modes_check.hpp"
#include "model/elastic_coordinates.hpp"
#include "model/expression_check.hpp"
#include "model/expression_eval.hpp"
#include "model/json_document.hpp"
#include "model/model_error.hpp"
#include "model/names.hpp"

namespace kanegen::model {
namespace {

std::string at(const std::string& where, const std::string& field) { return where + "/" + field; }

std::string format(double v) {
  std::ostringstream out;
  out.precision(6);
  out << v;
  return out.str();
}

template <class Item>
std::vector<std::string> names_of(const std::vector<Item>& items) {
  std::vector<std::string> names;
  for (const Item& i : items) names.push_back(i.name);
  return names;
}

/// A name and its place, to check names across the kinds of forces.
struct Named {
  std::string name;
  std::string where;
};

class Checker {
 public:
  Checker(Model& model, std::string root_place)
      : m_(model), file_(model.source_file), root_place_(std::move(root_place)) {}

  /// For check_parameter_values: the checks of values at `values`.
  Checker(Model& model, ParameterValues values, std::string origin)
      : m_(model), file_(model.source_file), values_(std::move(values)), origin_(std::move(origin)) {}

  void run_value_checks() {
    check_bodies();
    for (const Joint& j : m_.joints) check_joint_values(j);
    for (const Spring& s : m_.springs) check_spring_values(s);
  }

  void run() {
    check_names();
    values_ = default_parameter_values(m_);  // the expressions are checked before they are evaluated
    check_numbers();
    check_expressions();
    check_bodies();
    check_joints();
    check_tree();
    check_references();
    check_flexible();
    check_loops();
    check_interfaces();
    check_moving_mass();
  }

 private:
  [[noreturn]] void error(const std::string& place, const std::string& problem,
                          const std::string& fix) const {
    throw ModelError(file_, place, problem, fix);
  }

  template <class Item>
  void unique(const std::vector<Item>& items, const std::string& what) const {
    std::map<std::string, const Item*> seen;
    for (const Item& item : items) {
      auto [it, fresh] = seen.emplace(item.name, &item);
      if (!fresh)
        error(at(item.where, "name"),
              "duplicate " + what + " name '" + item.name + "' (also at " + it->second->where + ")",
              "rename one of them");
    }
  }

  /// The names of all entries of "forces", whatever their type, in file order.
  std::vector<Named> force_names() const {
    std::vector<Named> names;
    for (const PointForce& f : m_.forces) names.push_back({f.name, f.where});
    for (const Spring& s : m_.springs) names.push_back({s.name, s.where});
    for (const JointEffort& e : m_.joint_efforts) names.push_back({e.name, e.where});
    const auto index = [](const Named& n) {
      const auto slash = n.where.rfind('/');
      return slash == std::string::npos ? 0L : std::strtol(n.where.c_str() + slash + 1, nullptr, 10);
    };
    std::stable_sort(names.begin(), names.end(),
                     [&](const Named& a, const Named& b) { return index(a) < index(b); });
    return names;
  }

  void check_names() const {
    unique(m_.parameters, "parameter");
    unique(m_.bodies, "body");
    unique(m_.joints, "joint");
    unique(force_names(), "force");
    unique(m_.outputs, "output");
    unique(m_.loops, "loop");
    for (const Body& b : m_.bodies)
      if (b.name == m_.ground)
        error(at(b.where, "name"), "'" + b.name + "' names the fixed ground, not a body", "rename the body");
  }

  void for_each_scalar(const std::function<void(const Scalar&)>& visit) const {
    for (const Scalar& s : m_.gravity) visit(s);
    for (const Body& b : m_.bodies) {
      visit(b.mass);
      for (const Scalar& s : b.com) visit(s);
      for (const Scalar& s : b.inertia) visit(s);
    }
    for (const Joint& j : m_.joints) {
      for (const Scalar& s : j.origin_xyz) visit(s);
      for (const Scalar& s : j.origin_rpy) visit(s);
      visit(j.spring_stiffness);
      visit(j.spring_rest);
      visit(j.damping);
    }
    for (const PointForce& f : m_.forces) {
      for (const Scalar& s : f.point) visit(s);
      for (const Scalar& s : f.force) visit(s);
    }
    for (const Loop& l : m_.loops) {
      for (const Scalar& s : l.point) visit(s);
      for (const Scalar& s : l.point2) visit(s);
    }
    for (const Spring& s : m_.springs) {
      for (const Scalar& x : s.point) visit(x);
      for (const Scalar& x : s.point2) visit(x);
      visit(s.stiffness);
      visit(s.rest_length);
      visit(s.damping);
    }
    // A joint effort may also use t: check_joint_efforts reads it.
    for (const JointEffort& e : m_.joint_efforts)
      if (e.value.is_literal) visit(e.value);
    for (const Output& o : m_.outputs)
      if (o.kind == OutputKind::point_position)
        for (const Scalar& s : o.point) visit(s);
  }

  void check_numbers() const {
    const auto finite = [&](double v, const std::string& place) {
      if (!std::isfinite(v)) error(place, "number is not finite (" + format(v) + ")", "use a finite value");
    };
    for (const Parameter& p : m_.parameters) finite(p.value, p.where);
    for_each_scalar([&](const Scalar& s) {
      if (s.is_literal) finite(s.value, s.where);
    });
    for (const Joint& j : m_.joints) {
      for (double a : j.axis) finite(a, at(j.where, "axis"));
      finite(j.q0, at(j.where, "initial/q"));
      finite(j.u0, at(j.where, "initial/u"));
    }
  }

  void check_prescribed() const {
    std::vector<std::string> names = names_of(m_.parameters);
    names.push_back("t");
    ParameterValues values = default_parameter_values(m_);
    for (const Joint& j : m_.joints)
      for (const PrescribedPiece& piece : j.prescribed) {
        if (auto issue = check_expression(piece.q, names))
          error(piece.where, describe_with_caret(piece.q, *issue), issue->fix + " (and t, the time)");
        values["t"] = piece.has_until ? piece.until : 0.0;
        const double value = evaluate_expression(piece.q, values);
        if (!std::isfinite(value))
          error(piece.where,
                "prescribed motion '" + piece.q + "' is not finite at t = " + format(values["t"]),
                "check it at the parameters' default values");
      }
  }

  /// A joint effort's value: an expression in the parameters and t, finite at t = 0.
  void check_joint_efforts() const {
    std::vector<std::string> names = names_of(m_.parameters);
    names.push_back("t");
    ParameterValues values = default_parameter_values(m_);
    values["t"] = 0.0;
    for (const JointEffort& e : m_.joint_efforts) {
      if (e.value.is_literal) continue;
      if (auto issue = check_expression(e.value.text, names))
        error(e.value.where, describe_with_caret(e.value.text, *issue), issue->fix + " (and t, the time)");
      if (!std::isfinite(evaluate_expression(e.value.text, values)))
        error(e.value.where, "joint effort '" + e.value.text + "' is not finite at t = 0",
              "check it at the parameters' default values");
    }
  }

  void check_expressions() const {
    check_prescribed();
    check_joint_efforts();
    const std::vector<std::string> parameters = names_of(m_.parameters);
    const ParameterValues defaults = default_parameter_values(m_);
    for_each_scalar([&](const Scalar& s) {
      if (s.is_literal) return;
      if (auto issue = check_expression(s.text, parameters))
        error(s.where, describe_with_caret(s.text, *issue), issue->fix);
      // As for numbers: a value that is not finite (1/0, sqrt(-2), 1e400)
      // would be folded into the generated code as inf or nan.
      const double value = evaluate_expression(s.text, defaults);
      if (!std::isfinite(value))
        error(s.where,
              "expression '" + s.text + "' is " +
                  (std::isnan(value) ? "not a real number (NaN)" : "infinite") +
                  " at the parameters' default values",
              "check it and the defaults under /parameters: a division by zero, the square root or logarithm "
              "of a negative number, or a value beyond 1e308 are the usual causes");
    });
  }

  static std::string inertia_place(const Body& b) {
    // JSON gives each entry its own pointer (/bodies/0/inertia/ixx); URDF one
    // element for all six, since they are mixed by the frame rotation.
    const std::string& first = b.inertia[0].where;
    if (first == b.inertia[1].where) return first;
    return first.substr(0, first.rfind('/'));
  }

  void check_bodies() const {
    for (const Body& b : m_.bodies) {
      // Evaluated, so that a mass or an inertia given by an expression is
      // checked at the parameter values, not only when it is a number.
      const double mass = evaluate(b.mass, values_);
      std::array<double, 6> inertia{};
      for (int k = 0; k < 6; ++k) inertia[k] = evaluate(b.inertia[k], values_);
      const bool zero_inertia =
          std::all_of(inertia.begin(), inertia.end(), [](double v) { return v == 0.0; });
      if (mass < 0)
        error(b.mass.where, "negative mass (" + described(b.mass) + ") of body '" + b.name + "'",
              "give a positive mass in kg" + parameter_fix(b.mass));
      if (mass == 0 && !zero_inertia)
        error(b.mass.where,
              "zero mass" + in_parentheses(b.mass) + " with a nonzero inertia in body '" + b.name + "'",
              "give a positive mass, or set all inertia entries to 0 for a massless frame" +
                  parameter_fix(b.mass));
      if (!zero_inertia) check_inertia(b, inertia);
    }
  }

  /// "-1.2", or for an expression "-1.2 = m1*2 with m1 = -0.6 from --set m1=-0.6".
  std::string described(const Scalar& s) const {
    const std::string value = format(evaluate(s, values_));
    if (s.is_literal) return value;
    const std::vector<std::string> used = parameters_in(s.text);
    if (used.size() == 1 && used[0] == s.text)  // a bare parameter: "m = -1.2 from --set"
      return s.text + " = " + value + (origin_.empty() ? "" : " " + origin_);
    std::string text = value + " = " + s.text;
    for (std::size_t k = 0; k < used.size(); ++k)
      text += (k ? ", " : " with ") + used[k] + " = " + format(values_.at(used[k]));
    return text + (origin_.empty() ? "" : " " + origin_);
  }

  /// Where to fix a value given by an expression: its parameters.
  std::string parameter_fix(const Scalar& s) const {
    if (s.is_literal) return "";
    const std::vector<std::string> used = parameters_in(s.text);
    if (used.empty()) return "";
    return " (check " + join(used, ", ") +
           (origin_.empty() ? std::string(" under /parameters") : std::string(" in --set")) + ")";
  }

  /// The model's parameters named in an expression, in order of first use.
  std::vector<std::string> parameters_in(const std::string& text) const {
    std::vector<std::string> used;
    for (std::size_t i = 0; i < text.size();) {
      if (!(std::isalpha(static_cast<unsigned char>(text[i])) || text[i] == '_')) {
        ++i;
        continue;
      }
      std::size_t end = i;
      while (end < text.size() && (std::isalnum(static_cast<unsigned char>(text[end])) || text[end] == '_'))
        ++end;
      const std::string name = text.substr(i, end - i);
      if (values_.count(name) && std::find(used.begin(), used.end(), name) == used.end())
        used.push_back(name);
      i = end;
    }
    return used;
  }

  /// "; izz = k*m1*l1^2/12 with k = -1, m1 = 2, l1 = 0.5 from --set" for the entries given by expressions.
  std::string inertia_expressions(const Body& b) const {
    static const char* const kEntries[6] = {"ixx", "iyy", "izz", "ixy", "ixz", "iyz"};
    std::vector<std::string> entries, used;
    for (int k = 0; k < 6; ++k) {
      if (b.inertia[k].is_literal) continue;
      entries.push_back(std::string(kEntries[k]) + " = " + b.inertia[k].text);
      for (const std::string& p : parameters_in(b.inertia[k].text))
        if (std::find(used.begin(), used.end(), p) == used.end()) used.push_back(p);
    }
    if (entries.empty()) return "";
    std::string text = "; " + join(entries, ", ");
    for (std::size_t k = 0; k < used.size(); ++k)
      text += (k ? ", " : " with ") + used[k] + " = " + format(values_.at(used[k]));
    return text + (origin_.empty() ? "" : " " + origin_);
  }

  void check_inertia(const Body& b, const std::array<double, 6>& i) const {
    Eigen::Matrix3d tensor;
    tensor << i[0], i[3], i[4], i[3], i[1], i[5], i[4], i[5], i[2];
    const Eigen::Vector3d l = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(tensor, Eigen::EigenvaluesOnly)
                                  .eigenvalues();  // ascending
    const double tolerance = 1e-9 * l.cwiseAbs().maxCoeff();
    const std::string moments = format(l[0]) + ", " + format(l[1]) + ", " + format(l[2]);
    const std::string from = inertia_expressions(b);
    if (l[0] < -tolerance)
      error(inertia_place(b),
            "inertia of body '" + b.name + "' has a negative principal moment (principal moments " + moments +
                from + ")",
            "check the entries: ixx, iyy, izz are positive and the products of inertia ixy, ixz, iyz are the "
            "tensor's off-diagonal entries (-integral of x*y dm), small next to them");
    if (l[0] + l[1] < l[2] - tolerance)
      error(inertia_place(b),
            "inertia of body '" + b.name + "' violates the triangle inequality (principal moments " +
                moments + ": " + format(l[0]) + " + " + format(l[1]) + " < " + format(l[2]) + from + ")",
            "no mass distribution has such moments: check the entries (the sum of any two principal moments "
            "must be at least the third)");
  }

  void check_joints() const {
    for (Joint& j : m_.joints) {
      check_joint_values(j);
      if (!j.moves()) continue;
      const double norm = std::sqrt(j.axis[0] * j.axis[0] + j.axis[1] * j.axis[1] + j.axis[2] * j.axis[2]);
      if (!(norm > 1e-12))
        error(at(j.where, "axis"), "zero-length axis of joint '" + j.name + "'",
              "give the axis a direction, e.g. [0, 0, 1] (it is normalised at load)");
      for (double& a : j.axis) a /= norm;
    }
  }

  void check_joint_values(const Joint& j) const {
    if (evaluate(j.spring_stiffness, values_) < 0)
      error(j.spring_stiffness.where,
            "negative spring stiffness" + in_parentheses(j.spring_stiffness) + " of joint '" + j.name + "'",
            "use a stiffness >= 0" + parameter_fix(j.spring_stiffness));
    if (evaluate(j.damping, values_) < 0)
      error(j.damping.where, "negative damping" + in_parentheses(j.damping) + " of joint '" + j.name + "'",
            "use a damping coefficient >= 0" + parameter_fix(j.damping));
  }

  /// " (= expression with ...)" for an expression; nothing for a number, as before.
  std::string in_parentheses(const Scalar& s) const { return s.is_literal ? "" : " (" + described(s) + ")"; }

  std::string unknown_body_fix(const std::string& name, bool allow_ground) const {
    std::vector<std::string> candidates = names_of(m_.bodies);
    if (allow_ground) candidates.push_back(m_.ground);
    const std::string guess = nearest(name, candidates);
    if (!guess.empty()) return "did you mean '" + guess + "'?";
    return allow_ground ? "use a body name or '" + m_.ground + "'" : "use the name of a body";
  }

  void check_tree() {
    std::map<std::string, std::size_t> body;
    for (std::size_t i = 0; i < m_.bodies.size(); ++i) body[m_.bodies[i].name] = i;
    parent_joint_.assign(m_.bodies.size(), -1);
    for (std::size_t k = 0; k < m_.joints.size(); ++k) {
      const Joint& j = m_.joints[k];
      if (j.child == m_.ground)
        error(at(j.where, "child"), "the ground '" + m_.ground + "' cannot be the child of a joint",
              "swap parent and child");
      if (!body.count(j.child))
        error(at(j.where, "child"), "unknown body '" + j.child + "'", unknown_body_fix(j.child, false));
      if (j.parent != m_.ground && !body.count(j.parent))
        error(at(j.where, "parent"), "unknown body '" + j.parent + "'", unknown_body_fix(j.parent, true));
      if (j.parent == j.child)
        error(at(j.where, "child"), "joint '" + j.name + "' connects body '" + j.child + "' to itself",
              "give it another parent");
      int& parent = parent_joint_[body[j.child]];
      if (parent >= 0)
        error(at(j.where, "child"),
              "body '" + j.child + "' is already the child of joint '" + m_.joints[parent].name + "' (" +
                  m_.joints[parent].where + ")",
              "a body hangs from exactly one joint: remove one of the joints, and close the loop with an "
              "entry in \"loops\" instead");
      parent = static_cast<int>(k);
    }
    for (std::size_t b = 0; b < m_.bodies.size(); ++b)
      if (parent_joint_[b] < 0)
        error(m_.bodies[b].where, "body '" + m_.bodies[b].name + "' is not the child of any joint",
              "attach it with a joint whose child is '" + m_.bodies[b].name + "', or remove it");
    // Each body has one parent, so its chain of parents either reaches the
    // ground or runs into a loop.
    for (std::size_t b = 0; b < m_.bodies.size(); ++b) {
      std::vector<std::size_t> chain{b};
      for (;;) {
        const Joint& j = m_.joints[parent_joint_[chain.back()]];
        if (j.parent == m_.ground) break;
        const std::size_t up = body[j.parent];
        const bool loops = std::find(chain.begin(), chain.end(), up) != chain.end();
        chain.push_back(up);
        if (!loops) continue;
        std::vector<std::string> names;
        for (std::size_t c : chain) names.push_back(m_.bodies[c].name);
        if (up == b)
          error(at(m_.joints[parent_joint_[b]].where, "parent"),
                "joints form a cycle: " + join(names, " -> "),
                "each chain of parents must end at '" + m_.ground + "': make one of these bodies hang from " +
                    m_.ground + " or from a body outside the cycle");
        error(m_.bodies[b].where,
              "body '" + m_.bodies[b].name + "' is not connected to the ground (its parents " +
                  join(names, " -> ") + " loop)",
              "attach the chain to '" + m_.ground + "'");
      }
    }
  }

  void check_references() const {
    std::set<std::string> bodies;
    for (const Body& b : m_.bodies) bodies.insert(b.name);
    for (const PointForce& f : m_.forces)
      if (!bodies.count(f.body))
        error(at(f.where, "body"), "force '" + f.name + "' names unknown body '" + f.body + "'",
              unknown_body_fix(f.body, false));
    for (const Spring& s : m_.springs) check_spring(s, bodies);
    for (const JointEffort& e : m_.joint_efforts) check_joint_effort(e);
    for (const Output& o : m_.outputs) {
      if (o.kind == OutputKind::reaction) {
        if (std::none_of(m_.loops.begin(), m_.loops.end(), [&](const Loop& l) { return l.name == o.loop; })) {
          const std::string guess = nearest(o.loop, names_of(m_.loops));
          error(at(o.where, "loop"), "output '" + o.name + "' names unknown loop '" + o.loop + "'",
                guess.empty() ? "use the name of an entry in \"loops\"" : "did you mean '" + guess + "'?");
        }
        continue;
      }
      if (o.kind == OutputKind::point_position || o.node != -1 || !o.node_set.empty()) {
        if (!bodies.count(o.body))
          error(at(o.where, "body"), "output '" + o.name + "' names unknown body '" + o.body + "'",
                unknown_body_fix(o.body, false));
        continue;
      }
      const auto j =
          std::find_if(m_.joints.begin(), m_.joints.end(), [&](const Joint& x) { return x.name == o.joint; });
      if (j == m_.joints.end()) {
        const std::string guess = nearest(o.joint, names_of(m_.joints));
        error(at(o.where, "joint"), "output '" + o.name + "' names unknown joint '" + o.joint + "'",
              guess.empty() ? "use the name of a joint" : "did you mean '" + guess + "'?");
      }
      if (!j->moves())
        error(at(o.where, "joint"),
              "output '" + o.name + "' names fixed joint '" + o.joint + "', which has no coordinate",
              "name a " + joint_type_list(JointKinds::one_coordinate, "or") + " joint");
      if (joint_type_info(j->type).coordinates > 1)
        error(at(o.where, "joint"),
              "output '" + o.name + "' names " + joint_type_info(j->type).name + " joint '" + o.joint +
                  "', which has several coordinates",
              "every coordinate and speed is a column of the simulation's CSV already; for the child's "
              "position give a point_position output");
    }
  }

  void check_spring(const Spring& s, const std::set<std::string>& bodies) const {
    const std::string what = "spring '" + s.name + "'";
    if (s.body == m_.ground)
      error(at(s.where, "body"), what + " has its first point on the ground",
            "swap the ends: give the moving body as \"body\" and the ground as \"body2\"");
    if (!bodies.count(s.body))
      error(at(s.where, "body"), what + " names unknown body '" + s.body + "'",
            unknown_body_fix(s.body, false));
    if (s.body2 != m_.ground && !bodies.count(s.body2))
      error(at(s.where, "body2"), what + " names unknown body '" + s.body2 + "'",
            unknown_body_fix(s.body2, true));
    if (s.body2 == s.body)
      error(at(s.where, "body2"), what + " has both points on body '" + s.body + "'",
            "attach its second point to another body or to '" + m_.ground +
                "': between two points of one body it is an internal force and does nothing");
    check_spring_values(s);
  }

  void check_spring_values(const Spring& s) const {
    const auto non_negative = [&](const Scalar& x, const std::string& quantity, const std::string& unit) {
      if (evaluate(x, values_) < 0)
        error(x.where, "negative " + quantity + " (" + described(x) + ") of spring '" + s.name + "'",
              "give a " + quantity + " >= 0, in " + unit + parameter_fix(x));
    };
    non_negative(s.stiffness, "stiffness", "N/m");
    non_negative(s.rest_length, "rest length", "m");
    non_negative(s.damping, "damping", "N s/m");
  }

  void check_joint_effort(const JointEffort& e) const {
    const std::string what = "joint effort '" + e.name + "'";
    const auto j =
        std::find_if(m_.joints.begin(), m_.joints.end(), [&](const Joint& x) { return x.name == e.joint; });
    if (j == m_.joints.end()) {
      const std::string guess = nearest(e.joint, names_of(m_.joints));
      error(at(e.where, "joint"), what + " names unknown joint '" + e.joint + "'",
            guess.empty() ? "use the name of a moving joint" : "did you mean '" + guess + "'?");
    }
    if (!j->moves())
      error(at(e.where, "joint"), what + " acts on fixed joint '" + e.joint + "', which has no coordinate",
            "name a " + joint_type_list(JointKinds::one_coordinate, "or") + " joint");
    if (joint_type_info(j->type).coordinates > 1)
      error(at(e.where, "joint"),
            what + " acts on " + joint_type_info(j->type).name + " joint '" + e.joint +
                "', which has several speeds",
            "give the moment as a body-fixed force pair, or drive the joint's inputs (tau)");
    if (j->is_prescribed())
      error(at(e.where, "joint"), what + " acts on prescribed joint '" + e.joint + "', whose motion is given",
            "remove it, or name a joint that is not prescribed");
  }

  static constexpr int kMaxElements = 1000;

  int free_coordinates(const ElasticPart& f) const {
    const int per_node = f.formulation == BeamFormulation::planar ? 3 : 6;
    const int fixed = f.support == BeamSupport::clamped         ? per_node
                      : f.support == BeamSupport::pinned_pinned ? (per_node == 3 ? 3 : 6)
                                                                : 0;
    return f.num_nodes() * per_node - fixed;
  }

  void check_beam(const Body& b) const {
    const ElasticPart& f = b.elastic;
    const bool planar = f.formulation == BeamFormulation::planar;
    const std::string section = at(f.where, "section"), material = at(f.where, "material");
    if (f.Iz <= 0)
      error(section, "missing 'Iz' of the beam of body '" + b.name + "'",
            "give \"Iz\": int y^2 dA in m^4 (bending in the body x-y plane)");
    if (!planar) {
      if (f.Iy <= 0)
        error(section, "missing 'Iy' of the spatial beam of body '" + b.name + "'",
              "give \"Iy\": int z^2 dA in m^4");
      if (f.J <= 0)
        error(section, "missing 'J' of the spatial beam of body '" + b.name + "'",
              "give \"J\", the torsion constant in m^4");
      if (f.G <= 0)
        error(material, "missing 'G' of the spatial beam of body '" + b.name + "'",
              "give \"G\" (Pa) or \"poisson\", for the torsional stiffness");
    }
    if (f.num_elements() > kMaxElements)
      error(f.where,
            "the beam of body '" + b.name + "' has " + std::to_string(f.num_elements()) +
                " elements, more than the limit of " + std::to_string(kMaxElements),
            "use fewer elements, or modal reduction (\"modes\") for a fine mesh");
    std::array<double, 3> from{0.0, 0.0, 0.0};
    for (const BeamSegment& s : f.segments) {
      const double dx = s.to[0] - from[0], dy = s.to[1] - from[1], dz = s.to[2] - from[2];
      for (double v : s.to)
        if (!std::isfinite(v))
          error(s.where, "a coordinate of the segment is not finite", "use finite numbers");
      if (!(std::sqrt(dx * dx + dy * dy + dz * dz) > 1e-12))
        error(s.where, "zero-length beam segment in body '" + b.name + "'",
              "give a positive length, or an end point away from the previous one");
      if (!planar && std::abs(dx) < 1e-9 * std::abs(dz) && std::abs(dy) < 1e-9 * std::abs(dz))
        error(s.where,
              "a spatial beam segment along the body z axis is not supported (its section axes are "
              "taken from the body z axis)",
              "turn the body frame (the joint origin's rpy) so that the segment is not along z");
      if (planar && std::abs(dz) > 0)
        error(s.where, "a planar beam must lie in the body x-y plane (z = 0)",
              "make the segment's z zero, or use \"formulation\": \"spatial\"");
      from = s.to;
    }
    if (f.support == BeamSupport::pinned_pinned && (f.segments.size() != 1 || f.segments[0].to[1] != 0 ||
                                                    f.segments[0].to[2] != 0 || f.segments[0].to[0] <= 0))
      error(at(f.where, "support"), "a pinned-pinned beam must be one straight run along the body's +x axis",
            "use \"length\" and \"elements\", or \"clamped\"");
    const int available = free_coordinates(f);
    if (f.modes > available)
      error(at(f.where, "modes"),
            std::to_string(f.modes) + " modes asked, but the supported beam of body '" + b.name +
                "' has only " + std::to_string(available) + " coordinates (the limit)",
            "ask for at most " + std::to_string(available) + " modes, or use more elements");
    if (f.support == BeamSupport::free)
      error(at(f.where, "support"), "a free beam would have rigid-body modes in its elastic coordinates",
            "use \"clamped\" or \"pinned-pinned\": the joints carry the rigid motion");
    if (f.modal_damping > 0 && !f.assumed_modes.empty())
      error(at(f.where, "damping"),
            "a modal damping ratio needs the beam's own modes, which assumed modes are not",
            "use \"rayleigh\": [alpha, beta]");
    if (f.modal_damping > 0 && f.modes == 0)
      error(at(f.where, "damping"), "a modal damping ratio needs modal coordinates",
            "add \"modes\": k, or use \"rayleigh\": [alpha, beta]");
    if (f.tip_mass == 0)
      for (double v : f.tip_inertia)
        if (v != 0) error(at(f.where, "tip"), "a tip inertia without a tip mass", "give the tip a mass");
  }

  /// Resolves kTipNode and checks that `node` is a node of flexible body
  /// `body_name`; returns that body (nullptr if there is none of that name,
  /// which check_tree or check_references report).
  const Body* check_node(int& node, const std::string& body_name, const std::string& place,
                         const std::string& what) const {
    const auto b =
        std::find_if(m_.bodies.begin(), m_.bodies.end(), [&](const Body& x) { return x.name == body_name; });
    if (b == m_.bodies.end()) return nullptr;
    if (!b->flexible)
      error(place, what + " names a node of body '" + body_name + "', which is rigid",
            "remove the node, or make '" + body_name + "' flexible");
    if (b->elastic.mesh.present())
      error(place, what + " names a node of body '" + body_name + "', which is a mesh body",
            "name a node set of its mesh instead (\"node_set\"; a joint: \"parent_node_set\")");
    const int last = b->elastic.num_nodes() - 1;
    if (node == kTipNode) node = last;
    if (node < 0 || node > last)
      error(place, "node " + std::to_string(node) + " of body '" + body_name + "' does not exist",
            "give a node from 0 (at the body frame's origin) to " + std::to_string(last) + " (\"tip\")");
    return &*b;
  }

  /// Every elastic coordinate given an initial value exists.
  void check_elastic_initial(const Body& b) const {
    const std::vector<std::string> names = elastic_coordinate_names(b.elastic);
    for (const auto& [key, given] :
         {std::pair{"q", &b.elastic.initial_q}, std::pair{"u", &b.elastic.initial_u}})
      for (const auto& entry : *given) {
        const std::string& name = entry.first;
        if (std::find(names.begin(), names.end(), name) != names.end()) continue;
        const std::string prefix = b.name + ".", local = name.substr(std::min(prefix.size(), name.size()));
        const bool prefixed =
            name.rfind(prefix, 0) == 0 && std::find(names.begin(), names.end(), local) != names.end();
        const std::string guess = prefixed ? local : nearest(name, names);
        error(at(b.elastic.where, std::string("initial/") + key + "/" + pointer_token(name)),
              "body '" + b.name + "' has no elastic coordinate '" + name + "'",
              (prefixed        ? "write it without the body prefix: '" + guess + "'. "
               : guess.empty() ? ""
                               : "did you mean '" + guess + "'? ") +
                  "Its coordinates are " + coordinate_list(b.elastic, names));
      }
  }

  /// "mode1 to mode4", or the nodal ones with their pattern, for messages.
  static std::string coordinate_list(const ElasticPart& f, const std::vector<std::string>& names) {
    if (names.empty()) return "none";
    const bool modal = f.modes > 0 || !f.assumed_modes.empty();
    if (names.size() <= 4) return join(names);
    if (modal) return names.front() + " to " + names.back();
    return names.front() + ", " + names[1] + ", ..., " + names.back() + " (n<node>." +
           (f.formulation == BeamFormulation::planar ? "<u|v|theta_z>" : "<u|v|w|theta_x|theta_y|theta_z>") +
           " for each dof the support leaves free)";
  }

  /// A node set of mesh body `body_name` that something attaches to (`key`
  /// at `where` names it): it becomes one of the body's interfaces, the same
  /// set named twice being one, and its index is returned. `turns`: the
  /// rotation of the set is used. Whether the mesh has the set, and a
  /// rotation where one is used, are checked when the mesh is read
  /// (fem/model_mesh.hpp).
  int interface_of(const std::string& body_name, const std::string& set, const std::string& where,
                   const std::string& key, const std::string& what, bool turns) {
    const std::string place = at(where, key);
    if (body_name == m_.ground) error(place, "the ground has no node sets", "remove \"" + key + "\"");
    const auto b =
        std::find_if(m_.bodies.begin(), m_.bodies.end(), [&](const Body& x) { return x.name == body_name; });
    if (b == m_.bodies.end() || !b->flexible || !b->elastic.mesh.present())
      error(place,
            what + " names node set '" + set + "' of '" + body_name + "', which is not a mesh body (it is " +
                (b == m_.bodies.end() ? "unknown"
                 : !b->flexible       ? "rigid"
                                      : "a beam") +
                ")",
            b != m_.bodies.end() && b->flexible
                ? "remove \"" + key + "\": a beam's nodes are given by index (\"" +
                      (key == "parent_node_set" ? std::string("parent_node") : "node" + key.substr(8)) +
                      "\": 3, or \"tip\")"
                : "remove \"" + key +
                      "\" and give a point of the body frame; node sets belong to bodies "
                      "with \"flexible\": {\"mesh\": ...}");
    std::vector<MeshInterface>& sets = b->elastic.mesh.interfaces;
    auto found =
        std::find_if(sets.begin(), sets.end(), [&](const MeshInterface& x) { return x.node_set == set; });
    if (found == sets.end()) {
      sets.push_back({set, place, ""});
      found = sets.end() - 1;
    }
    if (turns && found->rotation_where.empty()) found->rotation_where = place;
    return static_cast<int>(found - sets.begin());
  }

  /// A joint on a node set of a mesh parent: its frame moves and turns with
  /// the set's averaged motion.
  void attach_to_node_set(Joint& j) {
    const std::string what = "joint '" + j.name + "'";
    j.parent_node = interface_of(j.parent, j.parent_node_set, j.where, "parent_node_set", what, true);
    if (!joint_type_info(j.type).on_nodes)
      error(at(j.where, "parent_node_set"),
            "only " + joint_type_list(JointKinds::on_nodes, "and") + " joints on node sets are supported",
            "attach " + std::string(joint_type_info(j.type).name) + " joint '" + j.name +
                "' to the body frame, or put a fixed joint and a body on the set");
  }

  void check_flexible() {
    for (Body& b : m_.bodies) {
      if (!b.flexible) continue;
      if (b.elastic.mesh.present()) {
        // The mesh itself is read and checked when code is generated (fem/elastic_model.hpp).
        if (b.elastic.modes < 1)
          error(at(b.elastic.where, "modes"), "body '" + b.name + "' keeps no modes",
                "give \"modes\": 1 or more");
        check_elastic_initial(b);
        continue;
      }
      check_beam(b);
      if (!b.elastic.assumed_modes.empty()) check_assumed_modes(m_, b);
      check_elastic_initial(b);
    }
    for (Joint& j : m_.joints)
      if (!j.parent_node_set.empty()) attach_to_node_set(j);
    for (Joint& j : m_.joints)
      if (j.parent_node != -1 && j.parent_node_set.empty()) {
        if (j.parent == m_.ground)
          error(at(j.where, "parent_node"), "the ground has no nodes", "remove \"parent_node\"");
        const Body* parent =
            check_node(j.parent_node, j.parent, at(j.where, "parent_node"), "joint '" + j.name + "'");
        if (parent && !joint_type_info(j.type).on_nodes)
          error(
              at(j.where, "parent_node"),
              "only " + joint_type_list(JointKinds::on_nodes, "and") + " joints on beam nodes are supported",
              "attach " + std::string(joint_type_info(j.type).name) + " joint '" + j.name +
                  "' to the body frame (remove \"parent_node\"), or put a fixed joint and a body on the node "
                  "and the slide on that body");
      }
    for (PointForce& f : m_.forces) {
      // A force acts at the set's averaged point, in world or body axes: the set's rotation is not used.
      if (!f.node_set.empty())
        f.node = interface_of(f.body, f.node_set, f.where, "node_set", "force '" + f.name + "'", false);
      else if (f.node != -1)
        check_node(f.node, f.body, at(f.where, "node"), "force '" + f.name + "'");
    }
    for (Output& o : m_.outputs) {
      if (!o.node_set.empty()) {
        if (o.kind != OutputKind::node_displacement)
          error(at(o.where, "node_set"),
                "output '" + o.name + "' is a beam's section resultant; a mesh body's node set has none",
                "use \"type\": \"node_displacement\" on a node set (its averaged displacement)");
        o.node = interface_of(o.body, o.node_set, o.where, "node_set", "output '" + o.name + "'", false);
        continue;
      }
      if (o.node == -1) continue;
      const Body* b = check_node(o.node, o.body, at(o.where, "node"), "output '" + o.name + "'");
      if (b && o.kind == OutputKind::bending_stress &&
          (b->elastic.fibre_y <= 0 ||
           (b->elastic.formulation == BeamFormulation::spatial && b->elastic.fibre_z <= 0)))
        error(at(o.where, "type"), "a stress output needs the extreme fibre distances of the section",
              "give \"fibre_y\" (and \"fibre_z\" for a spatial beam) under the body's flexible/section");
    }
  }

  void check_loops() {
    std::set<std::string> bodies;
    for (const Body& b : m_.bodies) bodies.insert(b.name);
    for (Loop& l : m_.loops) {
      const std::string what = "loop '" + l.name + "'";
      if (!bodies.count(l.body))
        error(at(l.where, "body"), what + " names unknown body '" + l.body + "'",
              l.body == m_.ground ? "give the ground as \"body2\" and a moving body as \"body\""
                                  : unknown_body_fix(l.body, false));
      if (l.body2 != m_.ground && !bodies.count(l.body2))
        error(at(l.where, "body2"), what + " names unknown body '" + l.body2 + "'",
              unknown_body_fix(l.body2, true));
      if (l.body == l.body2)
        error(at(l.where, "body2"), what + " ties body '" + l.body + "' to itself",
              "give two different bodies");
      if (l.node != -1) check_node(l.node, l.body, at(l.where, "node"), what);
      if (l.node2 != -1) {
        if (l.body2 == m_.ground) error(at(l.where, "node2"), "the ground has no nodes", "use \"point2\"");
        check_node(l.node2, l.body2, at(l.where, "node2"), what);
      }
      // Which sides' frames the loop's equations turn with (kane/loop_constraints.cpp): a spatial
      // hinge aligns both; a slider's line is the first body's; points alone need no rotation.
      const bool hinge = l.type == LoopType::revolute && !l.planar;
      if (!l.node_set.empty())
        l.node =
            interface_of(l.body, l.node_set, l.where, "node_set", what, hinge || l.type == LoopType::slider);
      if (!l.node_set2.empty())
        l.node2 = interface_of(l.body2, l.node_set2, l.where, "node_set2", what, hinge);
      for (double a : l.axis)
        if (!std::isfinite(a))
          error(at(l.where, "axis"), "number is not finite (" + format(a) + ")", "use a finite value");
      const double norm = std::sqrt(l.axis[0] * l.axis[0] + l.axis[1] * l.axis[1] + l.axis[2] * l.axis[2]);
      if (!(norm > 1e-12))
        error(at(l.where, "axis"), "zero-length axis of " + what,
              "give the axis a direction, e.g. [0, 0, 1]");
      for (double& a : l.axis) a /= norm;
    }
    if (!m_.loops.empty() && std::none_of(m_.joints.begin(), m_.joints.end(),
                                          [](const Joint& j) { return j.moves() && !j.is_prescribed(); }))
      error(m_.loops.front().where, "the loops close a mechanism with no free coordinate",
            "make a joint " + joint_type_list(JointKinds::moving, "or") + ", and not prescribed");
  }

  /// Craig-Bampton keeps the interfaces as coordinates: a body needs one.
  void check_interfaces() const {
    for (const Body& b : m_.bodies)
      if (b.flexible && b.elastic.mesh.craig_bampton && b.elastic.mesh.interfaces.empty())
        error(
            at(b.elastic.mesh.where, "reduction"),
            "Craig-Bampton reduction of body '" + b.name +
                "' needs an interface, and nothing is attached to its node sets",
            "attach a joint with \"parent_node_set\" (or a loop, force or output with \"node_set\"), or use "
            "\"reduction\": \"modal\"");
  }

  void check_moving_mass() const {
    if (std::none_of(m_.joints.begin(), m_.joints.end(), [](const Joint& j) { return j.moves(); }) &&
        std::none_of(m_.bodies.begin(), m_.bodies.end(), [](const Body& b) { return b.flexible; }))
      error(root_place_,
            "the model has no moving joint and no flexible body, so there is nothing to simulate",
            "make at least one joint " + joint_type_list(JointKinds::moving, "or"));
    // A moving joint that carries only massless bodies gives a zero row in M(q).
    std::map<std::string, std::vector<std::size_t>> children;  // body name -> child bodies
    std::map<std::string, std::size_t> body;
    for (std::size_t i = 0; i < m_.bodies.size(); ++i) body[m_.bodies[i].name] = i;
    for (const Joint& j : m_.joints) children[j.parent].push_back(body.at(j.child));
    for (const Joint& j : m_.joints) {
      if (!j.moves()) continue;
      bool unknown = false, massive = false;
      std::vector<std::size_t> stack{body.at(j.child)};
      while (!stack.empty()) {
        const Body& b = m_.bodies[stack.back()];
        stack.pop_back();
        unknown = unknown || !b.mass.is_literal;
        massive = massive || (b.mass.is_literal && b.mass.value > 0) || b.flexible;
        for (std::size_t c : children[b.name]) stack.push_back(c);
      }
      if (!unknown && !massive)
        error(j.where,
              "joint '" + j.name + "' moves only massless bodies, so the mass matrix would be singular",
              "give a body it carries a positive mass, or make the joint fixed");
    }
  }

  Model& m_;
  std::string file_;
  std::string root_place_;
  std::vector<int> parent_joint_;  ///< per body: index of the joint whose child it is
  ParameterValues values_;         ///< the parameters' values the physical checks use
  std::string origin_;             ///< where values_ came from, "" for the model's defaults
};

}  // namespace

void check_model(Model& model, const std::string& root_place) { Checker(model, root_place).run(); }

void check_parameter_values(const Model& model, const ParameterValues& values, const std::string& origin) {
  Model copy = model;  // the Checker may normalise; the caller's model stays as it is
  Checker(copy, values, origin).run_value_checks();
}

}  // namespace kanegen::model
