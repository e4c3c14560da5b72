// SPDX-License-Identifier: GPL-2.0-or-later
// A model's kernels loaded in-process for the Python module: the compiled
// model library (runner::build_model_library) opened with dlopen, its kernel
// table, and the parameter values the kernels are called with.
#pragma once

#include <pybind11/pybind11.h>

#include <string>
#include <utility>
#include <vector>

#include "kanegen/runtime/kernel_spec.hpp"
#include "kanegen/runtime/model_table.hpp"

namespace kanegen::python {

namespace py = pybind11;

/// How the model is generated (the runner cache's options).
struct LoadArguments {
  std::string dynamics = "auto";  ///< auto, recursive or composite
  bool jacobians = false;
  bool controller = false;
  bool verbose = false;
};

/// The length of a kernel argument and, for a matrix, its rows and columns
/// (columns 0 for a vector).
struct ArgumentShape {
  int length = 0, rows = 0, columns = 0;
};

struct LoadedModel {
  std::string model_path;  ///< as given to load
  std::string library;     ///< the cached kernels.so
  LoadArguments arguments;
  runtime::ModelTable table;
  std::vector<double> defaults;    ///< the Params storage with the model file's values
  std::vector<double> parameters;  ///< the Params storage the kernels are called with
  /// Per kernel (Kernel order), the shape of each argument (computed once, at load).
  std::vector<std::vector<ArgumentShape>> shapes;
};

/// Generates and compiles the model (through the runner cache) and loads its
/// kernels; raises kanegen.ModelError, kanegen.BuildError or kanegen.Error.
LoadedModel load_model(const std::string& path, const LoadArguments& arguments);

/// The value of parameter `index` in the Params storage `storage`.
double parameter_value(const LoadedModel& model, const std::vector<double>& storage, int index);
/// Sets parameter `name` in `storage`; raises KeyError naming the model's
/// parameters when it has none of that name.
void set_parameter_value(const LoadedModel& model, std::vector<double>& storage, const std::string& name,
                         double value);

/// The length of a kernel argument from its size in the spec ("NU*NU",
/// "2*NU*NTAU"); `shape` gets its rows and columns for a matrix (its
/// leading factors up to the first constant name are the rows; columns 0
/// for a vector).
int argument_length(const LoadedModel& model, const char* size, std::pair<int, int>* shape = nullptr);

/// Calls `kernel` on the Python arguments: its input arrays (1-D, or 2-D
/// with one state per row) and then its scalars, in the spec's order, and
/// `params` (None, or a dict of parameter values for this call).
py::object call_kernel(LoadedModel& model, runtime::Kernel kernel, const py::handle* arguments,
                       std::size_t count, py::handle params);

/// Defines one method per kernel of the spec that the runtime's table binds
/// (those taking a name or an index excepted: parameters have their own
/// methods) on the Python class.
void define_kernel_methods(py::class_<LoadedModel>& cls);

/// The kernel methods the model's table holds (a model without loops or
/// generated without the Jacobians has fewer).
std::vector<std::string> kernel_methods(const LoadedModel& model);

/// The Python exception types of the module (created by the module).
struct Errors {
  py::object error, model_error, build_error, missing_kernel_error, dynamics_error, simulation_error;
};
Errors& errors();
/// Raises `type` with `message` (throws py::error_already_set).
[[noreturn]] void raise(const py::object& type, const std::string& message);

}  // namespace kanegen::python
