// SPDX-License-Identifier: MIT
// This file is kanegen's output: you may use, copy, modify and distribute it under any terms you choose
// (docs/licensing.md).
// One instance of a kanegen FMU, whatever the FMI version: the model's kernels through the runtime's Model,
// its variables by value reference, model exchange (states, derivatives, the loops' drift as step events)
// and co-simulation (the runtime's integrators between communication points). fmi2_entry.cpp and
// fmi3_entry.cpp turn the FMI calls into calls of this class (docs/fmu.md).
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "kanegen/runtime/loops.hpp"
#include "kanegen/runtime/methods.hpp"
#include "kanegen/runtime/model.hpp"

namespace kanegen_fmu {

/// What the generated fmu_model.cpp fixes at export (kanegen fmu --integrator, --rtol, --atol, --max-step).
struct Settings {
  const char* token;                ///< fmi2 GUID / fmi3 instantiationToken
  kanegen::runtime::Method method;  ///< the co-simulation integrator
  double rtol, atol;                ///< its tolerances (adaptive methods)
  double max_step;                  ///< rk4's largest step inside a communication step
};
kanegen::runtime::ModelTable model_table();
Settings settings();

/// The value references, in this order (the exporter writes modelDescription.xml by the same layout):
/// 0 time, then the coordinates q, the speeds u, der(q), der(u), the inputs tau, the outputs y and
/// the parameters.
enum class Role { time, coordinate, speed, coordinate_rate, acceleration, input, output, parameter, none };
struct Variable {
  Role role = Role::none;
  int index = 0;
};

class Instance {
 public:
  /// error: whether the message reports a failure (else it is information).
  using Logger = std::function<void(bool error, const std::string& message)>;
  explicit Instance(Logger logger);

  Variable variable(unsigned value_reference) const;
  int state_count() const { return nq_ + nu_; }
  bool initialized() const { return initialized_; }
  double time() const { return t_; }

  /// Back to the state after instantiation (fmi2Reset, fmi3Reset).
  void reset();
  void enter_initialization(double start_time);
  /// The states not set are the model's initial state for the parameters set; with loops, the
  /// state is then assembled. False (logged) if the loops do not close.
  bool exit_initialization();

  /// False (logged) for an unknown value reference or a variable that cannot be set now.
  bool get(unsigned value_reference, double* value);
  bool set(unsigned value_reference, double value);

  // Model exchange.
  void set_time(double t) { t_ = t; }
  void set_states(const double* x);
  void get_states(double* x) const;
  /// dx/dt of the states (nq + nu); false (logged) at a singular configuration.
  bool derivatives(double* dx);
  /// Whether the loops have drifted past the tolerance (an integrator step completed).
  bool drifted() const;
  /// Puts the state back on the loops (event mode); *changed when it moved. False (logged) if it fails.
  bool project(bool* changed);

  /// Reports a failure through the importer's logger.
  void log_error(const std::string& message) const;

  // Co-simulation: integrates [t, t + h] with the inputs held. False (logged) if the integrator fails.
  bool do_step(double t, double h);

 private:
  int evaluate(double t, const double* x, double* dx);
  bool derivatives_at(const double* x, double* dx);
  /// x with the states not set replaced by the model's initial state, then assembled on the loops
  /// (*assembly says how); false (logged) if they do not close.
  bool start_state(std::vector<double>& x, kanegen::runtime::Assembly* assembly) const;

  Logger logger_;
  Settings settings_;
  kanegen::runtime::ModelTable table_;
  kanegen::runtime::Model model_;
  kanegen::runtime::LoopSolver loops_;
  int nq_, nu_, ntau_, ny_, np_;
  double t_ = 0.0;
  std::vector<double> x_, tau_, y_, dx_, lambda_;
  std::vector<char> state_set_;  ///< states given a value before initialization ended
  bool initialized_ = false;
};

}  // namespace kanegen_fmu
