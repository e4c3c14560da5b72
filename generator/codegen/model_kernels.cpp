// SPDX-License-Identifier: GPL-2.0-or-later
#include "codegen/model_kernels.hpp"

#include <stdexcept>
#include <string>

#include "codegen/cpp_printer.hpp"
#include "codegen/graph_derivative.hpp"
#include "codegen/unrolled_ldlt.hpp"

namespace kanegen::codegen {
namespace {

std::string str(long i) { return std::to_string(i); }

/// What the kernels of one model share: its equations, the graph they are
/// printed from, and which speeds are solved for.
struct Derivation {
  const model::Model& model;
  const kane::Equations& eq;
  const symbolic::Variables& vars;
  ExpressionGraph& graph;
  /// The speeds solved for (not prescribed), and each speed's index among
  /// them (-1 for a prescribed one).
  std::vector<int> solved, local;
  /// The given accelerations, piece by piece, as the first statements of the dynamics.
  KernelCode prescribed{Kernel::forward_dynamics, "", 0, ""};

  int n() const { return eq.nu; }
  int ns() const { return static_cast<int>(solved.size()); }
  bool loops() const { return eq.loops.size() > 0; }
  /// f_i - sum_p M_ip a_p over the prescribed speeds p: the right-hand side of a solved row.
  GiNaC::ex solved_rhs(int i) const {
    GiNaC::ex rhs = eq.forcing[i];
    for (const auto& [p, a] : vars.prescribed_acceleration) rhs -= eq.mass_matrix[i * n() + p] * a;
    return rhs;
  }
};

KernelCode printed(Kernel kernel, const ExpressionGraph& graph, const std::vector<Assignment>& assignments) {
  const PrintedKernel p = print_kernel(graph, assignments);
  return {kernel, p.body, p.operations, ""};
}

void split_speeds(Derivation& d) {
  d.local.assign(d.n(), -1);
  for (int i = 0; i < d.n(); ++i)
    if (!d.vars.prescribed_acceleration.count(i)) {
      d.local[i] = d.ns();
      d.solved.push_back(i);
    }
}

/// `double ap<i> = 0.0;` then the acceleration of the piece in force.
void print_prescribed_accelerations(Derivation& d) {
  for (const kane::PrescribedSpeed& ps : d.eq.prescribed) {
    const std::string a = symbolic::prescribed_acceleration_name(ps.speed);
    std::string& text = d.prescribed.body;
    text += "  double " + a + " = 0.0;  // prescribed acceleration of " + d.eq.speed_names[ps.speed] + "\n";
    for (std::size_t k = 0; k < ps.pieces.size(); ++k) {
      const kane::PrescribedSpeed::Piece& piece = ps.pieces[k];
      const PrintedKernel p =
          print_kernel(d.graph, {{a, d.graph.add(piece.acceleration)}}, "    ", "x" + a + "_" + str(k) + "_");
      d.prescribed.operations += p.operations;
      text += std::string(k == 0 ? "  " : " else ") +
              (piece.has_until ? "if (t < " + format_double(piece.until) + ") " : "") + "{\n" + p.body +
              "  }";
    }
    text += "\n";
  }
}

/// "  udot[i] = ap<i>;" for every prescribed speed.
std::string given_accelerations(const Derivation& d) {
  std::string s;
  for (const kane::PrescribedSpeed& ps : d.eq.prescribed)
    s += "  udot[" + str(ps.speed) + "] = " + symbolic::prescribed_acceleration_name(ps.speed) + ";\n";
  return s;
}

KernelCode set_parameter_kernel(const Derivation& d) {
  std::string body;
  for (const model::Parameter& par : d.model.parameters)
    body += "  if (std::strcmp(name, \"" + par.name + "\") == 0) {\n    p." + par.name +
            " = value;\n    return true;\n  }\n";
  return {Kernel::set_parameter, body + "  return false;\n", 0, ""};
}

KernelCode get_parameter_kernel(const Derivation& d) {
  std::string body = "  switch (i) {\n";
  for (std::size_t i = 0; i < d.model.parameters.size(); ++i)
    body += "    case " + str(static_cast<long>(i)) + ": return p." + d.model.parameters[i].name + ";\n";
  return {Kernel::get_parameter, body + "    default: return 0.0;\n  }\n", 0, ""};
}

KernelCode initial_state_kernel(const Derivation& d) {
  std::vector<Assignment> initial;
  for (const kane::PrescribedSpeed& ps : d.eq.prescribed) {
    initial.push_back({"q[" + str(ps.speed) + "]", d.graph.add(ps.position0)});
    initial.push_back({"u[" + str(ps.speed) + "]", d.graph.add(ps.speed0)});
  }
  return {Kernel::initial_state,
          "  for (int i = 0; i < NQ; ++i) q[i] = q0[i];\n  for (int i = 0; i < NU; ++i) u[i] = u0[i];\n" +
              print_kernel(d.graph, initial).body,
          0, ""};
}

KernelCode mass_matrix_kernel(const Derivation& d) {
  std::vector<Assignment> mass;
  for (int k = 0; k < d.n() * d.n(); ++k)
    mass.push_back({"M[" + str(k) + "]", d.graph.add(d.eq.mass_matrix[k])});
  return printed(Kernel::mass_matrix, d.graph, mass);
}

KernelCode forcing_kernel(const Derivation& d) {
  std::vector<Assignment> force;
  for (int i = 0; i < d.n(); ++i) force.push_back({"f[" + str(i) + "]", d.graph.add(d.eq.forcing[i])});
  return printed(Kernel::forcing, d.graph, force);
}

/// An open tree: M and the right-hand side as locals, then the LDL^T
/// unrolled for the model's structure, the prescribed speeds given.
KernelCode tree_dynamics_kernel(const Derivation& d) {
  std::vector<Assignment> dynamics;
  std::vector<bool> nonzero(static_cast<std::size_t>(d.ns()) * d.ns(), false);
  for (int i = 0; i < d.n(); ++i)
    for (int j = 0; j < d.n(); ++j) {
      const int node = d.graph.add(d.eq.mass_matrix[i * d.n() + j]);
      const int li = d.local[i], lj = d.local[j];
      if (li < 0 || lj < 0 || lj > li) continue;
      const Node& entry = d.graph.node(node);
      nonzero[li * d.ns() + lj] = !(entry.op == Op::number && entry.value == 0.0);
      if (nonzero[li * d.ns() + lj]) dynamics.push_back({"const double m" + str(li) + "_" + str(lj), node});
    }
  for (int i = 0; i < d.n(); ++i) {
    const int node = d.graph.add(d.eq.forcing[i]);
    if (d.local[i] < 0) continue;
    dynamics.push_back({"udot[" + str(i) + "]",
                        d.vars.prescribed_acceleration.empty() ? node : d.graph.add(d.solved_rhs(i))});
  }
  const PrintedKernel body = print_kernel(d.graph, dynamics);
  const UnrolledLdlt solve = unrolled_ldlt(nonzero, d.solved);
  return {Kernel::forward_dynamics,
          d.prescribed.body + body.body + solve.text + given_accelerations(d) + "  return 0;\n",
          body.operations + solve.operations + d.prescribed.operations,
          " (" + str(solve.operations) + " of them in LDL^T)"};
}

KernelCode constraints_kernel(const Derivation& d) {
  std::vector<Assignment> phi;
  for (int c = 0; c < d.eq.loops.size(); ++c)
    phi.push_back({"phi[" + str(c) + "]", d.graph.add(d.eq.loops.phi[c])});
  return printed(Kernel::constraints, d.graph, phi);
}

KernelCode constraint_jacobian_kernel(const Derivation& d) {
  std::vector<Assignment> jacobian;
  for (int k = 0; k < d.eq.loops.size() * d.n(); ++k)
    jacobian.push_back({"C[" + str(k) + "]", d.graph.add(d.eq.loops.jacobian[k])});
  return printed(Kernel::constraint_jacobian, d.graph, jacobian);
}

KernelCode constraint_bias_kernel(const Derivation& d) {
  std::vector<Assignment> bias;
  for (int c = 0; c < d.eq.loops.size(); ++c)
    bias.push_back({"gamma[" + str(c) + "]", d.graph.add(d.eq.loops.bias[c])});
  return printed(Kernel::constraint_bias, d.graph, bias);
}

/// Closed loops: M, C and the right-hand sides over the solved speeds, then
/// the saddle-point solve (templates/solve_saddle.hpp).
KernelCode constrained_dynamics_kernel(const Derivation& d) {
  const int n = d.n(), ns = d.ns(), nc = d.eq.loops.size();
  std::vector<Assignment> saddle;
  for (int c = 0; c < nc; ++c) {
    GiNaC::ex g = d.eq.loops.bias[c];  // gamma - sum_p C_cp a_p over the prescribed speeds p
    for (int i = 0; i < n; ++i) {
      const GiNaC::ex& entry = d.eq.loops.jacobian[c * n + i];
      if (d.local[i] >= 0)
        saddle.push_back({"Cs[" + str(c * ns + d.local[i]) + "]", d.graph.add(entry)});
      else
        g -= entry * d.vars.prescribed_acceleration.at(i);
    }
    saddle.push_back({"g[" + str(c) + "]", d.graph.add(g)});
  }
  for (int i = 0; i < ns; ++i)
    for (int j = 0; j < ns; ++j)
      saddle.push_back(
          {"Ms[" + str(i * ns + j) + "]", d.graph.add(d.eq.mass_matrix[d.solved[i] * n + d.solved[j]])});
  for (int i = 0; i < ns; ++i)
    saddle.push_back({"b[" + str(i) + "]", d.graph.add(d.solved_rhs(d.solved[i]))});
  const PrintedKernel body = print_kernel(d.graph, saddle);
  std::string unpack;  // the solved accelerations back into udot, the prescribed ones given
  for (int i = 0; i < ns; ++i) unpack += "  udot[" + str(d.solved[i]) + "] = b[" + str(i) + "];\n";
  return {Kernel::constrained_dynamics,
          "  constexpr int NS = " + str(ns) + ";  // speeds solved for (not prescribed)\n" +
              d.prescribed.body + "  double Ms[NS * NS], b[NS], Cs[NC * NS], g[NC];\n" + body.body +
              "  const int status = solve_saddle<NS, NC>(Ms, b, Cs, g, lambda);\n" + unpack +
              given_accelerations(d) + "  return status;\n",
          body.operations + d.prescribed.operations, ""};
}

/// With loops, forward_dynamics is the constrained dynamics without the loop forces.
KernelCode loop_dynamics_kernel(const KernelCode& constrained) {
  return {Kernel::forward_dynamics,
          "  double lambda[NC];\n  return constrained_dynamics(p, t, q, u, tau, udot, lambda);\n",
          constrained.operations, " (and the saddle-point solve)"};
}

KernelCode coordinate_rates_kernel(const Derivation& d) {
  std::vector<Assignment> rates;
  for (int i = 0; i < d.eq.nq; ++i)
    rates.push_back({"qdot[" + str(i) + "]", d.graph.add(d.eq.coordinate_rates[i])});
  return printed(Kernel::coordinate_rates, d.graph, rates);
}

KernelCode energy_kernel(Kernel kernel, const char* variable, const GiNaC::ex& energy,
                         ExpressionGraph& graph) {
  KernelCode code = printed(kernel, graph, {{variable, graph.add(energy)}});
  code.body = "  double " + std::string(variable) + ";\n" + code.body + "  return " + variable + ";\n";
  return code;
}

KernelCode generalized_momentum_kernel(const Derivation& d) {
  std::vector<Assignment> momentum;
  for (int r = 0; r < d.n(); ++r) {
    GiNaC::ex h = 0;
    for (int s = 0; s < d.n(); ++s) h += d.eq.mass_matrix[r * d.n() + s] * d.vars.u[s];
    momentum.push_back({"h[" + str(r) + "]", d.graph.add(h)});
  }
  return printed(Kernel::generalized_momentum, d.graph, momentum);
}

/// The loop forces among the outputs: lambda of the dynamics at zero inputs.
std::string reaction_outputs(const Derivation& d) {
  if (d.eq.reaction_outputs.empty()) return "";
  const std::size_t ntau = d.eq.input_names.size();
  std::string s =
      "  // Loop forces: lambda of the dynamics at these inputs of zero (NaN where it cannot be solved).\n"
      "  double reaction_udot[NU], lambda[NC];\n  const double no_inputs[" +
      str(static_cast<long>(ntau > 0 ? ntau : 1)) +
      "] = {};\n"
      "  const bool solved = constrained_dynamics(p, t, q, u, no_inputs, reaction_udot, lambda) == 0;\n";
  for (const auto& [index, row] : d.eq.reaction_outputs)
    s += "  y[" + str(index) + "] = solved ? lambda[" + str(row) + "] : std::nan(\"\");\n";
  return s;
}

KernelCode outputs_kernel(const Derivation& d) {
  std::vector<Assignment> outputs;
  for (std::size_t i = 0; i < d.eq.outputs.size(); ++i)
    outputs.push_back({"y[" + str(static_cast<long>(i)) + "]", d.graph.add(d.eq.outputs[i])});
  KernelCode code = printed(Kernel::outputs, d.graph, outputs);
  code.body += reaction_outputs(d);
  return code;
}

/// The input node of each symbol (q or u).
std::vector<int> input_nodes(ExpressionGraph& graph, const std::vector<GiNaC::symbol>& symbols) {
  std::vector<int> nodes;
  for (const GiNaC::symbol& s : symbols) nodes.push_back(graph.add(s));
  return nodes;
}

/// The Jacobian d rows / d variables into `target` (row-major): the
/// assignments of the entries that are not zero by structure, and in `fill`
/// a loop that zeroes the array first if any entry is (no code for those).
/// One variable at a time, so that each derivative of a shared node is made
/// once and reused by every row.
std::vector<Assignment> jacobian_entries(ExpressionGraph& graph, const std::vector<int>& rows,
                                         const std::vector<int>& variables, const std::string& target,
                                         const std::string& size, std::string& fill) {
  const std::size_t nv = variables.size();
  std::vector<int> entry(rows.size() * nv, -1);
  for (std::size_t j = 0; j < nv; ++j) {
    GraphDerivative derivative(graph, variables[j]);
    for (std::size_t i = 0; i < rows.size(); ++i) entry[i * nv + j] = derivative.of(rows[i]);
  }
  std::vector<Assignment> out;
  for (std::size_t k = 0; k < entry.size(); ++k)
    if (!is_zero(graph, entry[k])) out.push_back({target + "[" + str(static_cast<long>(k)) + "]", entry[k]});
  if (out.size() < entry.size())
    fill += "  for (int k = 0; k < " + size + "; ++k) " + target + "[k] = 0.0;\n";
  return out;
}

/// df/dq and df/du: stiffness (elastic and geometric), damping, velocity
/// terms, springs and the prescribed coordinates' terms, all through the
/// graph's shared intermediates.
KernelCode forcing_jacobian_kernel(const Derivation& d) {
  std::vector<int> forcing;
  for (int i = 0; i < d.n(); ++i) forcing.push_back(d.graph.add(d.eq.forcing[i]));
  std::string fill;
  std::vector<Assignment> entries =
      jacobian_entries(d.graph, forcing, input_nodes(d.graph, d.vars.q), "dfdq", "NU * NQ", fill);
  const std::vector<Assignment> by_speed =
      jacobian_entries(d.graph, forcing, input_nodes(d.graph, d.vars.u), "dfdu", "NU * NU", fill);
  entries.insert(entries.end(), by_speed.begin(), by_speed.end());
  const PrintedKernel p = print_kernel(d.graph, entries);
  return {Kernel::forcing_jacobian, fill + p.body, p.operations, ""};
}

/// d(M(q) a)/dq: the rows sum_s M_rs a_s, a the kernel's argument.
KernelCode mass_matrix_product_jacobian_kernel(const Derivation& d) {
  std::vector<int> products;
  for (int r = 0; r < d.n(); ++r) {
    std::vector<int> terms;
    for (int s = 0; s < d.n(); ++s)
      terms.push_back(d.graph.product(
          {d.graph.add(d.eq.mass_matrix[r * d.n() + s]), d.graph.input("a[" + str(s) + "]")}));
    products.push_back(d.graph.sum(std::move(terms)));
  }
  std::string fill;
  const std::vector<Assignment> entries =
      jacobian_entries(d.graph, products, input_nodes(d.graph, d.vars.q), "dMa_dq", "NU * NQ", fill);
  const PrintedKernel p = print_kernel(d.graph, entries);
  return {Kernel::mass_matrix_product_jacobian, fill + p.body, p.operations, ""};
}

/// d(C(q)^T lambda)/dq: the rows sum_c C_cr lambda_c, lambda the kernel's argument.
KernelCode constraint_force_jacobian_kernel(const Derivation& d) {
  const int nc = d.eq.loops.size();
  std::vector<int> forces;
  for (int r = 0; r < d.n(); ++r) {
    std::vector<int> terms;
    for (int c = 0; c < nc; ++c)
      terms.push_back(d.graph.product(
          {d.graph.add(d.eq.loops.jacobian[c * d.n() + r]), d.graph.input("lambda[" + str(c) + "]")}));
    forces.push_back(d.graph.sum(std::move(terms)));
  }
  std::string fill;
  const std::vector<Assignment> entries =
      jacobian_entries(d.graph, forces, input_nodes(d.graph, d.vars.q), "dCl_dq", "NU * NQ", fill);
  const PrintedKernel p = print_kernel(d.graph, entries);
  return {Kernel::constraint_force_jacobian, fill + p.body, p.operations, ""};
}

}  // namespace

std::vector<KernelCode> derive_kernels(const model::Model& model, const kane::Equations& eq,
                                       const symbolic::Variables& vars, ExpressionGraph& graph,
                                       bool jacobians) {
  Derivation d{model, eq, vars, graph, {}, {}, {}};
  split_speeds(d);
  print_prescribed_accelerations(d);
  std::vector<KernelCode> kernels{set_parameter_kernel(d), get_parameter_kernel(d), initial_state_kernel(d),
                                  mass_matrix_kernel(d), forcing_kernel(d)};
  const KernelCode constrained = d.loops() ? constrained_dynamics_kernel(d) : KernelCode{};
  kernels.push_back(d.loops() ? loop_dynamics_kernel(constrained) : tree_dynamics_kernel(d));
  kernels.push_back(coordinate_rates_kernel(d));
  kernels.push_back(energy_kernel(Kernel::kinetic_energy, "T", eq.kinetic_energy, graph));
  kernels.push_back(energy_kernel(Kernel::potential_energy, "V", eq.potential_energy, graph));
  kernels.push_back(energy_kernel(Kernel::nonconservative_power, "P", eq.nonconservative_power, graph));
  kernels.push_back(generalized_momentum_kernel(d));
  kernels.push_back(outputs_kernel(d));
  if (d.loops()) {
    kernels.push_back(constraints_kernel(d));
    kernels.push_back(constraint_jacobian_kernel(d));
    kernels.push_back(constraint_bias_kernel(d));
    kernels.push_back(constrained);
  }
  if (jacobians) {
    // d/dq of the kernels is the whole Jacobian only because q_dot = u.
    if (eq.nq != eq.nu) throw std::logic_error("the Jacobian kernels need q_dot = u (nq == nu)");
    kernels.push_back(forcing_jacobian_kernel(d));
    kernels.push_back(mass_matrix_product_jacobian_kernel(d));
    if (d.loops()) kernels.push_back(constraint_force_jacobian_kernel(d));
  }
  return kernels;
}

const KernelCode& find_kernel(const std::vector<KernelCode>& kernels, Kernel kernel) {
  for (const KernelCode& k : kernels)
    if (k.kernel == kernel) return k;
  throw std::logic_error(std::string("kernel not derived: ") + signature(kernel).name);
}

}  // namespace kanegen::codegen
