// SPDX-License-Identifier: GPL-2.0-or-later
// modelDescription.xml of a kanegen FMU, FMI 2.0 or 3.0, and FMI 3.0's sources/buildDescription.xml. Every
// text from the model passes through xml_attribute (xml_text.hpp).
#pragma once

#include <string>
#include <vector>

#include "fmu/fmu_variables.hpp"

namespace kanegen::fmu {

struct DescriptionOptions {
  int fmi_version = 2;         ///< 2 or 3
  bool model_exchange = true;  ///< the FMU's interfaces
  bool co_simulation = true;
  std::string token;                      ///< fmi2 guid / fmi3 instantiationToken
  std::string generation_tool;            ///< "kanegen VERSION"
  std::string integrator;                 ///< the co-simulation integrator, for the description
  std::vector<std::string> source_files;  ///< relative to sources/, the files an importer compiles
};

std::string model_description(const ModelFacts& facts, const FmuVariables& variables,
                              const DescriptionOptions& options);

/// sources/buildDescription.xml (FMI 3.0, 2.5.2): the files to compile, their language and include directory.
std::string build_description(const ModelFacts& facts, const DescriptionOptions& options);

}  // namespace kanegen::fmu
