// SPDX-License-Identifier: MIT
// The typed spec of every kernel (kernels.def) as data: the Kernel enum and
// one KernelSpec per kernel (its arguments by role, which models have it,
// whether the runtime's table binds it), plus the macros that turn a spec
// line into C++ (a function-pointer member, a forwarding method). Shared by
// the runtime and the generator, so that a kernel's signature is written once.
// Plain C++17, no GiNaC: the generator includes this header, never the reverse.
#pragma once

#include <cstddef>

namespace kanegen::runtime {

/// Every kernel, in the order a generated model declares them.
enum class Kernel {
#define KANEGEN_KERNEL(name, ...) name,
#include "kanegen/runtime/kernels.def"
#undef KANEGEN_KERNEL
};

/// Which models have a kernel: the Jacobians only those generated with
/// them (an option, for implicit integration), and of those the loop one
/// only closed loops; the quadratic controller kernels only those generated
/// with --controller (which brings the Jacobians too: linearize calls them).
enum class KernelPresence { always, with_loops, with_jacobians, with_loops_and_jacobians, with_controller };

/// Whether a model with (or without) loops, generated with (or without)
/// Jacobians and controller kernels, has a kernel of this presence.
constexpr bool kernel_present(KernelPresence presence, bool loops, bool jacobians, bool controller = false) {
  switch (presence) {
    case KernelPresence::always:
      return true;
    case KernelPresence::with_loops:
      return loops;
    case KernelPresence::with_jacobians:
      return jacobians;
    case KernelPresence::with_loops_and_jacobians:
      return loops && jacobians;
    case KernelPresence::with_controller:
      return controller;
  }
  return false;
}

/// How a kernel takes the model's Params (its first argument, if any).
enum class ParamsAccess { none, read, write };

/// What an argument after Params is: an input array, an output array, a
/// scalar (double), a name (const char*) or an index (int).
enum class ArgumentRole { in, out, scalar, text, index };

/// Whether the runtime's ModelTable holds the kernel, and whether Model
/// refuses a table of a model that should have it but does not.
enum class KernelBinding { unbound, required, optional };

struct KernelArgumentSpec {
  ArgumentRole role;
  const char* name;  ///< as in the generated code, e.g. "q"
  const char* size;  ///< its length in the generated code's constants, e.g. "NU*NU"; "1" for a scalar
};

struct KernelSpec {
  Kernel kernel;
  const char* name;
  const char* returns;  ///< "void", "int", "double" or "bool"
  ParamsAccess params;
  const KernelArgumentSpec* arguments;  ///< after Params
  std::size_t argument_count;
  KernelPresence presence;
  bool counted;  ///< its operation count is listed in the generated header
  KernelBinding binding;
  /// The rows of kanegen verify's report that compare it, ";"-separated; "" if none.
  const char* verify;
  const char* doc;  ///< the declaration's comment, "///" lines without the final newline
};

// ---- turning a spec line into C++ (used by model_table.hpp, model.hpp and below)

/// An argument role as a tuple (role, name, size) for KANEGEN_FOR_EACH.
#define KANEGEN_IN(name, size) (in, name, size)
#define KANEGEN_OUT(name, size) (out, name, size)
#define KANEGEN_SCALAR(name) (scalar, name, 1)
#define KANEGEN_TEXT(name) (text, name, 1)
#define KANEGEN_INDEX(name) (index, name, 1)

#define KANEGEN_ARGUMENT_TYPE_in const double*
#define KANEGEN_ARGUMENT_TYPE_out double*
#define KANEGEN_ARGUMENT_TYPE_scalar double
#define KANEGEN_ARGUMENT_TYPE_text const char*
#define KANEGEN_ARGUMENT_TYPE_index int
/// "const double* q" from (in, q, NQ).
#define KANEGEN_TYPED_ARGUMENT(role, name, size) KANEGEN_ARGUMENT_TYPE_##role name
/// "q" from (in, q, NQ).
#define KANEGEN_ARGUMENT_NAME(role, name, size) name
/// The spec of (in, q, NQ).
#define KANEGEN_ARGUMENT_SPEC(role, name, size) \
  ::kanegen::runtime::KernelArgumentSpec { ::kanegen::runtime::ArgumentRole::role, #name, #size }

/// F applied to each (role, name, size) of a kernel's parenthesized argument
/// list, comma-separated (up to 8 arguments).
#define KANEGEN_EXPAND(x) x
#define KANEGEN_FE_1(F, a) F a
#define KANEGEN_FE_2(F, a, ...) F a, KANEGEN_EXPAND(KANEGEN_FE_1(F, __VA_ARGS__))
#define KANEGEN_FE_3(F, a, ...) F a, KANEGEN_EXPAND(KANEGEN_FE_2(F, __VA_ARGS__))
#define KANEGEN_FE_4(F, a, ...) F a, KANEGEN_EXPAND(KANEGEN_FE_3(F, __VA_ARGS__))
#define KANEGEN_FE_5(F, a, ...) F a, KANEGEN_EXPAND(KANEGEN_FE_4(F, __VA_ARGS__))
#define KANEGEN_FE_6(F, a, ...) F a, KANEGEN_EXPAND(KANEGEN_FE_5(F, __VA_ARGS__))
#define KANEGEN_FE_7(F, a, ...) F a, KANEGEN_EXPAND(KANEGEN_FE_6(F, __VA_ARGS__))
#define KANEGEN_FE_8(F, a, ...) F a, KANEGEN_EXPAND(KANEGEN_FE_7(F, __VA_ARGS__))
#define KANEGEN_FE_PICK(_1, _2, _3, _4, _5, _6, _7, _8, N, ...) N
#define KANEGEN_FOR_EACH(F, ...)                                                                      \
  KANEGEN_EXPAND(KANEGEN_FE_PICK(__VA_ARGS__, KANEGEN_FE_8, KANEGEN_FE_7, KANEGEN_FE_6, KANEGEN_FE_5, \
                                 KANEGEN_FE_4, KANEGEN_FE_3, KANEGEN_FE_2, KANEGEN_FE_1, )(F, __VA_ARGS__))
/// KANEGEN_MAP(F, (a, b)): F applied to each of a parenthesized list.
#define KANEGEN_MAP(F, arguments) KANEGEN_FOR_EACH(F, KANEGEN_UNPAREN arguments)
#define KANEGEN_UNPAREN(...) __VA_ARGS__

/// The untyped Params of a function pointer, with its comma (nothing for none).
// clang-format off
#define KANEGEN_POINTER_PARAMS_read const void* p,
#define KANEGEN_POINTER_PARAMS_write void* p,
#define KANEGEN_POINTER_PARAMS_none
// clang-format on

// ---- the specs as data

namespace kernel_spec_detail {
#define KANEGEN_KERNEL(name, returns, params, arguments, ...) \
  inline constexpr KernelArgumentSpec name##_arguments[] = {KANEGEN_MAP(KANEGEN_ARGUMENT_SPEC, arguments)};
#include "kanegen/runtime/kernels.def"
#undef KANEGEN_KERNEL
#define KANEGEN_COUNTED_counted true
#define KANEGEN_COUNTED_not_counted false
}  // namespace kernel_spec_detail

/// Every kernel's spec, in Kernel order (kernel_specs[int(k)].kernel == k).
inline constexpr KernelSpec kernel_specs[] = {
#define KANEGEN_KERNEL(name, returns, params, arguments, presence, counted, binding, wrapper, verify, doc) \
  {Kernel::name,                                                                                           \
   #name,                                                                                                  \
   #returns,                                                                                               \
   ParamsAccess::params,                                                                                   \
   kernel_spec_detail::name##_arguments,                                                                   \
   sizeof(kernel_spec_detail::name##_arguments) / sizeof(KernelArgumentSpec),                              \
   KernelPresence::presence,                                                                               \
   KANEGEN_COUNTED_##counted,                                                                              \
   KernelBinding::binding,                                                                                 \
   verify,                                                                                                 \
   doc},
#include "kanegen/runtime/kernels.def"
#undef KANEGEN_KERNEL
};

inline constexpr std::size_t kernel_count = sizeof(kernel_specs) / sizeof(KernelSpec);

/// The spec of a kernel.
constexpr const KernelSpec& kernel_spec(Kernel kernel) {
  return kernel_specs[static_cast<std::size_t>(kernel)];
}

}  // namespace kanegen::runtime
