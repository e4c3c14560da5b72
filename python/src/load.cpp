// SPDX-License-Identifier: GPL-2.0-or-later
// Loading a model's kernels: the runner cache's model library, dlopen, the
// exported table; the parameters; the lengths of the kernels' arguments.
#include <dlfcn.h>

#include <stdexcept>
#include <string>

#include "kanegen/runtime/model.hpp"
#include "kernel_thunks.hpp"
#include "loaded_model.hpp"
#include "model/model_error.hpp"
#include "runner/runner_build.hpp"

namespace kanegen::python {
namespace {

codegen::DynamicsMethod dynamics_method(const std::string& dynamics) {
  if (dynamics == "auto") return codegen::DynamicsMethod::automatic;
  if (dynamics == "recursive") return codegen::DynamicsMethod::recursive;
  if (dynamics == "composite") return codegen::DynamicsMethod::composite;
  throw py::value_error("dynamics must be \"auto\", \"recursive\" or \"composite\", not \"" + dynamics +
                        "\"");
}

[[noreturn]] void raise_model_error(const model::ModelError& e) {
  py::object error = errors().model_error(e.what());
  error.attr("file") = e.file();
  error.attr("place") = e.place();
  PyErr_SetObject(errors().model_error.ptr(), error.ptr());
  throw py::error_already_set();
}

/// The cached kernels.so of the model, built if needed (the GIL released:
/// generating and compiling take seconds).
std::string built_library(const std::string& path, const LoadArguments& arguments) {
  runner::BuildOptions options;
  options.verbose = arguments.verbose;
  options.jacobians = arguments.jacobians || arguments.controller;
  options.controller = arguments.controller;
  options.dynamics = dynamics_method(arguments.dynamics);
  try {
    py::gil_scoped_release release;
    return runner::build_model_library(path, options);
  } catch (const model::ModelError& e) {
    raise_model_error(e);
  } catch (const runner::Interrupted& e) {
    raise(errors().build_error, e.what());
  } catch (const std::exception& e) {
    raise(errors().build_error, e.what());
  }
}

}  // namespace

LoadedModel load_model(const std::string& path, const LoadArguments& arguments) {
  LoadedModel model;
  model.model_path = path;
  model.arguments = arguments;
  model.library = built_library(path, arguments);
  // Kept open for the life of the process: the kernels' code and the
  // table's names are in it, and a Model may be copied anywhere.
  void* handle = dlopen(model.library.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!handle)
    raise(errors().build_error, model.library + ": cannot load the model library (" + dlerror() + ")");
  using Export = int (*)(runtime::ModelTable*, std::size_t);
  const auto fill = reinterpret_cast<Export>(dlsym(handle, "kanegen_model_table"));
  if (!fill)
    raise(errors().build_error, model.library + ": not a kanegen model library (no kanegen_model_table)");
  if (fill(&model.table, sizeof(runtime::ModelTable)) != 0)
    raise(errors().build_error,
          model.library +
              ": built against another kanegen runtime (its ModelTable differs); remove "
              "the cache entry or rebuild kanegen");
  try {
    const runtime::Model check(model.table);  // every kernel every model has
  } catch (const std::exception& e) {
    raise(errors().build_error, model.library + ": " + e.what());
  }
  model.defaults.assign(model.table.parameters_size / sizeof(double) + 1, 0.0);
  model.table.default_parameters(model.defaults.data());
  model.parameters = model.defaults;
  for (const runtime::KernelSpec& spec : runtime::kernel_specs) {
    std::vector<ArgumentShape> shapes;
    for (std::size_t i = 0; i < spec.argument_count; ++i) {
      std::pair<int, int> shape;
      const int length = argument_length(model, spec.arguments[i].size, &shape);
      shapes.push_back({length, shape.first, shape.second});
    }
    model.shapes.push_back(std::move(shapes));
  }
  return model;
}

double parameter_value(const LoadedModel& model, const std::vector<double>& storage, int index) {
  return model.table.get_parameter(storage.data(), index);
}

void set_parameter_value(const LoadedModel& model, std::vector<double>& storage, const std::string& name,
                         double value) {
  if (model.table.set_parameter(storage.data(), name.c_str(), value)) return;
  std::string known;
  for (int i = 0; i < model.table.np; ++i)
    known += std::string(i ? ", " : "") + model.table.parameter_names[i];
  throw py::key_error(name + ": " + model.table.name + " has no parameter of that name" +
                      (known.empty() ? std::string(" (it has none)") : "; its parameters: " + known));
}

int argument_length(const LoadedModel& model, const char* size, std::pair<int, int>* shape) {
  return runtime::kernel_argument_length(model.table, size, shape);
}

}  // namespace kanegen::python
