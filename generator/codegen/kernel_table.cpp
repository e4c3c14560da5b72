// SPDX-License-Identifier: GPL-2.0-or-later
#include "codegen/kernel_table.hpp"

#include <stdexcept>

namespace kanegen::codegen {
namespace {

// clang-format off
const std::vector<KernelSignature> kTable = {
  {Kernel::set_parameter, "set_parameter", "bool", "Params& p, const char* name, double value",
   "/// Sets a parameter by name; false if there is none of that name.",
   Presence::always, false, true},
  {Kernel::get_parameter, "get_parameter", "double", "const Params& p, int i",
   "/// The parameter with index i (0 <= i < NP) in parameter_names order.",
   Presence::always, false, true},
  {Kernel::initial_state, "initial_state", "void", "const Params& p, double* q, double* u",
   "/// The initial state for the parameters p: q0 and u0, except that a\n"
   "/// prescribed coordinate starts where its motion does at t = 0.",
   Presence::always, false, true},
  {Kernel::mass_matrix, "mass_matrix", "void", "const Params& p, const double* q, double* M",
   "/// M: NU*NU, row-major, symmetric positive definite.",
   Presence::always, true, true},
  {Kernel::forcing, "forcing", "void",
   "const Params& p, double t, const double* q, const double* u, const double* tau, double* f",
   "/// f: NU. q: NQ, u: NU, tau: NTAU.",
   Presence::always, true, true},
  {Kernel::forward_dynamics, "forward_dynamics", "int",
   "const Params& p, double t, const double* q, const double* u, const double* tau, double* udot",
   "/// udot: NU, solving M udot = f by a fixed-size LDL^T. Returns 0, or k > 0\n"
   "/// when the k-th pivot is not positive (singular M; udot is then invalid).",
   Presence::always, true, true},
  {Kernel::coordinate_rates, "coordinate_rates", "void", "const double* q, const double* u, double* qdot",
   "/// qdot: NQ, the kinematic equations.",
   Presence::always, false, true},
  {Kernel::kinetic_energy, "kinetic_energy", "double", "const Params& p, const double* q, const double* u",
   "/// T, the kinetic energy.",
   Presence::always, true, true},
  {Kernel::potential_energy, "potential_energy", "double", "const Params& p, const double* q",
   "/// V, the potential energy (gravity, springs, strain).",
   Presence::always, true, true},
  {Kernel::nonconservative_power, "nonconservative_power", "double",
   "const Params& p, double t, const double* q, const double* u, const double* tau",
   "/// P, the power of the forces not from V (dampers, inputs tau, joint efforts,\n"
   "/// body-fixed forces): d(T + V)/dt = P plus the power of the drivers of\n"
   "/// prescribed motions. 0 for a conservative model.",
   Presence::always, true, true},
  {Kernel::generalized_momentum, "generalized_momentum", "void",
   "const Params& p, const double* q, const double* u, double* h",
   "/// h: NU, the generalized momenta h = M(q) u = dT/du.",
   Presence::always, false, false},
  {Kernel::outputs, "outputs", "void", "const Params& p, double t, const double* q, const double* u, double* y",
   "/// y: NY, in output_names order.",
   Presence::always, true, true},
  {Kernel::inverse_dynamics, "inverse_dynamics", "void",
   "const Params& p, double t, const double* q, const double* u, const double* udot, double* tau",
   "/// tau: NU, the generalized forces that give the accelerations udot (NU) at\n"
   "/// (t, q, u): tau = M udot - f with the inputs 0, by Newton and Euler's\n"
   "/// recursion over the tree (M is never formed; a model with flexible bodies\n"
   "/// forms M udot - f). On an actuated joint's row, the input it needs; with\n"
   "/// loops, the constraint forces are not included (docs/controllers.md).",
   Presence::always, true, true},
  {Kernel::gravity, "gravity", "void", "const Params& p, const double* q, double* g",
   "/// g: NU, the generalized gravity forces g = dV_gravity/dq, with the sign of\n"
   "/// M udot + C u + g = tau (what a controller compensates).",
   Presence::always, true, true},
  {Kernel::constraints, "constraints", "void", "const Params& p, const double* q, double* phi",
   "/// phi: NC, the loop-closure residuals Phi(q) (position rows in m; the hinge\n"
   "/// alignment rows of a spatial revolute are cosines).",
   Presence::with_loops, true, true},
  {Kernel::constraint_jacobian, "constraint_jacobian", "void", "const Params& p, const double* q, double* C",
   "/// C: NC*NU, row-major, the Jacobian dPhi/dq (q_dot = u).",
   Presence::with_loops, true, true},
  {Kernel::constraint_bias, "constraint_bias", "void",
   "const Params& p, const double* q, const double* u, double* gamma",
   "/// gamma: NC, the acceleration level C udot = gamma = -(dC/dt) u.",
   Presence::with_loops, true, true},
  {Kernel::constrained_dynamics, "constrained_dynamics", "int",
   "const Params& p, double t, const double* q, const double* u, const double* tau, double* udot, "
   "double* lambda",
   "/// udot: NU and lambda: NC from M udot = f + C^T lambda, C udot = gamma, the\n"
   "/// prescribed speeds taking their given acceleration. lambda are the loop\n"
   "/// forces (see constraint_names). Returns 0; k > 0 when the k-th pivot of M\n"
   "/// is not positive; -k when the loop equations are dependent at q (a\n"
   "/// singular configuration: the k-th pivot of C M^-1 C^T vanished).",
   Presence::with_loops, false, true},
  {Kernel::forcing_jacobian, "forcing_jacobian", "void",
   "const Params& p, double t, const double* q, const double* u, const double* tau, double* dfdq, "
   "double* dfdu",
   "/// dfdq: NU*NQ and dfdu: NU*NU, row-major, the exact partial derivatives of\n"
   "/// forcing (stiffness, damping, velocity terms, springs, prescribed motions),\n"
   "/// for implicit integration (generated with --jacobians).",
   Presence::with_jacobians, true, true},
  {Kernel::mass_matrix_product_jacobian, "mass_matrix_product_jacobian", "void",
   "const Params& p, const double* q, const double* a, double* dMa_dq",
   "/// dMa_dq: NU*NQ, row-major, d(M(q) a)/dq for a fixed a (NU).",
   Presence::with_jacobians, true, true},
  {Kernel::constraint_force_jacobian, "constraint_force_jacobian", "void",
   "const Params& p, const double* q, const double* lambda, double* dCl_dq",
   "/// dCl_dq: NU*NQ, row-major, d(C(q)^T lambda)/dq for a fixed lambda (NC).",
   Presence::with_loops_and_jacobians, true, true},
  {Kernel::coriolis_matrix, "coriolis_matrix", "void", "const Params& p, const double* q, const double* u, double* C",
   "/// C: NU*NU, row-major, the Coriolis matrix from the Christoffel symbols of M:\n"
   "/// C u is the velocity terms of M udot + C u + g = tau, and Mdot - 2C is\n"
   "/// skew-symmetric (generated with --controller).",
   Presence::with_controller, true, true},
  {Kernel::output_jacobian, "output_jacobian", "void", "const Params& p, double t, const double* q, double* J",
   "/// J: NY*NU, row-major, d(outputs)/dq, so that ydot = J u for the outputs of\n"
   "/// position (points, joint coordinates, node displacements); the rows of\n"
   "/// outputs that depend on u (speeds, loop forces) are 0 (generated with --controller).",
   Presence::with_controller, true, true},
  {Kernel::output_jacobian_rate, "output_jacobian_rate", "void",
   "const Params& p, double t, const double* q, const double* u, double* Jdot_u",
   "/// Jdot_u: NY, the bias (dJ/dt) u of ydd = J udot + Jdot_u (generated with --controller).",
   Presence::with_controller, true, true},
  {Kernel::linearize, "linearize", "int",
   "const Params& p, double t, const double* q, const double* u, const double* tau, double* A, double* B",
   "/// A: 2NU*2NU and B: 2NU*NTAU, row-major, the exact state-space matrices of\n"
   "/// x = (q, u) about (t, q, u, tau): xdot ~ A dx + B dtau. Returns 0, or k > 0\n"
   "/// when the k-th pivot of M is not positive (generated with --controller).",
   Presence::with_controller, false, true},
};
// clang-format on

}  // namespace

const std::vector<KernelSignature>& kernel_table() { return kTable; }

bool present(Presence presence, bool loops, bool jacobians, bool controller) {
  switch (presence) {
    case Presence::always:
      return true;
    case Presence::with_loops:
      return loops;
    case Presence::with_jacobians:
      return jacobians;
    case Presence::with_loops_and_jacobians:
      return loops && jacobians;
    case Presence::with_controller:
      return controller;
  }
  return false;
}

const KernelSignature& signature(Kernel kernel) {
  for (const KernelSignature& s : kTable)
    if (s.kernel == kernel) return s;
  throw std::logic_error("kernel missing from the kernel table");
}

std::vector<KernelArgument> arguments(const KernelSignature& signature) {
  std::vector<KernelArgument> out;
  const std::string text = signature.arguments;
  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t end = text.find(',', start);
    if (end == std::string::npos) end = text.size();
    std::string argument = text.substr(start, end - start);
    while (!argument.empty() && argument.front() == ' ') argument.erase(argument.begin());
    const std::size_t space = argument.rfind(' ');
    out.push_back({argument.substr(0, space), argument.substr(space + 1)});
    start = end + 1;
  }
  return out;
}

}  // namespace kanegen::codegen
