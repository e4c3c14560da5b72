// SPDX-License-Identifier: GPL-2.0-or-later
// The sources/ of a kanegen FMU: the model's generated code (sources/model/), the runtime's sources it
// needs (sources/kanegen/runtime/ headers, sources/kanegen_runtime/), the FMI wrapper of the FMU's version
// (sources/fmu/, from templates/fmu/) and fmu/fmu_model.cpp, which binds the model and the export's
// settings. An importer compiles the .cpp files with sources/ as the include directory (docs/fmu.md).
#pragma once

#include <map>
#include <string>
#include <vector>

namespace kanegen::fmu {

struct SourceOptions {
  int fmi_version = 2;
  std::string identifier;  ///< the model's name (a C identifier, checked)
  std::string token;
  std::string method;  ///< the co-simulation integrator: rk4, dopri5, radau or implicit
  double rtol = 1e-8, atol = 1e-10, max_step = 1e-3;
};

/// path relative to sources/ -> content. `generated` is pipeline::GeneratedModel::files (its runner is
/// left out). Throws std::invalid_argument for an integrator an FMU cannot carry.
std::map<std::string, std::string> fmu_sources(const std::map<std::string, std::string>& generated,
                                               const SourceOptions& options);

/// The files of `sources` to compile, in a fixed order.
std::vector<std::string> compiled_files(const std::map<std::string, std::string>& sources);

/// Throws std::invalid_argument, naming the ones it can, if an FMU cannot integrate with `method`.
void check_integrator(const std::string& method);

/// The integrators an FMU's co-simulation can use, for messages and --help.
const std::vector<std::string>& fmu_integrators();

}  // namespace kanegen::fmu
