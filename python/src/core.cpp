// SPDX-License-Identifier: GPL-2.0-or-later
// kanegen._core: a model's generated kernels in-process for Python (the pure
// Python package kanegen wraps it; docs/python.md).
#include <dlfcn.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "kanegen/runtime/driver.hpp"
#include "kanegen/runtime/model.hpp"
#include "loaded_model.hpp"
#include "runner/runner_build.hpp"

namespace kanegen::python {
namespace {

std::vector<std::string> names(const char* const* list, int count) {
  std::vector<std::string> out;
  for (int i = 0; i < count; ++i) out.emplace_back(list && list[i] ? list[i] : "");
  return out;
}

py::array_t<double> vector_array(const double* values, int count) {
  py::array_t<double> out(count);
  for (int i = 0; i < count; ++i) out.mutable_data()[i] = values ? values[i] : 0.0;
  return out;
}

py::dict parameter_dict(const LoadedModel& model, const std::vector<double>& storage) {
  py::dict out;
  for (int i = 0; i < model.table.np; ++i)
    out[py::str(model.table.parameter_names[i])] = parameter_value(model, storage, i);
  return out;
}

/// The text a FILE* opened by open_memstream collected, the FILE* closed.
std::string collected(std::FILE* file, char*& buffer, std::size_t& size) {
  std::fclose(file);
  std::string text(buffer ? buffer : "", size);
  std::free(buffer);
  return text;
}

/// Runs the runtime's driver in-process on the model with its current
/// parameters: `arguments` after the program name (e.g. simulate --t-end 1).
/// Returns (exit status, what it wrote to stdout, what it wrote to stderr).
py::tuple run_driver(const LoadedModel& loaded, const std::vector<std::string>& arguments) {
  runtime::Model model(loaded.table);
  for (int i = 0; i < loaded.table.np; ++i)
    model.set_parameter(loaded.table.parameter_names[i], parameter_value(loaded, loaded.parameters, i));
  std::vector<std::string> args{"kanegen"};
  args.insert(args.end(), arguments.begin(), arguments.end());
  char *out_buffer = nullptr, *err_buffer = nullptr;
  std::size_t out_size = 0, err_size = 0;
  std::FILE* out = open_memstream(&out_buffer, &out_size);
  std::FILE* err = open_memstream(&err_buffer, &err_size);
  if (!out || !err) throw std::runtime_error("cannot allocate the simulation's output");
  int status = 0;
  {
    py::gil_scoped_release release;
    status = runtime::run_model(model, args, out, err);
  }
  const std::string out_text = collected(out, out_buffer, out_size);
  const std::string err_text = collected(err, err_buffer, err_size);
  return py::make_tuple(status, py::bytes(out_text), py::str(err_text));
}

void define_model_class(py::module_& module) {
  py::class_<LoadedModel> cls(module, "Model", "A model's compiled kernels, loaded in-process.");
  cls.def(py::init([](const std::string& path, const std::string& dynamics, bool jacobians, bool controller,
                      bool verbose) {
            return load_model(path, LoadArguments{dynamics, jacobians, controller, verbose});
          }),
          py::arg("path"), py::arg("dynamics") = "auto", py::arg("jacobians") = false,
          py::arg("controller") = false, py::arg("verbose") = false)
      .def_property_readonly("name", [](const LoadedModel& m) { return std::string(m.table.name); })
      .def_property_readonly("path", [](const LoadedModel& m) { return m.model_path; })
      .def_property_readonly("library", [](const LoadedModel& m) { return m.library; })
      .def_property_readonly("nq", [](const LoadedModel& m) { return m.table.nq; })
      .def_property_readonly("nu", [](const LoadedModel& m) { return m.table.nu; })
      .def_property_readonly("ntau", [](const LoadedModel& m) { return m.table.ntau; })
      .def_property_readonly("ny", [](const LoadedModel& m) { return m.table.ny; })
      .def_property_readonly("nc", [](const LoadedModel& m) { return m.table.nc; })
      .def_property_readonly("coordinates",
                             [](const LoadedModel& m) { return names(m.table.coordinate_names, m.table.nq); })
      .def_property_readonly("speeds",
                             [](const LoadedModel& m) { return names(m.table.speed_names, m.table.nu); })
      .def_property_readonly("inputs",
                             [](const LoadedModel& m) { return names(m.table.input_names, m.table.ntau); })
      .def_property_readonly("output_names",
                             [](const LoadedModel& m) { return names(m.table.output_names, m.table.ny); })
      .def_property_readonly("constraint_names",
                             [](const LoadedModel& m) { return names(m.table.constraint_names, m.table.nc); })
      .def_property_readonly("kernels", &kernel_methods, "The kernel methods this model's table holds.")
      .def_property_readonly("q0", [](const LoadedModel& m) { return vector_array(m.table.q0, m.table.nq); })
      .def_property_readonly("u0", [](const LoadedModel& m) { return vector_array(m.table.u0, m.table.nu); })
      .def_property_readonly(
          "parameters", [](const LoadedModel& m) { return parameter_dict(m, m.parameters); },
          "The current parameter values (a new dict; change them with set_parameters).")
      .def_property_readonly(
          "default_parameters", [](const LoadedModel& m) { return parameter_dict(m, m.defaults); },
          "The model file's parameter values.")
      .def(
          "set_parameters",
          [](LoadedModel& m, const py::dict& values) {
            std::vector<double> storage = m.parameters;  // all or nothing
            for (const auto& item : values)
              set_parameter_value(m, storage, py::cast<std::string>(item.first),
                                  py::cast<double>(item.second));
            m.parameters = std::move(storage);
          },
          py::arg("values"), "Sets parameters by name (a dict name: value); KeyError for an unknown name.")
      .def(
          "reset_parameters", [](LoadedModel& m) { m.parameters = m.defaults; },
          "Back to the model file's parameter values.")
      .def("_run_driver", &run_driver, py::arg("arguments"),
           "Runs the runtime's driver (as the runner's command line) in-process: (status, stdout bytes, "
           "stderr).");
  define_kernel_methods(cls);
}

void define_errors(py::module_& module) {
  Errors& e = errors();
  const auto make = [&](const char* name, const char* doc, PyObject* base) {
    py::object type = py::reinterpret_steal<py::object>(
        PyErr_NewExceptionWithDoc((std::string("kanegen.") + name).c_str(), doc, base, nullptr));
    if (!type) throw py::error_already_set();
    module.attr(name) = type;
    return type;
  };
  e.error = make("Error", "Every error kanegen reports; the message is kanegen's (what, where, the fix).",
                 PyExc_RuntimeError);
  e.model_error = make("ModelError", "A bad model file; .file and .place say where.", e.error.ptr());
  e.build_error = make(
      "BuildError", "The model could not be generated, compiled or cached (see the message).", e.error.ptr());
  e.missing_kernel_error =
      make("MissingKernelError",
           "The model was loaded without this kernel; the message says which load option "
           "generates it.",
           e.error.ptr());
  e.dynamics_error =
      make("DynamicsError", "The equations have no solution at this state (a singular mass matrix).",
           e.error.ptr());
  e.simulation_error =
      make("SimulationError", "A simulation failed; the message is the driver's.", e.error.ptr());
}

}  // namespace

Errors& errors() {
  static Errors* e = new Errors();  // never destroyed: Python owns the types until exit
  return *e;
}

void raise(const py::object& type, const std::string& message) {
  PyErr_SetString(type.ptr(), message.c_str());
  throw py::error_already_set();
}

}  // namespace kanegen::python

PYBIND11_MODULE(_core, module) {
  using namespace kanegen::python;
  module.doc() = "kanegen's compiled core: load a model's generated kernels and call them on NumPy arrays.";
  // The generator lives in this module, not in a kanegen executable: the
  // runner cache keys on this file, and the runtime is looked for next to it.
  Dl_info info{};
  if (dladdr(reinterpret_cast<void*>(&errors), &info) != 0 && info.dli_fname)
    kanegen::runner::set_generator_location(info.dli_fname);
  module.attr("version") = KANEGEN_VERSION;
  define_errors(module);
  define_model_class(module);
  module.def("integrator_needs_jacobians", &kanegen::runner::integrator_needs_jacobians,
             py::arg("integrator"),
             "Whether simulate's integrator needs the Jacobian kernels (load with jacobians=True).");
}
