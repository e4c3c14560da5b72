// SPDX-License-Identifier: GPL-2.0-or-later
#include "fmu/fmu_export.hpp"

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "fmu/embedded_files.hpp"
#include "fmu/fmu_binary.hpp"
#include "fmu/fmu_sources.hpp"
#include "fmu/model_description.hpp"
#include "fmu/xml_text.hpp"
#include "fmu/zip_writer.hpp"
#include "model/model_error.hpp"
#include "pipeline/pipeline.hpp"
#include "runner/generation_interrupt.hpp"
#include "runner/runner_build.hpp"

namespace kanegen::fmu {

namespace fs = std::filesystem;

namespace {

/// A directory of its own under the system's temporary one, removed with everything in it.
class WorkDirectory {
 public:
  WorkDirectory() {
    std::string pattern = (fs::temp_directory_path() / "kanegen-fmu-XXXXXX").string();
    if (mkdtemp(pattern.data()) == nullptr)
      throw std::runtime_error(pattern + ": cannot create a temporary directory to compile the FMU in");
    path_ = pattern;
  }
  ~WorkDirectory() {
    std::error_code ignored;
    fs::remove_all(path_, ignored);
  }
  WorkDirectory(const WorkDirectory&) = delete;
  WorkDirectory& operator=(const WorkDirectory&) = delete;
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

void write_file(const fs::path& path, const std::string& bytes) {
  if (!path.parent_path().empty()) fs::create_directories(path.parent_path());
  std::ofstream out(path, std::ios::binary);
  out << bytes;
  if (!out.flush()) throw std::runtime_error(path.string() + ": cannot write");
}

std::string token_of(const pipeline::GeneratedModel& generated, const ExportOptions& o) {
  std::string bytes = KANEGEN_VERSION;
  for (const auto& [name, text] : generated.files) bytes += name + "\n" + text;
  bytes += std::to_string(o.fmi_version) + o.integrator + std::to_string(o.rtol) + std::to_string(o.atol) +
           std::to_string(o.max_step) + std::to_string(static_cast<int>(o.dynamics)) +
           (o.model_exchange ? "me" : "") + (o.co_simulation ? "cs" : "");
  return "{kanegen-" + pipeline::digest(bytes) + "}";
}

/// documentation/index.html: what the FMU is and how to build its sources.
std::string documentation(const ModelFacts& facts, const DescriptionOptions& o) {
  const std::string name = xml_attribute(facts.identifier, "the model name");
  std::string files;
  for (const std::string& file : o.source_files) files += " sources/" + xml_attribute(file, "a source file");
  return "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>" + name +
         "</title></head><body>\n<h1>" + name + "</h1>\n<p>A kanegen model, exported as an FMI " +
         std::to_string(o.fmi_version) +
         ".0 FMU: its equations of motion derived by Kane's method and emitted as C++ kernels, with "
         "kanegen's "
         "runtime (co-simulation: " +
         xml_attribute(o.integrator, "the integrator") +
         ") and FMI wrapper. The states are the coordinates and their speeds; the inputs the generalized "
         "forces "
         "of the actuated joints. With closed loops, model exchange asks for a step event when the loops "
         "drift "
         "and puts the state back on them there.</p>\n<h2>Building the sources</h2>\n<p>C++17, every .cpp "
         "file "
         "below, <code>sources/</code> the include directory, e.g.</p>\n<pre>c++ -std=c++17 -O2 -fPIC "
         "-shared "
         "-fvisibility=hidden -Isources" +
         files + " -o " + name + ".so</pre>\n<p>Define FMI" + std::to_string(o.fmi_version) +
         "_FUNCTION_PREFIX=" + name + "_ to link it statically with other FMUs.</p>\n</body></html>\n";
}

/// The archive's entries: modelDescription.xml, the binary, sources/ and documentation/.
std::string archive(const ModelFacts& facts, const DescriptionOptions& description,
                    const std::map<std::string, std::string>& sources, const fs::path& binary) {
  ZipWriter zip;
  try {
    zip.add("modelDescription.xml", model_description(facts, fmu_variables(facts), description));
  } catch (const XmlTextError& e) {  // a name XML cannot carry: the model's to fix
    throw model::ModelError(facts.model_file, "modelDescription.xml", e.what(), "");
  }
  zip.add("binaries/" + platform_folder(description.fmi_version) + "/" + facts.identifier + ".so",
          pipeline::read_file(binary.string()));
  for (const auto& [path, text] : sources) zip.add("sources/" + path, text);
  if (description.fmi_version == 3)
    zip.add("sources/buildDescription.xml", build_description(facts, description));
  zip.add("documentation/index.html", documentation(facts, description));
  // FMI 3.0 2.5.1's place for licenses; the MIT license asks that its notice go with the runtime's files.
  zip.add("documentation/licenses/kanegen-runtime-MIT.txt", embedded::mit_license);
  return zip.finish();
}

/// The .fmu under a temporary name in its directory, renamed over the output when whole.
void write_atomically(const std::string& output, const std::string& bytes) {
  const fs::path target(output);
  const fs::path temporary =
      target.parent_path() / ("." + target.filename().string() + ".tmp." + std::to_string(getpid()));
  try {
    write_file(temporary, bytes);
    fs::rename(temporary, target);
  } catch (...) {
    std::error_code ignored;
    fs::remove(temporary, ignored);
    throw;
  }
}

}  // namespace

void check_export_options(const ExportOptions& o) {
  const fs::path output(o.output);
  if (output.extension() != ".fmu" || output.stem().empty())
    throw std::invalid_argument("-o " + o.output + ": an FMU's file name ends in .fmu (e.g. -o model.fmu)");
  if (fs::is_directory(output))
    throw std::invalid_argument("-o " + o.output + " is a directory; name the .fmu file");
  check_integrator(o.integrator);
  if (!(o.rtol > 0) || !(o.atol > 0) || !(o.max_step > 0))
    throw std::invalid_argument("--rtol, --atol and --max-step must be positive");
  if (!o.model_exchange && !o.co_simulation) throw std::invalid_argument("--kind: me, cs or both");
  // Before anything is generated, as simulate -o: the directory is made, and must take the .fmu.
  const fs::path directory = fs::absolute(output).parent_path();
  std::error_code error;
  fs::create_directories(directory, error);
  if (error || access(directory.c_str(), W_OK | X_OK) != 0)
    throw std::invalid_argument("-o " + o.output + ": cannot write in " + directory.string() +
                                (error ? " (" + error.message() + ")" : std::string()) +
                                "; choose a directory of yours");
}

void export_fmu(const ExportOptions& o) {
  check_export_options(o);
  const auto start = std::chrono::steady_clock::now();
  if (o.verbose) std::fprintf(stderr, "kanegen: generating %s ...\n", o.model.c_str());
  const model::Model model = model::load_model(o.model, o.load);
  pipeline::GenerateOptions generate;
  generate.jacobians = runner::integrator_needs_jacobians(o.integrator);
  generate.dynamics = o.dynamics;
  const pipeline::GeneratedModel generated = [&] {
    const runner::StopWhileGenerating stop(o.model, "written");
    return pipeline::generate(o.model, o.load, generate);
  }();

  SourceOptions source_options{o.fmi_version, generated.name, token_of(generated, o), o.integrator, o.rtol,
                               o.atol,        o.max_step};
  const std::map<std::string, std::string> sources = fmu_sources(generated.files, source_options);
  const WorkDirectory work;
  for (const auto& [path, text] : sources) write_file(work.path() / "sources" / path, text);
  const fs::path binary = work.path() / (generated.name + ".so");
  if (o.verbose) std::fprintf(stderr, "kanegen: compiling the FMU of %s ...\n", generated.name.c_str());
  const std::vector<std::string> files = compiled_files(sources);
  compile_binary((work.path() / "sources").string(), sources, binary.string(), o.verbose);

  ModelFacts facts = read_facts(binary.string());
  facts.model_file = o.model;
  add_units(model, facts);
  DescriptionOptions description{o.fmi_version,
                                 o.model_exchange,
                                 o.co_simulation,
                                 source_options.token,
                                 "kanegen " KANEGEN_VERSION,
                                 o.integrator,
                                 files};
  write_atomically(o.output, archive(facts, description, sources, binary));
  if (o.verbose)
    std::fprintf(stderr, "kanegen: wrote %s (FMI %d.0, %s) in %.1f s\n", o.output.c_str(), o.fmi_version,
                 o.model_exchange && o.co_simulation ? "model exchange and co-simulation"
                 : o.model_exchange                  ? "model exchange"
                                                     : "co-simulation",
                 std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
}

}  // namespace kanegen::fmu
