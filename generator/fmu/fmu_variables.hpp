// SPDX-License-Identifier: GPL-2.0-or-later
// The variables of a kanegen FMU, in value-reference order: 0 time, the coordinates q, the speeds u,
// der(q), der(u), the inputs tau, the outputs y and the parameters (templates/fmu/fmu_instance.cpp reads
// value references by the same layout). The states are q and u, all of the tree's coordinates also with
// closed loops (docs/fmu.md says why).
#pragma once

#include <string>
#include <vector>

namespace kanegen::model {
struct Model;
}

namespace kanegen::fmu {

/// What the FMU says of the model, read from its compiled kernel table (fmu_binary.hpp) and the model
/// file (units).
struct ModelFacts {
  std::string identifier;  ///< the model's name, a C identifier: modelIdentifier and the binary's name
  std::string model_file;  ///< for messages
  std::vector<std::string> coordinates, speeds, inputs, outputs, parameters;
  std::vector<double> q0, u0, parameter_values;
  /// Per coordinate: its joint ("" for an elastic coordinate).
  std::vector<std::string> coordinate_joints;
  /// Per coordinate, per speed and per input: the unit of its joint's type (model/joint_types.hpp: "rad",
  /// "rad/s", "N.m" for a turn, "m", "m/s", "N" for a slide), or "" where there is no one unit (an elastic
  /// coordinate, a quaternion's components, an input that is not a joint's "<coordinate>_tau").
  std::vector<std::string> coordinate_units, speed_units, input_units;
  bool loops = false;  ///< closed loops: the states' start values are guesses that assembly corrects
};

/// Fills the units of `facts` from the types of the joints of `model` that its coordinate_joints name. The
/// coordinates' speeds come first in q, in the order of the speeds (docs/model-format.md: a quaternion's w
/// after every coordinate with a speed), so speed i is the speed of coordinate i.
void add_units(const model::Model& model, ModelFacts& facts);

enum class Causality { independent, parameter, local, input, output };

struct Variable {
  std::string name;
  unsigned value_reference = 0;
  Causality causality = Causality::local;
  const char* variability = "continuous";  ///< "continuous" or "fixed"
  const char* initial = "";                ///< "exact", "approx", "calculated" or "" (not written)
  bool has_start = false;
  double start = 0.0;
  std::string unit;        ///< "" when kanegen does not know it
  int derivative_of = -1;  ///< for der(x): the index in the list of the state x
  std::string description;
};

struct FmuVariables {
  std::vector<Variable> all;                      ///< in value-reference order (index = value reference)
  std::vector<int> states, derivatives, outputs;  ///< indices into all
};

/// The FMU's variables of `facts`. Throws model::ModelError if two would have the same name (FMI asks
/// for unique names), naming both kinds and the model file.
FmuVariables fmu_variables(const ModelFacts& facts);

/// The units the variables use, each with its exponents of SI base units (for UnitDefinitions).
struct UnitDefinition {
  const char* name;
  int kg, m, s, rad;
};
std::vector<UnitDefinition> units_used(const FmuVariables& variables);

}  // namespace kanegen::fmu
