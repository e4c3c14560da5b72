// SPDX-License-Identifier: GPL-2.0-or-later
#include "fmu/fmu_binary.hpp"

#include <dlfcn.h>

#include <cstddef>
#include <memory>
#include <stdexcept>

#include "fmu/fmu_sources.hpp"
#include "fmu/shared_object.hpp"
#include "kanegen/runtime/model.hpp"
#include "kanegen/runtime/model_table.hpp"
#include "runner/runner_build.hpp"

namespace kanegen::fmu {

std::string platform_folder(int fmi_version) {
#if defined(__linux__) && defined(__x86_64__)
  return fmi_version == 2 ? "linux64" : "x86_64-linux";
#elif defined(__linux__) && defined(__aarch64__)
  if (fmi_version == 3) return "aarch64-linux";
  throw std::runtime_error("FMI 2.0 names no binaries folder for aarch64 Linux; export with --fmi 3");
#else
  (void)fmi_version;
  throw std::runtime_error("kanegen fmu builds binaries for Linux on x86_64 (and aarch64 with --fmi 3) only");
#endif
}

void compile_binary(const std::string& sources_dir, const std::map<std::string, std::string>& sources,
                    const std::string& binary, bool verbose) {
  // Hidden visibility: only the FMI functions (and the table kanegen reads) are exported, so that the
  // FMU's runtime never binds to another copy in the importer's process.
  const std::vector<std::string> flags = {"-std=c++17", "-O2", "-fPIC", "-fvisibility=hidden"};
  const std::string shared = shared_object(sources, flags, verbose);
  std::vector<std::string> args = flags;
  args.insert(args.end(), {"-shared", "-I" + sources_dir});
  std::string first;
  for (const std::string& file : compiled_files(sources))
    if (!is_shared(file)) {
      args.push_back(sources_dir + "/" + file);
      if (first.empty()) first = args.back();
    }
  args.push_back(shared);
  runner::compile_with(args, binary, "the FMU", first,
                       "the FMU's sources did not compile; please report this as a kanegen bug");
}

namespace {

std::vector<std::string> names(const char* const* list, int n) {
  std::vector<std::string> out;
  for (int i = 0; i < n; ++i) out.emplace_back(list[i]);
  return out;
}

struct Library {
  void* handle;
  ~Library() { dlclose(handle); }
};

}  // namespace

ModelFacts read_facts(const std::string& binary) {
  void* handle = dlopen(binary.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (handle == nullptr)
    throw std::runtime_error(binary + ": the FMU's binary cannot be loaded: " + dlerror());
  const Library library{handle};
  using TableExport = int (*)(runtime::ModelTable*, std::size_t);
  const auto export_table = reinterpret_cast<TableExport>(dlsym(handle, "kanegen_fmu_model_table"));
  runtime::ModelTable table;
  if (export_table == nullptr || export_table(&table, sizeof table) != 0)
    throw std::runtime_error(binary + ": the FMU's binary has no model table of this kanegen");
  // Everything is copied before the library is closed: the names live in it.
  const runtime::Model model(table);
  const runtime::ModelInfo& info = model.info();
  ModelFacts facts;
  facts.identifier = info.name;
  facts.coordinates = names(info.coordinate_names, info.nq);
  facts.speeds = names(info.speed_names, info.nu);
  facts.inputs = names(info.input_names, info.ntau);
  facts.outputs = names(info.output_names, info.ny);
  facts.parameters = names(info.parameter_names, info.np);
  facts.q0.assign(info.q0, info.q0 + info.nq);
  facts.u0.assign(info.u0, info.u0 + info.nu);
  for (int i = 0; i < info.np; ++i) facts.parameter_values.push_back(model.parameter(i));
  std::vector<double> q(static_cast<std::size_t>(info.nq) + 1), u(static_cast<std::size_t>(info.nu) + 1);
  model.initial_state(q.data(), u.data());  // prescribed coordinates start where their motion does
  facts.q0.assign(q.begin(), q.begin() + info.nq);
  facts.u0.assign(u.begin(), u.begin() + info.nu);
  facts.loops = info.nc > 0;
  if (info.coordinate_joints != nullptr) facts.coordinate_joints = names(info.coordinate_joints, info.nq);
  facts.coordinate_joints.resize(static_cast<std::size_t>(info.nq));
  return facts;
}

}  // namespace kanegen::fmu
