// SPDX-License-Identifier: GPL-2.0-or-later
// `kanegen fmu`: a model file to an FMU (FMI 2.0 or 3.0; model exchange, co-simulation or both) holding
// modelDescription.xml, the binary for this platform and the sources that build it (docs/fmu.md). The
// .fmu is written whole or not at all: under a temporary name, renamed when complete.
#pragma once

#include <string>

#include "codegen/model_kernels.hpp"
#include "model/load.hpp"

namespace kanegen::fmu {

struct ExportOptions {
  std::string model;   ///< the model file
  std::string output;  ///< NAME.fmu
  int fmi_version = 2;
  bool model_exchange = true, co_simulation = true;
  std::string integrator = "dopri5";  ///< co-simulation
  double rtol = 1e-8, atol = 1e-10;
  double max_step = 1e-3;  ///< rk4's largest step within a communication step
  model::LoadOptions load;
  codegen::DynamicsMethod dynamics = codegen::DynamicsMethod::automatic;  ///< --dynamics
  bool verbose = true;
};

/// Checks what can be checked before anything is generated (the output's name and directory, the
/// integrator); throws std::invalid_argument naming the option and the fix.
void check_export_options(const ExportOptions& options);

/// Writes options.output. Throws model::ModelError for a bad model, std::runtime_error otherwise (an
/// existing file at the output is then left as it was).
void export_fmu(const ExportOptions& options);

}  // namespace kanegen::fmu
