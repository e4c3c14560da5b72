// SPDX-License-Identifier: GPL-2.0-or-later
#include "fmu/fmu_variables.hpp"

#include <map>
#include <stdexcept>

#include "model/joint_types.hpp"
#include "model/model.hpp"
#include "model/model_error.hpp"

namespace kanegen::fmu {

namespace {

const UnitDefinition kUnits[] = {
    {"rad", 0, 0, 0, 1},  {"rad/s", 0, 0, -1, 1}, {"rad/s2", 0, 0, -2, 1},
    {"m", 0, 1, 0, 0},    {"m/s", 0, 1, -1, 0},   {"m/s2", 0, 1, -2, 0},
    {"N.m", 1, 2, -2, 0}, {"N", 1, 1, -2, 0},     {"s", 0, 0, 1, 0},
};

std::string per_second(const std::string& unit, const char* suffix) {
  return unit.empty() ? "" : unit + suffix;
}

Variable variable(const std::string& name, Causality causality, const std::string& description) {
  Variable v;
  v.name = name;
  v.causality = causality;
  v.description = description;
  return v;
}

// q, u and their derivatives.
void add_states(const ModelFacts& f, FmuVariables& out) {
  const char* initial = f.loops ? "approx" : "exact";  // with loops, assembly moves the dependent ones
  for (std::size_t i = 0; i < f.coordinates.size(); ++i) {
    Variable v = variable(f.coordinates[i], Causality::local, "coordinate");
    v.initial = initial;
    v.has_start = true;
    v.start = f.q0[i];
    v.unit = f.coordinate_units[i];
    out.states.push_back(static_cast<int>(out.all.size()));
    out.all.push_back(v);
  }
  for (std::size_t i = 0; i < f.speeds.size(); ++i) {
    Variable v = variable(f.speeds[i], Causality::local, "speed");
    v.initial = initial;
    v.has_start = true;
    v.start = f.u0[i];
    v.unit = i < f.speed_units.size() ? f.speed_units[i] : "";
    out.states.push_back(static_cast<int>(out.all.size()));
    out.all.push_back(v);
  }
  const std::size_t state_count = out.states.size();
  for (std::size_t k = 0; k < state_count; ++k) {
    const Variable& state = out.all[static_cast<std::size_t>(out.states[k])];
    Variable v = variable("der(" + state.name + ")", Causality::local, "derivative");
    v.initial = "calculated";
    v.unit = per_second(state.unit, k < f.coordinates.size() ? "/s" : "");
    if (k >= f.coordinates.size() && !state.unit.empty()) v.unit = state.unit + "2";  // rad/s -> rad/s2
    v.derivative_of = out.states[k];
    out.derivatives.push_back(static_cast<int>(out.all.size()));
    out.all.push_back(v);
  }
}

}  // namespace

void add_units(const model::Model& model, ModelFacts& facts) {
  const std::size_t n = facts.coordinates.size();
  facts.coordinate_units.assign(n, "");
  facts.speed_units.assign(facts.speeds.size(), "");
  facts.input_units.assign(facts.inputs.size(), "");
  for (std::size_t i = 0; i < n && i < facts.coordinate_joints.size(); ++i) {
    const model::JointTypeInfo* type = nullptr;
    for (const model::Joint& joint : model.joints)
      if (!facts.coordinate_joints[i].empty() && joint.name == facts.coordinate_joints[i])
        type = &model::joint_type_info(joint.type);
    if (type == nullptr) continue;
    facts.coordinate_units[i] = type->coordinate_unit;
    if (i < facts.speeds.size()) facts.speed_units[i] = type->speed_unit;
    for (std::size_t k = 0; k < facts.inputs.size(); ++k)
      if (facts.inputs[k] == facts.coordinates[i] + "_tau") facts.input_units[k] = type->force_unit;
  }
}

FmuVariables fmu_variables(const ModelFacts& f) {
  FmuVariables out;
  out.all.push_back(variable("time", Causality::independent, "time"));
  out.all.back().unit = "s";
  add_states(f, out);
  for (std::size_t i = 0; i < f.inputs.size(); ++i) {
    Variable v = variable(f.inputs[i], Causality::input, "generalized force of an actuated joint");
    v.has_start = true;  // inputs have a start value and no initial (FMI 2.0 2.2.7, FMI 3.0 2.4.7.4)
    v.unit = f.input_units[i];
    out.all.push_back(v);
  }
  for (const std::string& name : f.outputs) {
    out.outputs.push_back(static_cast<int>(out.all.size()));
    out.all.push_back(variable(name, Causality::output, "output"));
  }
  for (std::size_t i = 0; i < f.parameters.size(); ++i) {
    Variable v = variable(f.parameters[i], Causality::parameter, "parameter");
    v.variability = "fixed";  // the loops are assembled, and the initial state computed, with them
    v.initial = "exact";
    v.has_start = true;
    v.start = f.parameter_values[i];
    out.all.push_back(v);
  }
  std::map<std::string, std::size_t> seen;
  for (std::size_t i = 0; i < out.all.size(); ++i) {
    out.all[i].value_reference = static_cast<unsigned>(i);
    const auto [at, fresh] = seen.emplace(out.all[i].name, i);
    if (!fresh)
      throw model::ModelError(
          f.model_file, "the FMU's variable '" + out.all[i].name + "'",
          "two variables would have this name (kinds: " + out.all[at->second].description + ", " +
              out.all[i].description + "), and FMI asks for unique names",
          "rename one in the model file");
  }
  return out;
}

std::vector<UnitDefinition> units_used(const FmuVariables& variables) {
  std::vector<UnitDefinition> used;
  for (const UnitDefinition& unit : kUnits)
    for (const Variable& v : variables.all)
      if (v.unit == unit.name) {
        used.push_back(unit);
        break;
      }
  return used;
}

}  // namespace kanegen::fmu
