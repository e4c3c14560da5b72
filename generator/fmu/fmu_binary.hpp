// SPDX-License-Identifier: GPL-2.0-or-later
// The FMU's binary for this platform: sources/ compiled as an importer would (every .cpp, sources/ the
// include directory), with the compiler the runners are built with; and the model's facts read back from
// that binary, so that modelDescription.xml names exactly what the compiled code holds.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "fmu/fmu_variables.hpp"

namespace kanegen::fmu {

/// binaries/<platform>/ of FMI 2.0 ("linux64") or 3.0 ("x86_64-linux", ...) for this machine; throws
/// std::runtime_error on a platform neither names.
std::string platform_folder(int fmi_version);

/// Compiles the .cpp files of `sources` (path -> text, written in `sources_dir`) into the shared library
/// `binary`: those that do not depend on the model through the cached shared object (shared_object.hpp),
/// the others here, all with the same flags. Throws std::runtime_error with the compiler's messages,
/// runner::Interrupted if the user stopped it.
void compile_binary(const std::string& sources_dir, const std::map<std::string, std::string>& sources,
                    const std::string& binary, bool verbose);

/// Sizes, names, initial state and default parameters of the model compiled into `binary` (through its
/// kanegen_fmu_model_table export). The units and model_file are left to the caller.
ModelFacts read_facts(const std::string& binary);

}  // namespace kanegen::fmu
