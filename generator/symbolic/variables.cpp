// SPDX-License-Identifier: GPL-2.0-or-later
#include "symbolic/variables.hpp"

#include <cmath>
#include <stdexcept>

#include "model/model_error.hpp"

namespace kanegen::symbolic {

GiNaC::ex number(double value) {
  // Integers stay exact so that 0 and 1 simplify away in products.
  if (std::abs(value) < 1e15 && value == std::floor(value)) return GiNaC::numeric(static_cast<long>(value));
  return GiNaC::numeric(value);
}

std::string prescribed_acceleration_name(int speed) { return "ap" + std::to_string(speed); }

Variables::Variables(const model::Model& model, const std::vector<int>& elastic_counts)
    : source_file_(model.source_file) {
  cpp_names_[t] = "t";
  int index = 0;
  const auto add_state = [&]() {
    const std::string i = std::to_string(index++);
    q.emplace_back("q" + i);
    u.emplace_back("u" + i);
    cpp_names_[q.back()] = "q[" + i + "]";
    cpp_names_[u.back()] = "u[" + i + "]";
    udot.emplace_back("udot" + i);
    cpp_names_[udot.back()] = "udot[" + i + "]";
  };
  first_speed.assign(model.joints.size(), -1);
  for (std::size_t k = 0; k < model.joints.size(); ++k) {
    const model::Joint& joint = model.joints[k];
    if (!joint.moves()) continue;
    first_speed[k] = index;
    if (joint.is_prescribed()) {
      const std::string name = prescribed_acceleration_name(index);
      prescribed_acceleration.emplace(index, GiNaC::symbol(name));
      cpp_names_[prescribed_acceleration.at(index)] = name;
    }
    for (int c = 0; c < model::joint_type_info(joint.type).speeds; ++c) {
      add_state();
      tau.emplace_back("tau" + std::to_string(index - 1));
      cpp_names_[tau.back()] = "tau[" + std::to_string(index - 1) + "]";
    }
  }
  joint_coordinates = index;
  elastic_first.assign(model.bodies.size(), -1);
  elastic_count.assign(model.bodies.size(), 0);
  for (std::size_t b = 0; b < elastic_counts.size() && b < model.bodies.size(); ++b) {
    if (elastic_counts[b] <= 0) continue;
    elastic_first[b] = index;
    elastic_count[b] = elastic_counts[b];
    for (int k = 0; k < elastic_counts[b]; ++k) add_state();
  }
  for (std::size_t k = 0; k < model.joints.size(); ++k) {
    if (model.joints[k].type != model::JointType::spherical) continue;
    const std::string i = std::to_string(q.size());
    quaternion_w.emplace(static_cast<int>(k), static_cast<int>(q.size()));
    q.emplace_back("q" + i);
    cpp_names_[q.back()] = "q[" + i + "]";
  }
  for (const auto& parameter : model.parameters) {
    params.emplace_back("p_" + parameter.name);
    parameter_table_[parameter.name] = params.back();
    defaults_[params.back()] = number(parameter.value);
    cpp_names_[params.back()] = "p." + parameter.name;
  }
  parameter_table_["pi"] = GiNaC::Pi;
}

GiNaC::ex Variables::scalar(const model::Scalar& s) const {
  if (s.is_literal) return number(s.value);
  GiNaC::parser reader(parameter_table_, /*strict=*/true);
  try {
    return reader(s.text);
  } catch (const std::exception& e) {
    throw model::ModelError(
        source_file_, s.where, "cannot read expression '" + s.text + "' (" + e.what() + ")",
        "use numbers, parameter names, + - * / ^, parentheses and sin cos tan sqrt exp log");
  }
}

GiNaC::ex Variables::time_expression(const std::string& text, const std::string& where) const {
  GiNaC::symtab table = parameter_table_;
  table["t"] = t;
  GiNaC::parser reader(table, /*strict=*/true);
  try {
    return reader(text);
  } catch (const std::exception& e) {
    throw model::ModelError(
        source_file_, where, "cannot read expression '" + text + "' (" + e.what() + ")",
        "use numbers, t, parameter names, + - * / ^, parentheses and sin cos tan sqrt exp log");
  }
}

double Variables::at_defaults(const GiNaC::ex& e, double time) const {
  GiNaC::exmap values = defaults_;
  values[t] = GiNaC::numeric(time);
  const GiNaC::ex v = GiNaC::evalf(e.subs(values));
  if (!GiNaC::is_a<GiNaC::numeric>(v)) throw std::logic_error("at_defaults: not a number");
  return GiNaC::ex_to<GiNaC::numeric>(v).to_double();
}

std::string Variables::cpp_name(const GiNaC::symbol& s) const {
  auto it = cpp_names_.find(s);
  return it == cpp_names_.end() ? std::string() : it->second;
}

}  // namespace kanegen::symbolic
