// SPDX-License-Identifier: GPL-2.0-or-later
#include "fmu/shared_object.hpp"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "pipeline/pipeline.hpp"
#include "runner/runner_build.hpp"
#include "runner/runner_cache.hpp"

namespace kanegen::fmu {

namespace fs = std::filesystem;

namespace {

constexpr const char* kArtifact = "shared.o";

bool starts_with(const std::string& text, const std::string& start) { return text.rfind(start, 0) == 0; }

/// The shared .cpp files and every header they may include: every file but the model's own, its settings
/// and the FMI entry points with their declarations (which differ between FMI 2.0 and 3.0, so that both
/// versions share the object).
bool model_independent(const std::string& file) {
  return !starts_with(file, "model/") && !starts_with(file, "fmu/fmi") &&
         !starts_with(file, "fmu/kanegen_fmi") && file != "fmu/fmu_model.cpp";
}

void write(const fs::path& path, const std::string& text) {
  fs::create_directories(path.parent_path());
  std::ofstream out(path, std::ios::binary);
  out << text;
  if (!out.flush()) throw std::runtime_error(path.string() + ": cannot write");
}

}  // namespace

bool is_shared(const std::string& file) {
  return (starts_with(file, "kanegen_runtime/") && file.size() > 4 &&
          file.compare(file.size() - 4, 4, ".cpp") == 0) ||
         file == "fmu/fmu_instance.cpp";
}

std::string shared_object(const std::map<std::string, std::string>& sources,
                          const std::vector<std::string>& flags, bool verbose) {
  std::string key = KANEGEN_VERSION "\n" + runner::compiler_command() + "\n";
  for (const std::string& flag : flags) key += flag + "\n";
  std::vector<std::string> files;
  for (const auto& [file, text] : sources)
    if (model_independent(file)) {
      key += file + "\n" + pipeline::digest(text) + "\n";
      files.push_back(file);
    }
  const fs::path dir = runner::checked_cache_root() / ("fmu-shared-" + pipeline::digest(key));
  const runner::EntryLock lock(dir, verbose);  // one builder; the others wait and use its object
  std::string changed;
  switch (runner::entry_state(dir, &changed, kArtifact)) {
    case runner::EntryState::intact:
      return (dir / kArtifact).string();
    case runner::EntryState::changed:
      std::fprintf(stderr,
                   "kanegen: the cached FMU runtime in %s is not as it was built (%s); rebuilding it\n",
                   dir.c_str(), changed.c_str());
      runner::discard_entry(dir, kArtifact);
      break;
    case runner::EntryState::missing:
      break;
  }
  if (verbose)
    std::fprintf(stderr, "kanegen: compiling the FMU runtime (once; cached in %s) ...\n", dir.c_str());
  std::vector<std::string> args = flags;
  args.insert(args.end(), {"-nostdlib", "-r", "-I" + dir.string()});  // one relocatable object
  for (const std::string& file : files) {
    write(dir / file, sources.at(file));
    if (is_shared(file)) args.push_back((dir / file).string());
  }
  runner::compile_with(args, (dir / kArtifact).string(), "the FMU runtime",
                       (dir / "fmu/fmu_instance.cpp").string(),
                       "the FMU's runtime sources did not compile; please report this as a kanegen bug");
  runner::seal_entry(dir, files, kArtifact);
  return (dir / kArtifact).string();
}

}  // namespace kanegen::fmu
