// SPDX-License-Identifier: GPL-2.0-or-later
// One Python method per kernel of the spec, with its arguments' names:
// the input arrays in the spec's order, then its scalars (default 0), then
// params=None, e.g. forward_dynamics(q, u, tau, t=0.0, params=None).
#include <string>
#include <utility>
#include <vector>

#include "kernel_thunks.hpp"
#include "loaded_model.hpp"

namespace kanegen::python {
namespace {

using runtime::ArgumentRole;
using runtime::KernelSpec;

template <std::size_t>
using Object = py::object;

/// The names of the kernel's Python arguments: arrays first, then scalars.
struct Names {
  const char* arrays[8] = {};
  const char* scalars[8] = {};
  std::size_t array_count = 0, scalar_count = 0;
};

std::string docstring(const KernelSpec& spec) {
  std::string doc;
  const std::string text = spec.doc;
  std::size_t at = 0;
  while (at < text.size()) {
    std::size_t end = text.find('\n', at);
    if (end == std::string::npos) end = text.size();
    std::string line = text.substr(at, end - at);
    if (line.rfind("/// ", 0) == 0)
      line = line.substr(4);
    else if (line.rfind("///", 0) == 0)
      line = line.substr(3);
    doc += line + "\n";
    at = end + 1;
  }
  return doc +
         "\nArrays: 1-D for one state, or 2-D with one state per row (computed in C++ over the rows, "
         "the GIL released). params: None (the model's values) or a dict of values for this call.";
}

template <std::size_t... A, std::size_t... S>
void define(py::class_<LoadedModel>& cls, runtime::Kernel kernel, const Names& names,
            std::index_sequence<A...>, std::index_sequence<S...>) {
  const KernelSpec& spec = runtime::kernel_spec(kernel);
  cls.def(
      spec.name,
      [kernel](LoadedModel& model, Object<A>... arrays, Object<S>... scalars, py::object params) {
        const py::handle arguments[] = {arrays..., scalars..., py::handle()};
        return call_kernel(model, kernel, arguments, sizeof...(A) + sizeof...(S), params);
      },
      py::arg(names.arrays[A])..., py::arg_v(names.scalars[S], 0.0)..., py::arg_v("params", py::none()),
      docstring(spec).c_str());
}

/// As define, for a kernel whose last input array is tau: it may be omitted (None: zeros).
template <std::size_t... A, std::size_t... S>
void define_with_tau(py::class_<LoadedModel>& cls, runtime::Kernel kernel, const Names& names,
                     std::index_sequence<A...>, std::index_sequence<S...>) {
  const KernelSpec& spec = runtime::kernel_spec(kernel);
  cls.def(
      spec.name,
      [kernel](LoadedModel& model, Object<A>... arrays, py::object tau, Object<S>... scalars,
               py::object params) {
        const py::handle arguments[] = {arrays..., tau, scalars..., py::handle()};
        return call_kernel(model, kernel, arguments, sizeof...(A) + 1 + sizeof...(S), params);
      },
      py::arg(names.arrays[A])..., py::arg_v("tau", py::none()), py::arg_v(names.scalars[S], 0.0)...,
      py::arg_v("params", py::none()), docstring(spec).c_str());
}

template <std::size_t NA>
void define_with_arrays(py::class_<LoadedModel>& cls, runtime::Kernel kernel, const Names& names) {
  const bool tau_last = NA > 0 && std::string(names.arrays[NA - 1]) == "tau";
  constexpr std::size_t before_tau = NA > 0 ? NA - 1 : 0;
  if (names.scalar_count > 1)
    throw std::logic_error(std::string(runtime::kernel_spec(kernel).name) +
                           ": more than one scalar argument");
  if (tau_last && names.scalar_count == 0)
    define_with_tau(cls, kernel, names, std::make_index_sequence<before_tau>{},
                    std::make_index_sequence<0>{});
  else if (tau_last)
    define_with_tau(cls, kernel, names, std::make_index_sequence<before_tau>{},
                    std::make_index_sequence<1>{});
  else if (names.scalar_count == 0)
    define(cls, kernel, names, std::make_index_sequence<NA>{}, std::make_index_sequence<0>{});
  else
    define(cls, kernel, names, std::make_index_sequence<NA>{}, std::make_index_sequence<1>{});
}

/// Whether the kernel is a method: bound in the runtime's table, and taking
/// no name or index (set_parameter, get_parameter: the parameter methods).
bool bindable(const KernelSpec& spec) {
  if (spec.binding == runtime::KernelBinding::unbound) return false;
  for (std::size_t i = 0; i < spec.argument_count; ++i)
    if (spec.arguments[i].role == ArgumentRole::text || spec.arguments[i].role == ArgumentRole::index)
      return false;
  return true;
}

}  // namespace

std::vector<std::string> kernel_methods(const LoadedModel& model) {
  std::vector<std::string> out;
  for (const KernelSpec& spec : runtime::kernel_specs)
    if (bindable(spec) && kernel_entries[static_cast<std::size_t>(spec.kernel)].present(model.table))
      out.emplace_back(spec.name);
  return out;
}

void define_kernel_methods(py::class_<LoadedModel>& cls) {
  for (const KernelSpec& spec : runtime::kernel_specs) {
    if (!bindable(spec)) continue;
    Names names;
    for (std::size_t i = 0; i < spec.argument_count; ++i) {
      const ArgumentRole role = spec.arguments[i].role;
      if (role == ArgumentRole::in) names.arrays[names.array_count++] = spec.arguments[i].name;
      if (role == ArgumentRole::scalar) names.scalars[names.scalar_count++] = spec.arguments[i].name;
    }
    switch (names.array_count) {
      case 0:
        define_with_arrays<0>(cls, spec.kernel, names);
        break;
      case 1:
        define_with_arrays<1>(cls, spec.kernel, names);
        break;
      case 2:
        define_with_arrays<2>(cls, spec.kernel, names);
        break;
      case 3:
        define_with_arrays<3>(cls, spec.kernel, names);
        break;
      case 4:
        define_with_arrays<4>(cls, spec.kernel, names);
        break;
      default:
        throw std::logic_error(std::string(spec.name) + ": more input arrays than the module binds");
    }
  }
}

}  // namespace kanegen::python
