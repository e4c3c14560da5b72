// SPDX-License-Identifier: GPL-2.0-or-later
// Files compiled into the generator (cmake/EmbedText.cmake, kanegen_embed_files) so that an installed
// kanegen needs no data files: what every FMU's sources/ holds besides the model's own code.
#pragma once

namespace kanegen::embedded {

struct EmbeddedFile {
  const char* path;  ///< relative to sources/
  const char* text;
};

/// The runtime's sources and headers an FMU compiles, and the FMI wrapper (templates/fmu/), ended by
/// {nullptr, nullptr}. The wrapper's fmi2_entry.cpp and fmi3_entry.cpp are among them: an FMU takes the one
/// of its version (fmu_sources.cpp).
extern const EmbeddedFile fmu_files[];
/// templates/fmu/fmu_model.cpp.in: the model and the export's settings, filled per FMU.
extern const char* const fmu_model_template;
/// LICENSES/MIT.txt: the license of the runtime's files in sources/.
extern const char* const mit_license;

}  // namespace kanegen::embedded
