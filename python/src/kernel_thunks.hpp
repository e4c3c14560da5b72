// SPDX-License-Identifier: GPL-2.0-or-later
// Every kernel of the runtime's ModelTable callable through one untyped
// signature, made from the kernel spec (kanegen/runtime/kernels.def), so
// that the Python module binds each kernel from its spec rather than by hand.
#pragma once

#include <cstddef>
#include <type_traits>
#include <utility>

#include "kanegen/runtime/model_table.hpp"

namespace kanegen::python {

/// Calls one kernel of `table`: slot i of `slots` is the kernel's i-th
/// argument, Params included (a void* to the Params storage), an array as
/// its double*, a scalar as a double* to its value. Returns the kernel's
/// result as a double (0 for void).
using Thunk = double (*)(const runtime::ModelTable& table, void* const* slots);

namespace detail {

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

template <class F, F runtime::ModelTable::*member>
double thunk(const runtime::ModelTable& table, void* const* slots) {
  return Invoke<F>::run(table.*member, slots);
}

/// Whether the table holds the kernel (a null entry for a model without it).
template <class F, F runtime::ModelTable::*member>
bool present(const runtime::ModelTable& table) {
  return table.*member != nullptr;
}

}  // namespace detail

/// The thunk of a kernel and whether a table holds it; null for a kernel
/// the table does not bind (binding unbound in kernels.def).
struct KernelEntry {
  Thunk call;
  bool (*present)(const runtime::ModelTable& table);
};

// clang-format off
#define KANEGEN_PY_ENTRY_required(name) \
  KernelEntry{&detail::thunk<decltype(runtime::ModelTable::name), &runtime::ModelTable::name>, \
              &detail::present<decltype(runtime::ModelTable::name), &runtime::ModelTable::name>},
#define KANEGEN_PY_ENTRY_optional KANEGEN_PY_ENTRY_required
#define KANEGEN_PY_ENTRY_unbound(name) KernelEntry{nullptr, nullptr},
/// One entry per kernel, in Kernel order (as runtime::kernel_specs).
inline constexpr KernelEntry kernel_entries[] = {
#define KANEGEN_KERNEL(name, returns, params, arguments, presence, counted, binding, ...) \
  KANEGEN_PY_ENTRY_##binding(name)
#include "kanegen/runtime/kernels.def"
#undef KANEGEN_KERNEL
};
#undef KANEGEN_PY_ENTRY_required
#undef KANEGEN_PY_ENTRY_optional
#undef KANEGEN_PY_ENTRY_unbound
// clang-format on

static_assert(sizeof(kernel_entries) / sizeof(KernelEntry) == runtime::kernel_count,
              "one entry per kernel of kernels.def");

}  // namespace kanegen::python
