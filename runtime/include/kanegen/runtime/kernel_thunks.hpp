// SPDX-License-Identifier: MIT
// Every kernel of a ModelTable callable through one untyped signature, made
// from the kernel spec (kernels.def), so that a caller can call a kernel it
// knows by name, its arguments sized and laid out by the spec, without
// naming it in code: the runner's batch command ("kernels") and the Python
// module. Header-only; not part of an FMU's runtime.
#pragma once

#include <cctype>
#include <cstddef>
#include <cstring>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>

#include "kanegen/runtime/kernel_spec.hpp"
#include "kanegen/runtime/model_table.hpp"

namespace kanegen::runtime {

/// Calls one kernel of `table`: slot i of `slots` is the kernel's i-th
/// argument, Params included (a void* to the Params storage), an array as
/// its double*, a scalar as a double* to its value. Returns the kernel's
/// result as a double (0 for void).
using KernelThunk = double (*)(const ModelTable& table, void* const* slots);

namespace thunk_detail {

template <class T>
struct Take;
template <>
struct Take<const void*> {
  static const void* from(void* slot) { return slot; }
};
template <>
struct Take<void*> {
  static void* from(void* slot) { return slot; }
};
template <>
struct Take<const double*> {
  static const double* from(void* slot) { return static_cast<const double*>(slot); }
};
template <>
struct Take<double*> {
  static double* from(void* slot) { return static_cast<double*>(slot); }
};
template <>
struct Take<double> {
  static double from(void* slot) { return *static_cast<const double*>(slot); }
};
template <>
struct Take<const char*> {
  static const char* from(void* slot) { return static_cast<const char*>(slot); }
};
template <>
struct Take<int> {
  static int from(void* slot) { return *static_cast<const int*>(slot); }
};

template <class F>
struct Invoke;
template <class R, class... A>
struct Invoke<R (*)(A...)> {
  template <std::size_t... I>
  static double run(R (*f)(A...), void* const* slots, std::index_sequence<I...>) {
    if constexpr (std::is_void_v<R>) {
      f(Take<A>::from(slots[I])...);
      return 0.0;
    } else {
      return static_cast<double>(f(Take<A>::from(slots[I])...));
    }
  }
  static double run(R (*f)(A...), void* const* slots) {
    return run(f, slots, std::index_sequence_for<A...>{});
  }
};

template <class F, F ModelTable::*member>
double thunk(const ModelTable& table, void* const* slots) {
  return Invoke<F>::run(table.*member, slots);
}

/// Whether the table holds the kernel (a null entry for a model without it).
template <class F, F ModelTable::*member>
bool present(const ModelTable& table) {
  return table.*member != nullptr;
}

}  // namespace thunk_detail

/// The thunk of a kernel and whether a table holds it; null for a kernel
/// the table does not bind (binding unbound in kernels.def).
struct KernelEntry {
  KernelThunk call;
  bool (*present)(const ModelTable& table);
};

// clang-format off
#define KANEGEN_THUNK_ENTRY_required(name) \
  KernelEntry{&thunk_detail::thunk<decltype(ModelTable::name), &ModelTable::name>, \
              &thunk_detail::present<decltype(ModelTable::name), &ModelTable::name>},
#define KANEGEN_THUNK_ENTRY_optional KANEGEN_THUNK_ENTRY_required
#define KANEGEN_THUNK_ENTRY_unbound(name) KernelEntry{nullptr, nullptr},
/// One entry per kernel, in Kernel order (as runtime::kernel_specs).
inline constexpr KernelEntry kernel_entries[] = {
#define KANEGEN_KERNEL(name, returns, params, arguments, presence, counted, binding, ...) \
  KANEGEN_THUNK_ENTRY_##binding(name)
#include "kanegen/runtime/kernels.def"
#undef KANEGEN_KERNEL
};
#undef KANEGEN_THUNK_ENTRY_required
#undef KANEGEN_THUNK_ENTRY_optional
#undef KANEGEN_THUNK_ENTRY_unbound
// clang-format on

static_assert(sizeof(kernel_entries) / sizeof(KernelEntry) == kernel_count,
              "one entry per kernel of kernels.def");

/// The length of a kernel argument from its size in the spec ("NU*NU",
/// "2*NU*NTAU") in the table's sizes; `shape` gets its rows and columns for
/// a matrix (its leading factors up to the first constant name are the rows;
/// columns 0 for a vector). Throws std::logic_error for a size it cannot read.
inline int kernel_argument_length(const ModelTable& t, const char* size,
                                  std::pair<int, int>* shape = nullptr) {
  int rows = 1, columns = 1;  // the leading factors up to the first name, and the others
  bool named = false;
  for (const char* at = size;;) {
    const char* end = std::strchr(at, '*');
    const std::string factor(at, end ? static_cast<std::size_t>(end - at) : std::strlen(at));
    const bool number = !factor.empty() && std::isdigit(static_cast<unsigned char>(factor[0])) != 0;
    int value = 0;
    if (number)
      value = std::stoi(factor);
    else if (factor == "NQ")
      value = t.nq;
    else if (factor == "NU")
      value = t.nu;
    else if (factor == "NTAU")
      value = t.ntau;
    else if (factor == "NY")
      value = t.ny;
    else if (factor == "NC")
      value = t.nc;
    else if (factor == "NP")
      value = t.np;
    else
      throw std::logic_error(std::string("kernel argument size ") + size + ": unknown " + factor);
    (named ? columns : rows) *= value;
    named = named || !number;
    if (!end) break;
    at = end + 1;
  }
  const bool matrix = std::strchr(size, '*') != nullptr;
  if (shape) *shape = matrix ? std::make_pair(rows, columns) : std::make_pair(rows * columns, 0);
  return rows * columns;
}

}  // namespace kanegen::runtime
