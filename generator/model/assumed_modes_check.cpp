// SPDX-License-Identifier: GPL-2.0-or-later
#include "model/assumed_modes_check.hpp"

#include <Eigen/Dense>
#include <cmath>
#include <sstream>
#include <vector>

#include "model/expression_check.hpp"
#include "model/expression_eval.hpp"
#include "model/model_error.hpp"

namespace kanegen::model {
namespace {

std::string format(double v) {
  std::ostringstream out;
  out.precision(6);
  out << v;
  return out.str();
}

/// One component of a mode: its text, its place, and whether its slope is a
/// nodal dof (bending: theta_z = v', theta_y = -w').
struct Component {
  const std::string* text;
  std::string key;
  bool bending;
};

class ModeChecker {
 public:
  ModeChecker(const Model& model, const Body& body)
      : file_(model.source_file), body_(body), beam_(body.elastic), values_(default_parameter_values(model)) {
    for (const Parameter& p : model.parameters) names_.push_back(p.name);
    names_.push_back("x");
    names_.push_back("L");
    length_ = beam_.segments.empty() ? 0.0 : beam_.segments.back().to[0];
    values_["L"] = length_;
  }

  void run() {
    const int count = static_cast<int>(beam_.assumed_modes.size());
    if (count > kMaxAssumedModes)
      error(beam_.where + "/assumed_modes",
            std::to_string(count) + " assumed modes in body '" + body_.name + "', more than the limit of " +
                std::to_string(kMaxAssumedModes),
            "keep the " + std::to_string(kMaxAssumedModes) +
                " most important shapes, or use the beam's own modes (\"modes\") instead");
    std::vector<Eigen::VectorXd> samples;
    for (int k = 0; k < count; ++k) {
      const AssumedMode& mode = beam_.assumed_modes[k];
      samples.push_back(sample(mode, k + 1));
      check_deforms(samples.back(), mode, k + 1);
    }
    check_independent(samples);
  }

 private:
  [[noreturn]] void error(const std::string& place, const std::string& problem,
                          const std::string& fix) const {
    throw ModelError(file_, place, problem, fix);
  }

  std::string mode_name(int k) const {
    return "assumed mode " + std::to_string(k) + " (" + body_.name + ".mode" + std::to_string(k) + ")";
  }

  std::vector<Component> components(const AssumedMode& mode) const {
    std::vector<Component> c{{&mode.u, "u", false}, {&mode.v, "v", true}};
    if (beam_.formulation == BeamFormulation::spatial) {
      c.push_back({&mode.w, "w", true});
      c.push_back({&mode.theta, "theta", false});
    }
    return c;
  }

  double value(const std::string& text, double x, const std::string& place, const std::string& key, int k) {
    values_["x"] = x;
    const double v = evaluate_expression(text, values_);
    if (!std::isfinite(v))
      error(place,
            "'" + key + "' of " + mode_name(k) + " is " +
                (std::isnan(v) ? "not a real number (NaN)" : "infinite") + " at x = " + format(x) + " (" +
                text + ")",
            "make the shape finite on the whole beam, 0 <= x <= L (L = " + format(length_) +
                " m), at the parameters' default values");
    return v;
  }

  /// The slope by a second-order difference, one-sided at the ends so that
  /// the shape is only evaluated on the beam (sqrt(x) is fine on it).
  double slope(const std::string& text, double x, const std::string& place, const std::string& key, int k) {
    const double h = 1e-5 * length_;
    if (x - h < 0)
      return (-3 * value(text, x, place, key, k) + 4 * value(text, x + h, place, key, k) -
              value(text, x + 2 * h, place, key, k)) /
             (2 * h);
    if (x + h > length_)
      return (3 * value(text, x, place, key, k) - 4 * value(text, x - h, place, key, k) +
              value(text, x - 2 * h, place, key, k)) /
             (2 * h);
    return (value(text, x + h, place, key, k) - value(text, x - h, place, key, k)) / (2 * h);
  }

  /// The mode as the generator's basis column sees it: per node, the value of
  /// every component and L times the slope of the bending ones.
  Eigen::VectorXd sample(const AssumedMode& mode, int k) {
    const int elements = beam_.num_elements();
    std::vector<double> out;
    for (const Component& c : components(mode)) {
      const std::string place = mode.where + "/" + c.key;
      if (auto issue = check_expression(*c.text, names_))
        error(place, describe_with_caret(*c.text, *issue),
              issue->fix + " (shape functions also know x, the beam coordinate, and L, the beam length)");
      for (int i = 0; i <= elements; ++i) {
        const double x = length_ * i / elements;
        out.push_back(value(*c.text, x, place, c.key, k));
        if (c.bending) out.push_back(length_ * slope(*c.text, x, place, c.key, k));
      }
    }
    return Eigen::Map<Eigen::VectorXd>(out.data(), static_cast<Eigen::Index>(out.size()));
  }

