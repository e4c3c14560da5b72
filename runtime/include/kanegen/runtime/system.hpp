// SPDX-License-Identifier: MIT
// The uniform face of a generated model. Every generated header defines, in
// namespace kanegen_models::<model>, a `struct System` of this shape, for
// code that is a template over the model (examples/, the tests, RK4 loops on
// a controller). The runtime's driver needs only its kernel_table (below):
// it calls the kernels through function pointers, so the runtime library
// never depends on a particular model.
//
//   struct System {
//     using Params = <model>::Params;            // plain struct, one double per parameter
//     static constexpr int nq, nu, ntau, ny, np; // sizes (coordinates, speeds, inputs, outputs, parameters)
//     static constexpr const char* name;         // the model's name
//     static const char* const* coordinate_names();  // nq entries
//     static const char* const* speed_names();       // nu entries
//     static const char* const* input_names();       // ntau entries
//     static const char* const* output_names();      // ny entries
//     static const char* const* parameter_names();   // np entries
//     static const double* q0();                     // nq initial coordinates
//     static const double* u0();                     // nu initial speeds
//     static bool set_parameter(Params& p, const char* name, double value);  // false if unknown
//     static double get_parameter(const Params& p, int index);
//     static void initial_state(const Params& p, double* q, double* u);  // q0, u0, prescribed at t = 0
//     // M: nu*nu, row-major, symmetric
//     static void mass_matrix(const Params& p, const double* q, double* M);
//     // f: nu; M udot = f + (inputs), f includes gravity, velocity terms, springs, dampers, point forces,
//     tau static void forcing(const Params& p, double t, const double* q, const double* u, const double* tau,
//     double* f);
//     // udot: nu; returns 0 on success, k > 0 if the k-th pivot of M's LDL^T was not positive
//     static int forward_dynamics(const Params& p, double t, const double* q, const double* u, const double*
//     tau,
//                                 double* udot);
//     static void coordinate_rates(const double* q, const double* u, double* qdot);  // kinematic equations
//     static double kinetic_energy(const Params& p, const double* q, const double* u);
//     static double potential_energy(const Params& p, const double* q);
//     static void outputs(const Params& p, double t, const double* q, const double* u, double* y);  // ny
//     static void generalized_momentum(const Params& p, const double* q, const double* u, double* h);  // M u
//     // Only models with closed loops (docs/closed-loops.md) have these (their
//     // kernel_table leaves the loop entries null, nc 0, for an open tree):
//     static constexpr int nc;                          // loop-closure equations
//     static const char* const* constraint_names();     // nc entries
//     static const int* coordinate_roles();             // nq: 0 free, 1 marked independent, 2 prescribed
//     static void constraints(const Params& p, const double* q, double* phi);               // nc
//     static void constraint_jacobian(const Params& p, const double* q, double* C);         // nc*nu
//     static void constraint_bias(const Params& p, const double* q, const double* u, double* gamma);  // nc
//     static int constrained_dynamics(const Params& p, double t, const double* q, const double* u,
//                                     const double* tau, double* udot, double* lambda);  // -k: singular
//     // The same kernels as a table of function pointers, for the runtime's
//     // Model (model.hpp: make_model<System>()); Table is model_table.hpp's ModelTable:
//     template <class Table> static Table kernel_table();
//   };
//
// The generator prints every kernel's declaration, definition, System member
// and table entry from one typed spec, kernels.def, from which ModelTable and
// Model take their kernels too.
//
// All generated functions are allocation-free and exception-free; arrays
// with a size of zero are still valid pointers (sized 1 in the generated code).
#pragma once

namespace kanegen::runtime {

/// The state vector of a System is x = [q (nq); u (nu)].
template <class System>
constexpr int state_size() {
  return System::nq + System::nu;
}

}  // namespace kanegen::runtime
