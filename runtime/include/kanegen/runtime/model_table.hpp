// SPDX-License-Identifier: MIT
// The kernels of one generated model as plain function pointers: what the
// generated `kernel_table<kanegen::runtime::ModelTable>()` fills in (see the
// generated header), so that everything in the runner that does not depend
// on the model is compiled once, in the runtime library. Every kernel takes
// the model's Params as an untyped pointer.
#pragma once

#include <cstddef>
#include <new>
#include <type_traits>

#include "kanegen/runtime/kernel_spec.hpp"

namespace kanegen::runtime {

struct ModelTable {
  // Sizes, names and the default initial state.
  const char* name = nullptr;
  int nq = 0, nu = 0, ntau = 0, ny = 0, np = 0;
  const char* const* coordinate_names = nullptr;
  const char* const* speed_names = nullptr;
  const char* const* input_names = nullptr;
  const char* const* output_names = nullptr;
  const char* const* parameter_names = nullptr;
  const double* q0 = nullptr;
  const double* u0 = nullptr;
  /// Per coordinate (nq): its joint ("" for an elastic coordinate) and the
  /// bodies it moves, moved_bodies[moved_bodies_first[i] .. moved_bodies_first[i + 1]);
  /// null in tables written without them.
  const char* const* coordinate_joints = nullptr;
  const int* moved_bodies_first = nullptr;
  const char* const* moved_bodies = nullptr;
  /// Forces not from a potential other than the inputs (nonconservative_power
  /// not 0 at tau = 0), or prescribed motions.
  bool nonconservative = false;
  // Closed loops (0 and null for an open tree).
  int nc = 0;
  const char* const* constraint_names = nullptr;
  const int* coordinate_roles = nullptr;  ///< nq: 0 free, 1 marked independent, 2 prescribed

  /// The size of Params, and its default construction in storage of that size.
  std::size_t parameters_size = 0;
  void (*default_parameters)(void* p) = nullptr;

  /// The default P in the storage p, for a generated kernel_table's
  /// default_parameters (here, so that the generated header includes nothing).
  template <class P>
  static void construct_parameters(void* p) {
    static_assert(std::is_trivially_copyable<P>::value && alignof(P) <= alignof(double),
                  "the runtime keeps Params in storage of doubles");
    new (p) P();
  }

  // The kernels bound to the runtime, one function-pointer member each, from
  // kernels.def (the generated header documents each). A kernel a model does
  // not have (the loop kernels of an open tree, the Jacobians of a model
  // generated without them, a kernel newer than the table's writer) is null.
#define KANEGEN_MEMBER_required(name, returns, params, arguments) \
  returns (*name)(KANEGEN_POINTER_PARAMS_##params KANEGEN_MAP(KANEGEN_TYPED_ARGUMENT, arguments)) = nullptr;
#define KANEGEN_MEMBER_optional KANEGEN_MEMBER_required
#define KANEGEN_MEMBER_unbound(name, returns, params, arguments)
#define KANEGEN_KERNEL(name, returns, params, arguments, presence, counted, binding, ...) \
  KANEGEN_MEMBER_##binding(name, returns, params, arguments)
#include "kanegen/runtime/kernels.def"
#undef KANEGEN_KERNEL
#undef KANEGEN_MEMBER_required
#undef KANEGEN_MEMBER_optional
#undef KANEGEN_MEMBER_unbound
};

}  // namespace kanegen::runtime