  /// A shape that vanishes at every node would be a zero column of the basis;
  /// one without strain (constant u and theta, straight v and w) a rigid
  /// motion, which the joints carry and which has no stiffness.
  void check_deforms(const Eigen::VectorXd& s, const AssumedMode& mode, int k) const {
    const double scale = s.cwiseAbs().maxCoeff();
    if (scale < 1e-12)
      error(mode.where, mode_name(k) + " is zero at every node of the beam",
            "give it a nonzero \"u\" or \"v\"" +
                std::string(beam_.formulation == BeamFormulation::spatial ? ", \"w\" or \"theta\"" : "") +
                " in x (a missing component is 0), or remove it");
    const int nodes = beam_.num_elements() + 1;
    double strain = 0;
    int offset = 0;
    for (const Component& c : components(mode)) {
      // Per node: the value, then (bending) L times the slope; strain is a
      // change of the slope in bending, of the value otherwise.
      const int stride = c.bending ? 2 : 1, first = offset + (c.bending ? 1 : 0);
      for (int i = 0; i + 1 < nodes; ++i)
        strain = std::max(strain, std::abs(s[first + (i + 1) * stride] - s[first + i * stride]));
      offset += stride * nodes;
    }
    if (strain < 1e-9 * scale)
      error(mode.where,
            mode_name(k) + " does not deform the beam (constant u" +
                std::string(beam_.formulation == BeamFormulation::spatial ? " and theta, straight v and w"
                                                                          : ", straight v") +
                "): it is a rigid motion",
            "make it a function of x that bends, stretches or twists the beam (the joints carry the rigid "
            "motion)");
  }

  /// Each sampled shape must not be a combination of the earlier ones (on the
  /// nodes, which is what the basis holds): the mass matrix would be singular.
  void check_independent(const std::vector<Eigen::VectorXd>& samples) const {
    for (std::size_t k = 1; k < samples.size(); ++k) {
      Eigen::MatrixXd earlier(samples[k].size(), static_cast<Eigen::Index>(k));
      for (std::size_t j = 0; j < k; ++j) earlier.col(static_cast<Eigen::Index>(j)) = samples[j];
      const Eigen::VectorXd c = earlier.colPivHouseholderQr().solve(samples[k]);
      const double residual = (earlier * c - samples[k]).norm();
      if (residual > 1e-8 * samples[k].norm()) continue;
      std::string combination;
      for (Eigen::Index j = 0; j < c.size(); ++j) {
        if (std::abs(c[j]) < 1e-9 * c.cwiseAbs().maxCoeff()) continue;
        const std::string sign = combination.empty() ? (c[j] < 0 ? "-" : "") : (c[j] < 0 ? " - " : " + ");
        combination += sign + format(std::abs(c[j])) + " * mode " + std::to_string(j + 1);
      }
      const int number = static_cast<int>(k) + 1;
      error(beam_.assumed_modes[k].where,
            mode_name(number) + " is linearly dependent on the modes before it: at the nodes it is " +
                combination,
            "remove it or change it (the shapes are sampled at the " +
                std::to_string(beam_.num_elements() + 1) + " nodes of a mesh of " +
                std::to_string(beam_.num_elements()) +
                " \"elements\": a shape that oscillates faster than the mesh needs more elements)");
    }
  }

  std::string file_;
  const Body& body_;
  const ElasticPart& beam_;
  ParameterValues values_;
  std::vector<std::string> names_;
  double length_ = 0.0;
};

}  // namespace

void check_assumed_modes(const Model& model, Body& body) {
  for (const Parameter& p : model.parameters)
    if (p.name == "x" || p.name == "L")
      throw ModelError(
          model.source_file, p.where,
          "parameter '" + p.name + "' clashes with the " +
              (p.name == "x" ? "beam coordinate x" : "beam length L") + " of the assumed modes of body '" +
              body.name + "'",
          "rename the parameter: in shape functions x is the beam coordinate and L the beam length");
  ModeChecker(model, body).run();
  body.elastic.shape_parameters = default_parameter_values(model);
}

}  // namespace kanegen::model
