// SPDX-License-Identifier: GPL-2.0-or-later
#include "codegen/model_kernels.hpp"

#include <map>
#include <optional>
#include <stdexcept>
#include <string>

#include "codegen/cpp_printer.hpp"
#include "codegen/cpp_text.hpp"
#include "codegen/graph_derivative.hpp"
#include "codegen/graph_substitution.hpp"
#include "codegen/kernel_splitter.hpp"
#include "codegen/unrolled_ldlt.hpp"
#include "codegen/unrolled_saddle.hpp"

namespace kanegen::codegen {
namespace {

std::string str(long i) { return std::to_string(i); }

/// What the kernels of one model share: its equations, the graph they are
/// printed from, and which speeds are solved for.
struct Derivation {
  const model::Model& model;
  kane::DerivationContext& eq;
  const symbolic::Variables& vars;
  ExpressionGraph& graph;
  ScalarType scalar;  ///< of the emitted code
  /// The speeds solved for (not prescribed), and each speed's index among
  /// them (-1 for a prescribed one).
  std::vector<int> solved, local;
  /// The given accelerations, piece by piece, as the first statements of the dynamics.
  KernelCode prescribed{Kernel::forward_dynamics, "", 0, ""};
  /// Kernels of more statements are split into functions (kernel_splitter.hpp); 0: never.
  int split_threshold = 0;
  /// forward_dynamics's method on an open tree, and what it was made with.
  DynamicsMethod dynamics = DynamicsMethod::automatic;
  mutable DynamicsChoice chosen{};
  /// constrained_dynamics, derived once where it is first needed
  /// (forward_dynamics with loops calls it and takes its count).
  mutable std::optional<KernelCode> constrained{};

  int n() const { return eq.nu(); }
  int ns() const { return static_cast<int>(solved.size()); }
  bool loops() const { return eq.has_loops(); }
  /// f_i - sum_p M_ip a_p over the prescribed speeds p: the right-hand side of a solved row.
  GiNaC::ex solved_rhs(int i) const {
    GiNaC::ex rhs = eq.forcing()[i];
    for (const auto& [p, a] : vars.prescribed_acceleration) rhs -= eq.mass_matrix()[i * n() + p] * a;
    return rhs;
  }
};

/// The assignments printed, split into functions past the threshold (the
/// count note then says so); `arrays`: the kernel's local arrays that they assign.
KernelCode printed(Kernel kernel, const Derivation& d, const std::vector<Assignment>& assignments,
                   const std::vector<KernelArgument>& arrays = {}) {
  const PrintedKernel p = print_kernel(d.graph, assignments, d.scalar);
  const SplitBody split = split_kernel(p, signature(kernel), d.scalar, d.split_threshold, arrays);
  return {kernel, split.body, p.operations, split.note()};
}

void split_speeds(Derivation& d) {
  d.local.assign(d.n(), -1);
  for (int i = 0; i < d.n(); ++i)
    if (!d.vars.prescribed_acceleration.count(i)) {
      d.local[i] = d.ns();
      d.solved.push_back(i);
    }
}

/// `double ap<i> = 0.0;` (or float) then the acceleration of the piece in force.
void print_prescribed_accelerations(Derivation& d) {
  for (const kane::PrescribedSpeed& ps : d.eq.coordinates().prescribed) {
    const std::string a = symbolic::prescribed_acceleration_name(ps.speed);
    std::string& text = d.prescribed.body;
    text += "  " + std::string(d.scalar.name()) + " " + a + " = " + d.scalar.literal(0.0) +
            ";  // prescribed acceleration of " + cpp_comment_text(d.eq.coordinates().speed_names[ps.speed]) +
            "\n";
    for (std::size_t k = 0; k < ps.pieces.size(); ++k) {
      const kane::PrescribedSpeed::Piece& piece = ps.pieces[k];
      const PrintedKernel p = print_kernel(d.graph, {{a, d.graph.add(piece.acceleration)}}, d.scalar, "    ",
                                           "x" + a + "_" + str(k) + "_");
      d.prescribed.operations += p.operations;
      text += std::string(k == 0 ? "  " : " else ") +
              (piece.has_until ? "if (t < " + d.scalar.literal(piece.until) + ") " : "") + "{\n" + p.body +
              "  }";
    }
    text += "\n";
  }
}

/// "  udot[i] = ap<i>;" for every prescribed speed.
std::string given_accelerations(const Derivation& d) {
  std::string s;
  for (const kane::PrescribedSpeed& ps : d.eq.coordinates().prescribed)
    s += "  udot[" + str(ps.speed) + "] = " + symbolic::prescribed_acceleration_name(ps.speed) + ";\n";
  return s;
}

/// The names compared by a loop of its own rather than strcmp: the kernels
/// need nothing from the C library beyond <math.h> (freestanding targets).
KernelCode set_parameter_kernel(const Derivation& d) {
  std::string body;
  if (!d.model.parameters.empty())
    body +=
        "  const auto is = [name](const char* candidate) {\n"
        "    const char* c = name;\n"
        "    while (*c != '\\0' && *c == *candidate) {\n"
        "      ++c;\n"
        "      ++candidate;\n"
        "    }\n"
        "    return *c == *candidate;\n"
        "  };\n";
  for (const model::Parameter& par : d.model.parameters)
    body += "  if (is(" + cpp_string_literal(par.name) + ")) {\n    p." + cpp_identifier(par.name) +
            " = value;\n    return true;\n  }\n";
  return {Kernel::set_parameter, body + "  return false;\n", 0, ""};
}

KernelCode get_parameter_kernel(const Derivation& d) {
  std::string body = "  switch (i) {\n";
  for (std::size_t i = 0; i < d.model.parameters.size(); ++i)
    body += "    case " + str(static_cast<long>(i)) + ": return p." +
            cpp_identifier(d.model.parameters[i].name) + ";\n";
  return {Kernel::get_parameter, body + "    default: return " + d.scalar.literal(0.0) + ";\n  }\n", 0, ""};
}

KernelCode initial_state_kernel(const Derivation& d) {
  std::vector<Assignment> initial;
  for (const kane::PrescribedSpeed& ps : d.eq.coordinates().prescribed) {
    initial.push_back({"q[" + str(ps.speed) + "]", d.graph.add(ps.position0)});
    initial.push_back({"u[" + str(ps.speed) + "]", d.graph.add(ps.speed0)});
  }
  return {Kernel::initial_state,
          "  for (int i = 0; i < NQ; ++i) q[i] = q0[i];\n  for (int i = 0; i < NU; ++i) u[i] = u0[i];\n" +
              print_kernel(d.graph, initial, d.scalar).body,
          0, ""};
}

bool has_world_mass(const Derivation& d) {
  const kane::WorldMass& w = d.eq.world_mass();
  return static_cast<int>(w.axis.size()) == d.n() && static_cast<int>(w.momentum.size()) == d.n() &&
         !w.pairs.empty();
}

/// M as a loop over the pairs (r, s) of kane::WorldMass: straight-line
/// code for the n axes and momenta, then per pair a product of six. The
/// source grows as n (plus a table of the pairs) where the entries one by
/// one grow as n^2, and so does the compile time; each entry costs 11
/// operations, structural zeros or not.
KernelCode world_mass_loop_kernel(const Derivation& d, long straight_line) {
  const kane::WorldMass& w = d.eq.world_mass();
  std::vector<Assignment> values;
  for (int r = 0; r < d.n(); ++r)
    for (int k = 0; k < 6; ++k) values.push_back({"ax[" + str(6 * r + k) + "]", d.graph.add(w.axis[r][k])});
  for (int s = 0; s < d.n(); ++s)
    for (int k = 0; k < 6; ++k)
      values.push_back({"hm[" + str(6 * s + k) + "]", d.graph.add(w.momentum[s][k])});
  const std::string real = d.scalar.name();
  const KernelCode body = printed(Kernel::mass_matrix, d, values, {{real + "*", "ax"}, {real + "*", "hm"}});
  const long pairs = static_cast<long>(w.pairs.size());
  std::string rows, columns;
  for (const auto& [r, s] : w.pairs) {
    rows += (rows.empty() ? "" : ", ") + str(r);
    columns += (columns.empty() ? "" : ", ") + str(s);
  }
  std::string text =
      "  // M_rs = M_sr = ax_r . hm_s over the pairs (r, s), r on s's path: ax_r the joint's\n"
      "  // partial velocities at the world origin, hm_s the world momentum with u_s = 1.\n";
  text += "  " + real + " ax[NU * 6], hm[NU * 6];\n" + body.body;
  text += "  static const int pair_r[" + str(pairs) + "] = {" + rows + "};\n";
  text += "  static const int pair_s[" + str(pairs) + "] = {" + columns + "};\n";
  text += "  for (int k = 0; k < NU * NU; ++k) M[k] = " + d.scalar.literal(0.0) + ";\n";
  text += "  for (int k = 0; k < " + str(pairs) + "; ++k) {\n";
  text += "    const " + real + "* a = ax + 6 * pair_r[k];\n";
  text += "    const " + real + "* h = hm + 6 * pair_s[k];\n";
  text +=
      "    M[pair_r[k] * NU + pair_s[k]] = M[pair_s[k] * NU + pair_r[k]] =\n"
      "        a[0] * h[0] + a[1] * h[1] + a[2] * h[2] + a[3] * h[3] + a[4] * h[4] + a[5] * h[5];\n"
      "  }\n";
  return {Kernel::mass_matrix, text, body.operations + 11 * pairs,
          " (a loop over " + str(pairs) + " pairs of world axes and momenta; entry by entry: " +
              str(straight_line) + ")" + body.count_note};
}

/// M entry by entry, or, past the split threshold on a rigid tree with the
/// world projection, as a loop over pairs (world_mass_loop_kernel).
KernelCode mass_matrix_kernel(const Derivation& d) {
  std::vector<Assignment> mass;
  for (int k = 0; k < d.n() * d.n(); ++k)
    mass.push_back({"M[" + str(k) + "]", d.graph.add(d.eq.mass_matrix()[k])});
  if (d.split_threshold > 0 && has_world_mass(d)) {
    const long straight_line = count_operations(d.graph, mass);
    if (straight_line > d.split_threshold) return world_mass_loop_kernel(d, straight_line);
  }
  return printed(Kernel::mass_matrix, d, mass);
}

KernelCode forcing_kernel(const Derivation& d) {
  std::vector<Assignment> force;
  for (int i = 0; i < d.n(); ++i) force.push_back({"f[" + str(i) + "]", d.graph.add(d.eq.forcing()[i])});
  return printed(Kernel::forcing, d, force);
}

/// The composite solve's statements before its LDL^T: the lower triangle of
/// M over the solved speeds as locals (`nonzero`: its structure) and the
/// right-hand sides into udot.
struct CompositeParts {
  std::vector<Assignment> assignments;
  std::vector<bool> nonzero;
};

CompositeParts composite_parts(const Derivation& d) {
  CompositeParts parts{{}, std::vector<bool>(static_cast<std::size_t>(d.ns()) * d.ns(), false)};
  for (int i = 0; i < d.n(); ++i)
    for (int j = 0; j < d.n(); ++j) {
      const int node = d.graph.add(d.eq.mass_matrix()[i * d.n() + j]);
      const int li = d.local[i], lj = d.local[j];
      if (li < 0 || lj < 0 || lj > li) continue;
      const Node& entry = d.graph.node(node);
      parts.nonzero[li * d.ns() + lj] = !(entry.op == Op::number && entry.value == 0.0);
      if (parts.nonzero[li * d.ns() + lj])
        parts.assignments.push_back(
            {"const " + std::string(d.scalar.name()) + " m" + str(li) + "_" + str(lj), node});
    }
  for (int i = 0; i < d.n(); ++i) {
    const int node = d.graph.add(d.eq.forcing()[i]);
    if (d.local[i] < 0) continue;
    parts.assignments.push_back({"udot[" + str(i) + "]", d.vars.prescribed_acceleration.empty()
                                                             ? node
                                                             : d.graph.add(d.solved_rhs(i))});
  }
  return parts;
}

/// An open tree: M and the right-hand side as locals, then the LDL^T
/// unrolled for the model's structure, the prescribed speeds given.
KernelCode composite_dynamics_kernel(const Derivation& d) {
  const CompositeParts parts = composite_parts(d);
  const KernelCode body = printed(Kernel::forward_dynamics, d, parts.assignments);
  const UnrolledLdlt solve = unrolled_ldlt(parts.nonzero, d.solved, d.scalar);
  return {Kernel::forward_dynamics,
          d.prescribed.body + body.body + solve.text + given_accelerations(d) + "  return 0;\n",
          body.operations + solve.operations + d.prescribed.operations,
          " (" + str(solve.operations) + " of them in LDL^T)" + body.count_note};
}

/// composite_dynamics_kernel's operation count, without its text.
long composite_dynamics_operations(const Derivation& d) {
  const CompositeParts parts = composite_parts(d);
  return count_operations(d.graph, parts.assignments) + unrolled_ldlt_operations(parts.nonzero, d.solved) +
         d.prescribed.operations;
}

/// The recursion's statements: the pivots, then u_dot.
std::vector<Assignment> recursive_assignments(const Derivation& d) {
  std::vector<Assignment> dynamics;
  const std::string real = "const " + std::string(d.scalar.name()) + " ";
  for (int s : d.eq.recursion().pivot_order)
    dynamics.push_back({real + "pivot" + str(s), d.graph.add(d.eq.recursion().pivots[s])});
  for (int r = 0; r < d.n(); ++r)
    dynamics.push_back({"udot[" + str(r) + "]", d.graph.add(d.eq.recursion().accelerations[r])});
  return dynamics;
}

/// An open rigid tree by the articulated-body recursion: u_dot straight
/// from the graph; a pivot D that is not positive (a joint moving a subtree
/// without mass or inertia about its axis) returns its speed + 1, leaves first.
KernelCode recursive_dynamics_kernel(const Derivation& d) {
  const KernelCode body = printed(Kernel::forward_dynamics, d, recursive_assignments(d));
  std::string checks;
  for (int s : d.eq.recursion().pivot_order)
    checks += "  if (!(pivot" + str(s) + " > " + d.scalar.literal(0.0) + ")) return " + str(s + 1) + ";\n";
  return {Kernel::forward_dynamics,
          "  // Articulated-body recursion; pivot<k>: the subtree's inertia about joint k's axis.\n" +
              body.body + checks + "  return 0;\n",
          body.operations, body.count_note};
}

bool has_recursion(const Derivation& d) {
  return d.eq.recursion().unavailable.empty() &&
         static_cast<int>(d.eq.recursion().accelerations.size()) == d.n();
}

/// An open tree's choice between the recursion and the composite solve, as
/// asked or by operation count, from the counts alone: the header gives both,
/// but only the one chosen is printed, since the loser can be large (the
/// composite's LDL^T grows as n^3).
DynamicsChoice tree_dynamics_choice(const Derivation& d, DynamicsMethod method) {
  DynamicsChoice choice;
  choice.composite_operations = composite_dynamics_operations(d);
  if (!has_recursion(d)) {
    if (method == DynamicsMethod::recursive)
      throw std::logic_error("recursive forward dynamics for a model without the recursion");
    return choice;
  }
  choice.recursive_operations = count_operations(d.graph, recursive_assignments(d));
  choice.recursive =
      method == DynamicsMethod::recursive ||
      (method == DynamicsMethod::automatic && choice.recursive_operations < choice.composite_operations);
  return choice;
}

KernelCode tree_dynamics_kernel(const Derivation& d, DynamicsMethod method, DynamicsChoice& choice) {
  choice = tree_dynamics_choice(d, method);
  if (choice.recursive) {
    KernelCode recursive = recursive_dynamics_kernel(d);
    recursive.count_note = " (recursive; composite inertias and LDL^T: " + str(choice.composite_operations) +
                           ")" + recursive.count_note;
    return recursive;
  }
  KernelCode composite = composite_dynamics_kernel(d);
  if (!has_recursion(d)) return composite;
  // " (N of them in LDL^T)" becomes " (composite inertias, N of them in LDL^T; recursive: R)",
  // a split note after it kept.
  const std::string& note = composite.count_note;
  const std::size_t close = note.find(')');
  composite.count_note = " (composite inertias, " + note.substr(2, close - 2) +
                         "; recursive: " + str(choice.recursive_operations) + note.substr(close);
  return composite;
}

KernelCode constraints_kernel(const Derivation& d) {
  std::vector<Assignment> phi;
  for (int c = 0; c < d.eq.loops().size(); ++c)
    phi.push_back({"phi[" + str(c) + "]", d.graph.add(d.eq.loops().phi[c])});
  return printed(Kernel::constraints, d, phi);
}

KernelCode constraint_jacobian_kernel(const Derivation& d) {
  std::vector<Assignment> jacobian;
  for (int k = 0; k < d.eq.loops().size() * d.n(); ++k)
    jacobian.push_back({"C[" + str(k) + "]", d.graph.add(d.eq.loops().jacobian[k])});
  return printed(Kernel::constraint_jacobian, d, jacobian);
}

KernelCode constraint_bias_kernel(const Derivation& d) {
  std::vector<Assignment> bias;
  for (int c = 0; c < d.eq.loops().size(); ++c)
    bias.push_back({"gamma[" + str(c) + "]", d.graph.add(d.eq.loops().bias[c])});
  return printed(Kernel::constraint_bias, d, bias);
}

/// The saddle-point system over the solved speeds as graph nodes: M (ns*ns),
/// C (nc*ns), b = f - M_p a_p and g = gamma - C_p a_p (p the prescribed speeds).
struct SaddleNodes {
  std::vector<int> m, c, b, g;
};

SaddleNodes saddle_nodes(const Derivation& d) {
  const int n = d.n(), ns = d.ns(), nc = d.eq.loops().size();
  SaddleNodes s;
  for (int r = 0; r < nc; ++r) {
    GiNaC::ex g = d.eq.loops().bias[r];
    for (int i = 0; i < n; ++i) {
      const GiNaC::ex& entry = d.eq.loops().jacobian[r * n + i];
      if (d.local[i] >= 0)
        s.c.push_back(d.graph.add(entry));
      else
        g -= entry * d.vars.prescribed_acceleration.at(i);
    }
    s.g.push_back(d.graph.add(g));
  }
  for (int i = 0; i < ns; ++i)
    for (int j = 0; j < ns; ++j)
      s.m.push_back(d.graph.add(d.eq.mass_matrix()[d.solved[i] * n + d.solved[j]]));
  for (int i = 0; i < ns; ++i) s.b.push_back(d.graph.add(d.solved_rhs(d.solved[i])));
  return s;
}

/// Dense in everything: M, C and the right-hand sides as arrays, then
/// templates/solve_saddle.hpp.
KernelCode dense_constrained_dynamics_kernel(const Derivation& d, const SaddleNodes& nodes) {
  const int ns = d.ns(), nc = d.eq.loops().size();
  std::vector<Assignment> saddle;
  for (int r = 0; r < nc; ++r) {
    for (int i = 0; i < ns; ++i) saddle.push_back({"Cs[" + str(r * ns + i) + "]", nodes.c[r * ns + i]});
    saddle.push_back({"g[" + str(r) + "]", nodes.g[r]});
  }
  for (int k = 0; k < ns * ns; ++k) saddle.push_back({"Ms[" + str(k) + "]", nodes.m[k]});
  for (int i = 0; i < ns; ++i) saddle.push_back({"b[" + str(i) + "]", nodes.b[i]});
  const std::string real = std::string(d.scalar.name()) + "*";
  const KernelCode body = printed(Kernel::constrained_dynamics, d, saddle,
                                  {{real, "Ms"}, {real, "b"}, {real, "Cs"}, {real, "g"}});
  std::string unpack;  // the solved accelerations back into udot, the prescribed ones given
  for (int i = 0; i < ns; ++i) unpack += "  udot[" + str(d.solved[i]) + "] = b[" + str(i) + "];\n";
  return {Kernel::constrained_dynamics,
          "  constexpr int NS = " + str(ns) + ";  // speeds solved for (not prescribed)\n" +
              d.prescribed.body + "  " + d.scalar.name() + " Ms[NS * NS], b[NS], Cs[NC * NS], g[NC];\n" +
              body.body + "  const int status = solve_saddle<NS, NC>(Ms, b, Cs, g, lambda);\n" + unpack +
              given_accelerations(d) + "  return status;\n",
          body.operations + d.prescribed.operations + dense_saddle_operations(ns, nc), body.count_note};
}

/// Sparse: the entries of M and C that are not zero by structure as locals,
/// the right-hand side in elimination order, then the unrolled LDL^T.
KernelCode sparse_constrained_dynamics_kernel(const Derivation& d, const SaddleNodes& nodes,
                                              const SaddleStructure& structure, const std::vector<int>& order,
                                              const UnrolledSaddle& solve) {
  const int ns = d.ns(), nc = d.eq.loops().size();
  std::vector<int> position(order.size());
  for (std::size_t k = 0; k < order.size(); ++k) position[order[k]] = static_cast<int>(k);
  const std::string real = "const " + std::string(d.scalar.name()) + " ";
  std::vector<Assignment> saddle;
  for (int i = 0; i < ns; ++i)
    for (int j = 0; j <= i; ++j)
      if (structure.nonzero_m[i * ns + j])
        saddle.push_back({real + "m" + str(i) + "_" + str(j), nodes.m[i * ns + j]});
  for (int r = 0; r < nc; ++r)
    for (int i = 0; i < ns; ++i)
      if (structure.nonzero_c[r * ns + i])
        saddle.push_back({real + "c" + str(r) + "_" + str(i), nodes.c[r * ns + i]});
  for (int i = 0; i < ns; ++i) saddle.push_back({"z[" + str(position[i]) + "]", nodes.b[i]});
  for (int r = 0; r < nc; ++r) saddle.push_back({"z[" + str(position[ns + r]) + "]", nodes.g[r]});
  const KernelCode body =
      printed(Kernel::constrained_dynamics, d, saddle, {{std::string(d.scalar.name()) + "*", "z"}});
  // udot and lambda out of z, the prescribed accelerations given; z holds
  // -lambda (M udot + C^T z = b), lambda as in M udot = f + C^T lambda.
  std::string unpack;
  for (int i = 0; i < ns; ++i) unpack += "  udot[" + str(d.solved[i]) + "] = z[" + str(position[i]) + "];\n";
  for (int r = 0; r < nc; ++r) unpack += "  lambda[" + str(r) + "] = -z[" + str(position[ns + r]) + "];\n";
  return {Kernel::constrained_dynamics,
          d.prescribed.body + "  " + d.scalar.name() + " z[" + str(ns + nc) +
              "];  // the right-hand side [b; g], then [udot; lambda], in elimination order\n" + body.body +
              solve.text + unpack + given_accelerations(d) + "  return 0;\n",
          body.operations + d.prescribed.operations + solve.operations, body.count_note};
}

/// Closed loops: M, C and the right-hand sides over the solved speeds, then
/// the saddle-point solve, sparse (unrolled for the structure of M and C)
/// or dense (templates/solve_saddle.hpp), whichever counts fewer operations.
KernelCode saddle_dynamics_kernel(const Derivation& d) {
  const int ns = d.ns(), nc = d.eq.loops().size();
  const SaddleNodes nodes = saddle_nodes(d);
  SaddleStructure structure{ns, nc, std::vector<bool>(nodes.m.size()), std::vector<bool>(nodes.c.size())};
  for (std::size_t k = 0; k < nodes.m.size(); ++k) structure.nonzero_m[k] = !is_zero(d.graph, nodes.m[k]);
  for (std::size_t k = 0; k < nodes.c.size(); ++k) structure.nonzero_c[k] = !is_zero(d.graph, nodes.c[k]);
  const std::vector<int> order = saddle_elimination_order(structure);
  const UnrolledSaddle sparse = unrolled_saddle(structure, order, d.scalar);
  const long dense = dense_saddle_operations(ns, nc);
  if (sparse.operations < dense) {
    KernelCode code = sparse_constrained_dynamics_kernel(d, nodes, structure, order, sparse);
    // Solve against solve: the rest of the kernel is the same either way.
    code.count_note = " (" + str(sparse.operations) + " of them in the saddle-point solve, a sparse LDL^T; " +
                      "the dense solve would take " + str(dense) + " in their place)" + code.count_note;
    return code;
  }
  KernelCode code = dense_constrained_dynamics_kernel(d, nodes);
  code.count_note = " (" + str(dense) + " of them in the saddle-point solve, dense; the sparse LDL^T would " +
                    "take " + str(sparse.operations) + " in their place)" + code.count_note;
  return code;
}

KernelCode constrained_dynamics_kernel(const Derivation& d) {
  if (!d.constrained) d.constrained = saddle_dynamics_kernel(d);
  return *d.constrained;
}

/// With loops, forward_dynamics is the constrained dynamics without the loop forces.
KernelCode loop_dynamics_kernel(const Derivation& d) {
  const KernelCode& constrained = constrained_dynamics_kernel(d);
  d.chosen.composite_operations = constrained.operations;
  return {Kernel::forward_dynamics,
          "  " + std::string(d.scalar.name()) +
              " lambda[NC];\n  return constrained_dynamics(p, t, q, u, tau, udot, lambda);\n",
          constrained.operations, constrained.count_note};
}

KernelCode forward_dynamics_kernel(const Derivation& d) {
  return d.loops() ? loop_dynamics_kernel(d) : tree_dynamics_kernel(d, d.dynamics, d.chosen);
}

KernelCode coordinate_rates_kernel(const Derivation& d) {
  std::vector<Assignment> rates;
  for (int i = 0; i < d.eq.nq(); ++i)
    rates.push_back({"qdot[" + str(i) + "]", d.graph.add(d.eq.coordinates().rates[i])});
  return printed(Kernel::coordinate_rates, d, rates);
}

KernelCode energy_kernel(Kernel kernel, const char* variable, const GiNaC::ex& energy, const Derivation& d) {
  KernelCode code = printed(kernel, d, {{variable, d.graph.add(energy)}});
  code.body = "  " + std::string(d.scalar.name()) + " " + std::string(variable) + ";\n" + code.body +
              "  return " + variable + ";\n";
  return code;
}

KernelCode kinetic_energy_kernel(const Derivation& d) {
  return energy_kernel(Kernel::kinetic_energy, "T", d.eq.energies().kinetic, d);
}

KernelCode potential_energy_kernel(const Derivation& d) {
  return energy_kernel(Kernel::potential_energy, "V", d.eq.energies().potential, d);
}

KernelCode nonconservative_power_kernel(const Derivation& d) {
  return energy_kernel(Kernel::nonconservative_power, "P", d.eq.energies().nonconservative_power, d);
}

/// h = M u: on a rigid tree by the recursion (the context's generalized_momentum,
/// O(n)) or from M's entries (O(n^2)), whichever counts fewer operations; the
/// note gives the other's count.
KernelCode generalized_momentum_kernel(const Derivation& d) {
  std::vector<Assignment> from_m, recursive;
  for (int r = 0; r < d.n(); ++r) {
    GiNaC::ex h = 0;
    for (int s = 0; s < d.n(); ++s) h += d.eq.mass_matrix()[r * d.n() + s] * d.vars.u[s];
    const std::string target = "h[" + str(r) + "]";
    from_m.push_back({target, d.graph.add(h)});
    if (!d.eq.generalized_momentum().empty())
      recursive.push_back({target, d.graph.add(d.eq.generalized_momentum()[r])});
  }
  if (recursive.empty()) return printed(Kernel::generalized_momentum, d, from_m);
  const long by_m = count_operations(d.graph, from_m), by_recursion = count_operations(d.graph, recursive);
  const bool by_tree = by_recursion < by_m;
  KernelCode code = printed(Kernel::generalized_momentum, d, by_tree ? recursive : from_m);
  // Not among the header's counts: the choice is said in the body.
  code.body = "  // " + std::string(by_tree ? "Recursive" : "M u") + ": " + str(code.operations) +
              " operations; " + (by_tree ? "M u" : "recursive") + ": " + str(by_tree ? by_m : by_recursion) +
              ".\n" + code.body;
  return code;
}

/// The loop forces among the outputs: lambda of the dynamics at zero inputs.
std::string reaction_outputs(const Derivation& d) {
  if (d.eq.outputs().reactions.empty()) return "";
  const std::size_t ntau = d.eq.coordinates().input_names.size();
  std::string s =
      "  // Loop forces: lambda of the dynamics at these inputs of zero (NaN where it cannot be solved).\n"
      "  " +
      std::string(d.scalar.name()) + " reaction_udot[NU], lambda[NC];\n  const " + d.scalar.name() +
      " no_inputs[" + str(static_cast<long>(ntau > 0 ? ntau : 1)) +
      "] = {};\n"
      "  const bool solved = constrained_dynamics(p, t, q, u, no_inputs, reaction_udot, lambda) == 0;\n";
  for (const auto& [index, row] : d.eq.outputs().reactions)
    s += "  y[" + str(index) + "] = solved ? lambda[" + str(row) + "] : NAN;\n";
  return s;
}

KernelCode outputs_kernel(const Derivation& d) {
  std::vector<Assignment> outputs;
  for (std::size_t i = 0; i < d.eq.outputs().values.size(); ++i)
    outputs.push_back({"y[" + str(static_cast<long>(i)) + "]", d.graph.add(d.eq.outputs().values[i])});
  KernelCode code = printed(Kernel::outputs, d, outputs);
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

/// f with the inputs 0: what the model's own forces give.
GiNaC::ex unforced(const Derivation& d, int r) {
  GiNaC::exmap no_inputs;
  for (const GiNaC::symbol& tau : d.vars.tau) no_inputs[tau] = 0;
  return d.eq.forcing()[r].subs(no_inputs);
}

/// The tree's inverse dynamics is Newton and Euler's recursion: rigid bodies only.
bool has_recursive_inverse_dynamics(const Derivation& d) { return !d.eq.inverse_dynamics().inertial.empty(); }

/// Row r of the recursive inverse dynamics, M udot - f(tau = 0), in q, u and udot.
int inverse_dynamics_row(const Derivation& d, int r) {
  GiNaC::exmap no_inputs;
  for (const GiNaC::symbol& tau : d.vars.tau) no_inputs[tau] = 0;
  return d.graph.add(d.eq.inverse_dynamics().inertial[r].subs(no_inputs));
}

/// Row r of f - M udot on a rigid tree: the generalized inputs f(tau) - f(0)
/// less `inverse_dynamics` (a node of the recursion's row r, M udot - f(0),
/// possibly with u or udot replaced).
int residual_row(const Derivation& d, int r, int inverse_dynamics) {
  return d.graph.sum({d.graph.add(d.eq.forcing()[r] - unforced(d, r)),
                      d.graph.product({d.graph.constant(-1.0), inverse_dynamics})});
}

/// The rows of the recursive inverse dynamics with u = 0 (none of its
/// velocity terms) and udot replaced by `accelerations` (nodes; 0 or a
/// kernel argument).
std::vector<int> inverse_dynamics_at_rest(const Derivation& d, const std::vector<int>& accelerations) {
  std::map<int, int> replaced;
  for (int i = 0; i < d.n(); ++i) {
    replaced[d.graph.add(d.vars.u[i])] = d.graph.constant(0.0);
    replaced[d.graph.add(d.vars.udot[i])] = accelerations[i];
  }
  GraphSubstitution at_rest(d.graph, std::move(replaced));
  std::vector<int> rows;
  for (int r = 0; r < d.n(); ++r) rows.push_back(at_rest.of(inverse_dynamics_row(d, r)));
  return rows;
}

/// df/dq and df/du: stiffness (elastic and geometric), damping, velocity
/// terms, springs and the prescribed coordinates' terms, all through the
/// graph's shared intermediates; on a rigid tree f = (f(tau) - f(0)) -
/// ID(q, u, 0), the recursion's derivatives, O(n^2) (on arm7 9823
/// operations against f's own 10700).
KernelCode forcing_jacobian_kernel(const Derivation& d) {
  std::vector<int> forcing;
  for (int i = 0; i < d.n(); ++i) forcing.push_back(d.graph.add(d.eq.forcing()[i]));
  if (has_recursive_inverse_dynamics(d)) {
    std::map<int, int> no_acceleration;
    for (int i = 0; i < d.n(); ++i) no_acceleration[d.graph.add(d.vars.udot[i])] = d.graph.constant(0.0);
    GraphSubstitution at_rest(d.graph, std::move(no_acceleration));
    for (int r = 0; r < d.n(); ++r) forcing[r] = residual_row(d, r, at_rest.of(inverse_dynamics_row(d, r)));
  }
  std::string fill;
  std::vector<Assignment> entries =
      jacobian_entries(d.graph, forcing, input_nodes(d.graph, d.vars.q), "dfdq", "NU * NQ", fill);
  const std::vector<Assignment> by_speed =
      jacobian_entries(d.graph, forcing, input_nodes(d.graph, d.vars.u), "dfdu", "NU * NU", fill);
  entries.insert(entries.end(), by_speed.begin(), by_speed.end());
  KernelCode code = printed(Kernel::forcing_jacobian, d, entries);
  code.body = fill + code.body;
  return code;
}

/// d(M(q) a)/dq, a the kernel's argument: of the rows sum_s M_rs a_s, or on a
/// rigid tree of M a = ID(q, 0, a) - ID(q, 0, 0) by the recursion (O(n^2)
/// derivatives, where M's entries' grow faster), whichever has fewer
/// operations (on arm7 M's: 1808 against 4233).
KernelCode mass_matrix_product_jacobian_kernel(const Derivation& d) {
  std::vector<int> a, composite;
  for (int s = 0; s < d.n(); ++s) a.push_back(d.graph.input("a[" + str(s) + "]"));
  for (int r = 0; r < d.n(); ++r) {
    std::vector<int> terms;
    for (int s = 0; s < d.n(); ++s)
      terms.push_back(d.graph.product({d.graph.add(d.eq.mass_matrix()[r * d.n() + s]), a[s]}));
    composite.push_back(d.graph.sum(std::move(terms)));
  }
  std::string fill;
  std::vector<Assignment> entries =
      jacobian_entries(d.graph, composite, input_nodes(d.graph, d.vars.q), "dMa_dq", "NU * NQ", fill);
  if (has_recursive_inverse_dynamics(d)) {
    const std::vector<int> with_a = inverse_dynamics_at_rest(d, a),
                           without =
                               inverse_dynamics_at_rest(d, std::vector<int>(d.n(), d.graph.constant(0.0)));
    std::vector<int> recursive;
    for (int r = 0; r < d.n(); ++r)
      recursive.push_back(d.graph.sum({with_a[r], d.graph.product({d.graph.constant(-1.0), without[r]})}));
    std::string recursive_fill;
    std::vector<Assignment> by_recursion = jacobian_entries(
        d.graph, recursive, input_nodes(d.graph, d.vars.q), "dMa_dq", "NU * NQ", recursive_fill);
    if (count_operations(d.graph, by_recursion) < count_operations(d.graph, entries)) {
      entries = std::move(by_recursion);
      fill = std::move(recursive_fill);
    }
  }
  KernelCode code = printed(Kernel::mass_matrix_product_jacobian, d, entries);
  code.body = fill + code.body;
  return code;
}

/// d(C(q)^T lambda)/dq: the rows sum_c C_cr lambda_c, lambda the kernel's argument.
KernelCode constraint_force_jacobian_kernel(const Derivation& d) {
  const int nc = d.eq.loops().size();
  std::vector<int> forces;
  for (int r = 0; r < d.n(); ++r) {
    std::vector<int> terms;
    for (int c = 0; c < nc; ++c)
      terms.push_back(d.graph.product(
          {d.graph.add(d.eq.loops().jacobian[c * d.n() + r]), d.graph.input("lambda[" + str(c) + "]")}));
    forces.push_back(d.graph.sum(std::move(terms)));
  }
  std::string fill;
  const std::vector<Assignment> entries =
      jacobian_entries(d.graph, forces, input_nodes(d.graph, d.vars.q), "dCl_dq", "NU * NQ", fill);
  KernelCode code = printed(Kernel::constraint_force_jacobian, d, entries);
  code.body = fill + code.body;
  return code;
}

/// tau = M udot - f(tau = 0): on a rigid tree Newton and Euler's recursion
/// (the context's inverse_dynamics); M udot - f formed from M and f is
/// counted too, for the header (and is the body with flexible bodies).
KernelCode inverse_dynamics_kernel(const Derivation& d) {
  std::vector<Assignment> recursive, formed;
  for (int r = 0; r < d.n(); ++r) {
    const GiNaC::ex f = unforced(d, r);
    GiNaC::ex m_udot = 0;
    for (int s = 0; s < d.n(); ++s) m_udot += d.eq.mass_matrix()[r * d.n() + s] * d.vars.udot[s];
    const std::string target = "tau[" + str(r) + "]";
    formed.push_back({target, d.graph.add(m_udot - f)});
    if (has_recursive_inverse_dynamics(d)) recursive.push_back({target, inverse_dynamics_row(d, r)});
  }
  if (recursive.empty()) {
    KernelCode from_m = printed(Kernel::inverse_dynamics, d, formed);
    from_m.count_note = " (M udot - f: flexible bodies)" + from_m.count_note;
    return from_m;
  }
  KernelCode code = printed(Kernel::inverse_dynamics, d, recursive);
  code.count_note = " (recursive; M udot - f from M and f: " + str(count_operations(d.graph, formed)) + ")" +
                    code.count_note;
  return code;
}

/// g = dV_gravity/dq: the recursion's on a rigid tree, else the gradient of
/// the gravity potential in the graph (q_dot = u).
KernelCode gravity_kernel(const Derivation& d) {
  std::vector<Assignment> g;
  if (!d.eq.inverse_dynamics().gravity.empty()) {
    for (int r = 0; r < d.n(); ++r)
      g.push_back({"g[" + str(r) + "]", d.graph.add(d.eq.inverse_dynamics().gravity[r])});
    return printed(Kernel::gravity, d, g);
  }
  const int potential = d.graph.add(d.eq.energies().gravity_potential);
  for (int r = 0; r < d.n(); ++r)
    g.push_back({"g[" + str(r) + "]", GraphDerivative(d.graph, d.graph.add(d.vars.q[r])).of(potential)});
  return printed(Kernel::gravity, d, g);
}

/// Entries of M and their derivatives: dm[k][i * n + j] = dM_ij/dq_k.
std::vector<std::vector<int>> mass_matrix_derivatives(const Derivation& d) {
  const int n = d.n();
  std::vector<int> entries;
  for (int k = 0; k < n * n; ++k) entries.push_back(d.graph.add(d.eq.mass_matrix()[k]));
  std::vector<std::vector<int>> dm(n);
  for (int k = 0; k < n; ++k) {
    GraphDerivative derivative(d.graph, d.graph.add(d.vars.q[k]));
    for (int e : entries) dm[k].push_back(derivative.of(e));
  }
  return dm;
}

/// On a rigid tree, C from the recursion: the velocity terms Q(q, u) =
/// sum_jk G_ijk u_j u_k are the part of ID(q, u, 0) even in u (gravity and
/// springs do not depend on u, the dampers' forces are linear in it: odd),
/// so E = ID(q, u, 0) + ID(q, -u, 0) = 2 (Q + G(q)) and C = dQ/du / 2 = dE/du / 4.
/// O(n^2) derivatives of an O(n) recursion; empty where there is none.
std::vector<Assignment> recursive_coriolis_entries(const Derivation& d, std::string& fill) {
  if (!has_recursive_inverse_dynamics(d)) return {};
  ExpressionGraph& graph = d.graph;
  std::map<int, int> at_rest, reversed;
  for (int i = 0; i < d.n(); ++i) {
    const int u = graph.add(d.vars.u[i]), udot = graph.add(d.vars.udot[i]);
    at_rest[udot] = reversed[udot] = graph.constant(0.0);
    reversed[u] = graph.product({graph.constant(-1.0), u});
  }
  GraphSubstitution forward(graph, std::move(at_rest)), backward(graph, std::move(reversed));
  std::vector<int> quarter_even;
  for (int r = 0; r < d.n(); ++r) {
    const int row = inverse_dynamics_row(d, r);
    quarter_even.push_back(
        graph.product({graph.constant(0.25), graph.sum({forward.of(row), backward.of(row)})}));
  }
  return jacobian_entries(graph, quarter_even, input_nodes(graph, d.vars.u), "C", "NU * NU", fill);
}

/// C_ij = sum_k G_ijk u_k with the Christoffel symbols of the first kind
/// G_ijk = (dM_ij/dq_k + dM_ik/dq_j - dM_jk/dq_i) / 2: then Mdot - 2C is
/// skew-symmetric and C u is the velocity terms of Kane's equations; from
/// M's derivatives, or from the recursion (recursive_coriolis_entries) where
/// that has fewer operations.
KernelCode coriolis_matrix_kernel(const Derivation& d) {
  const int n = d.n();
  const std::vector<std::vector<int>> dm = mass_matrix_derivatives(d);
  ExpressionGraph& graph = d.graph;
  const int half = graph.constant(0.5), minus_half = graph.constant(-0.5);
  std::vector<Assignment> entries;
  std::string fill;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      std::vector<int> terms;
      for (int k = 0; k < n; ++k) {
        const int uk = graph.add(d.vars.u[k]);
        for (const auto& [factor, node] :
             {std::pair{half, dm[k][i * n + j]}, std::pair{half, dm[j][i * n + k]},
              std::pair{minus_half, dm[i][j * n + k]}})
          if (!is_zero(graph, node)) terms.push_back(graph.product({factor, node, uk}));
      }
      const int c = graph.sum(std::move(terms));
      if (!is_zero(graph, c)) entries.push_back({"C[" + str(i * n + j) + "]", c});
    }
  if (static_cast<int>(entries.size()) < n * n) fill = "  for (int k = 0; k < NU * NU; ++k) C[k] = 0.0;\n";
  std::string recursive_fill;
  std::vector<Assignment> recursive = recursive_coriolis_entries(d, recursive_fill);
  if (!recursive.empty() && count_operations(graph, recursive) < count_operations(graph, entries)) {
    entries = std::move(recursive);
    fill = std::move(recursive_fill);
  }
  KernelCode code = printed(Kernel::coriolis_matrix, d, entries);
  code.body = fill + code.body;
  return code;
}

/// The outputs of position (independent of u) as nodes; 0 for the others.
std::vector<int> position_outputs(const Derivation& d) {
  std::vector<int> rows;
  for (const GiNaC::ex& y : d.eq.outputs().values) rows.push_back(d.graph.add(y));
  for (const GiNaC::symbol& u : d.vars.u) {
    GraphDerivative derivative(d.graph, d.graph.add(u));
    for (int& row : rows)
      if (!is_zero(d.graph, derivative.of(row))) row = d.graph.constant(0.0);
  }
  return rows;
}

/// J[i][j] = dy_i/dq_j over the outputs of position (row-major nodes).
std::vector<int> output_jacobian_entries(const Derivation& d, const std::vector<int>& rows) {
  const std::size_t n = static_cast<std::size_t>(d.n());
  std::vector<int> entry(rows.size() * n);
  for (std::size_t j = 0; j < n; ++j) {
    GraphDerivative derivative(d.graph, d.graph.add(d.vars.q[j]));
    for (std::size_t i = 0; i < rows.size(); ++i) entry[i * n + j] = derivative.of(rows[i]);
  }
  return entry;
}

KernelCode output_jacobian_kernel(const Derivation& d) {
  const std::vector<int> entry = output_jacobian_entries(d, position_outputs(d));
  std::vector<Assignment> out;
  for (std::size_t k = 0; k < entry.size(); ++k)
    if (!is_zero(d.graph, entry[k])) out.push_back({"J[" + str(static_cast<long>(k)) + "]", entry[k]});
  const std::string fill =
      out.size() < entry.size() ? "  for (int k = 0; k < NY * NU; ++k) J[k] = 0.0;\n" : std::string();
  KernelCode code = printed(Kernel::output_jacobian, d, out);
  code.body = fill + code.body;
  return code;
}

/// Jdot_u = d(J u)/dq u + d(J u)/dt with u held: the directional derivative
/// of the output velocity J u along the motion.
KernelCode output_jacobian_rate_kernel(const Derivation& d) {
  ExpressionGraph& graph = d.graph;
  const std::vector<int> rows = position_outputs(d);
  const std::vector<int> entry = output_jacobian_entries(d, rows);
  const std::size_t n = static_cast<std::size_t>(d.n());
  std::vector<int> velocity(rows.size());
  for (std::size_t i = 0; i < rows.size(); ++i) {
    std::vector<int> terms;
    for (std::size_t j = 0; j < n; ++j)
      if (!is_zero(graph, entry[i * n + j]))
        terms.push_back(graph.product({entry[i * n + j], graph.add(d.vars.u[j])}));
    velocity[i] = graph.sum(std::move(terms));
  }
  std::vector<std::vector<int>> terms(rows.size());
  for (std::size_t k = 0; k < n; ++k) {
    GraphDerivative derivative(graph, graph.add(d.vars.q[k]));
    for (std::size_t i = 0; i < rows.size(); ++i) {
      const int dv = derivative.of(velocity[i]);
      if (!is_zero(graph, dv)) terms[i].push_back(graph.product({dv, graph.add(d.vars.u[k])}));
    }
  }
  GraphDerivative by_time(graph, graph.add(d.vars.t));
  std::vector<Assignment> out;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const int dt = by_time.of(velocity[i]);
    if (!is_zero(graph, dt)) terms[i].push_back(dt);
    out.push_back({"Jdot_u[" + str(static_cast<long>(i)) + "]", graph.sum(std::move(terms[i]))});
  }
  return printed(Kernel::output_jacobian_rate, d, out);
}

/// linearize's end: M = L L^T in place, then A's and B's lower rows (which
/// hold M dudot/dx and M dudot/dtau) solved column by column.
const char* const kLinearizeSolve =
    "  // M = L L^T in place (lower triangle), then each column of the lower rows solved.\n"
    "  for (int j = 0; j < NU; ++j) {\n"
    "    double pivot = M[j * NU + j];\n"
    "    for (int k = 0; k < j; ++k) pivot -= M[j * NU + k] * M[j * NU + k];\n"
    "    if (!(pivot > 0.0)) return j + 1;\n"
    "    M[j * NU + j] = sqrt(pivot);\n"
    "    for (int i = j + 1; i < NU; ++i) {\n"
    "      double s = M[i * NU + j];\n"
    "      for (int k = 0; k < j; ++k) s -= M[i * NU + k] * M[j * NU + k];\n"
    "      M[i * NU + j] = s / M[j * NU + j];\n"
    "    }\n"
    "  }\n"
    "  const auto solve = [&M](double* x, int stride) {\n"
    "    for (int i = 0; i < NU; ++i) {\n"
    "      for (int k = 0; k < i; ++k) x[i * stride] -= M[i * NU + k] * x[k * stride];\n"
    "      x[i * stride] /= M[i * NU + i];\n"
    "    }\n"
    "    for (int i = NU - 1; i >= 0; --i) {\n"
    "      for (int k = i + 1; k < NU; ++k) x[i * stride] -= M[k * NU + i] * x[k * stride];\n"
    "      x[i * stride] /= M[i * NU + i];\n"
    "    }\n"
    "  };\n"
    "  for (int c = 0; c < NX; ++c) solve(A + NU * NX + c, NX);\n"
    "  for (int c = 0; c < NTAU; ++c) solve(B + NU * NTAU + c, NTAU);\n"
    "  return 0;\n";

/// linearize's start: udot by forward_dynamics, M, A and B zeroed but for
/// qdot = u.
const char* const kLinearizeStart =
    "  constexpr int NX = 2 * NU;\n"
    "  double udot[NU], M[NU * NU];\n"
    "  const int status = forward_dynamics(p, t, q, u, tau, udot);\n"
    "  if (status != 0) return status;\n"
    "  mass_matrix(p, q, M);\n"
    "  for (int k = 0; k < NX * NX; ++k) A[k] = 0.0;\n"
    "  for (int k = 0; k < NX * NTAU; ++k) B[k] = 0.0;\n"
    "  for (int i = 0; i < NU; ++i) A[i * NX + NU + i] = 1.0;  // qdot = u\n";

/// Rigid trees: the residual R(q, u, udot, tau) = f(q, u, tau) - M(q) udot is 0
/// along every motion, so M dudot/dx = dR/dx at udot = forward_dynamics; R is
/// the generalized inputs f(tau) - f(0) less the recursive inverse dynamics
/// (M udot - f(0), O(n)), and its derivatives in the graph are O(n^2) (as
/// Pinocchio's ABA derivatives are made from RNEA's), where those of the
/// composite M and f grow with n^3 and more.
std::string recursive_linearize(const Derivation& d) {
  std::vector<int> residual;
  for (int r = 0; r < d.n(); ++r) residual.push_back(residual_row(d, r, inverse_dynamics_row(d, r)));
  std::string fill;
  std::vector<Assignment> entries =
      jacobian_entries(d.graph, residual, input_nodes(d.graph, d.vars.q), "dRdq", "NU * NQ", fill);
  const std::vector<Assignment> by_speed =
      jacobian_entries(d.graph, residual, input_nodes(d.graph, d.vars.u), "dRdu", "NU * NU", fill);
  entries.insert(entries.end(), by_speed.begin(), by_speed.end());
  const bool inputs = !d.vars.tau.empty();
  if (inputs) {
    const std::vector<Assignment> by_input =
        jacobian_entries(d.graph, residual, input_nodes(d.graph, d.vars.tau), "dRdtau", "NU * NTAU", fill);
    entries.insert(entries.end(), by_input.begin(), by_input.end());
  }
  // Split as the other kernels are (chain20: about 100000 operations); the
  // parts read udot and write the derivatives through the locals' pointers.
  std::vector<KernelArgument> locals{{"double*", "udot"}, {"double*", "dRdq"}, {"double*", "dRdu"}};
  if (inputs) locals.push_back({"double*", "dRdtau"});
  const KernelCode derivatives = printed(Kernel::linearize, d, entries, locals);
  std::string text = std::string(kLinearizeStart) + "  double dRdq[NU * NQ], dRdu[NU * NU]" +
                     (inputs ? ", dRdtau[NU * NTAU]" : "") + ";\n" + fill + derivatives.body +
                     "  for (int i = 0; i < NU; ++i)\n"
                     "    for (int j = 0; j < NU; ++j) {\n"
                     "      A[(NU + i) * NX + j] = dRdq[i * NQ + j];\n"
                     "      A[(NU + i) * NX + NU + j] = dRdu[i * NU + j];\n"
                     "    }\n";
  if (inputs)
    text +=
        "  for (int i = 0; i < NU; ++i)\n"
        "    for (int j = 0; j < NTAU; ++j) B[(NU + i) * NTAU + j] = dRdtau[i * NTAU + j];\n";
  return text + kLinearizeSolve;
}

/// x = (q, u), xdot = (u, udot): A = [0 I; dudot/dq dudot/du], B = [0; dudot/dtau]
/// from M dudot/dq = df/dq - d(M a)/dq (a = udot), M dudot/du = df/du and
/// M dudot/dtau = df/dtau, solved by a Cholesky factor of M; on a rigid tree
/// from the recursive inverse dynamics (recursive_linearize), otherwise
/// df/dtau is derived here and the rest are the Jacobian kernels.
KernelCode linearize_kernel(const Derivation& d) {
  if (has_recursive_inverse_dynamics(d)) return {Kernel::linearize, recursive_linearize(d), 0, ""};
  std::string text = std::string(kLinearizeStart) +
                     "  double dfdq[NU * NQ], dfdu[NU * NU], dMa_dq[NU * NQ];\n"
                     "  forcing_jacobian(p, t, q, u, tau, dfdq, dfdu);\n"
                     "  mass_matrix_product_jacobian(p, q, udot, dMa_dq);\n"
                     "  for (int i = 0; i < NU; ++i)\n"
                     "    for (int j = 0; j < NU; ++j) {\n"
                     "      A[(NU + i) * NX + j] = dfdq[i * NQ + j] - dMa_dq[i * NQ + j];\n"
                     "      A[(NU + i) * NX + NU + j] = dfdu[i * NU + j];\n"
                     "    }\n";
  if (!d.vars.tau.empty()) {
    std::vector<int> forcing;
    for (int i = 0; i < d.n(); ++i) forcing.push_back(d.graph.add(d.eq.forcing()[i]));
    std::string fill;
    const std::vector<Assignment> by_input =
        jacobian_entries(d.graph, forcing, input_nodes(d.graph, d.vars.tau), "dfdtau", "NU * NTAU", fill);
    const PrintedKernel p = print_kernel(d.graph, by_input, d.scalar);
    text += "  double dfdtau[NU * NTAU];\n" + fill + p.body +
            "  for (int i = 0; i < NU; ++i)\n"
            "    for (int j = 0; j < NTAU; ++j) B[(NU + i) * NTAU + j] = dfdtau[i * NTAU + j];\n";
  }
  return {Kernel::linearize, text + kLinearizeSolve, 0, ""};
}

/// Each kernel's derivation, registered by its spec line: the function
/// <name>_kernel, in Kernel order (a kernel of kernels.def without one is a
/// compile error here).
using Derive = KernelCode (*)(const Derivation&);
const Derive kDerive[] = {
#define KANEGEN_KERNEL(name, ...) &name##_kernel,
#include "kanegen/runtime/kernels.def"
#undef KANEGEN_KERNEL
};
static_assert(sizeof(kDerive) / sizeof(Derive) == runtime::kernel_count, "one derivation per kernel");

/// What the kernels of this kind of model need: q_dot = u for the Jacobians
/// (d/dq of a kernel is its whole Jacobian only then), and for the
/// controller kernels the Jacobians (linearize calls them), no loops and no
/// prescribed speeds (the pipeline refuses those).
void check_options(const Derivation& d, bool jacobians, bool controller) {
  if (jacobians && d.eq.nq() != d.eq.nu())
    throw std::logic_error("the Jacobian kernels need q_dot = u (nq == nu)");
  if (controller && (!jacobians || d.loops() || !d.eq.coordinates().prescribed.empty()))
    throw std::logic_error("the controller kernels need the Jacobians, no loops and no prescribed speeds");
}

}  // namespace

std::vector<KernelCode> derive_kernels(kane::DerivationContext& products, ExpressionGraph& graph,
                                       bool jacobians, bool controller, const ScalarType& scalar,
                                       DynamicsMethod dynamics, DynamicsChoice* choice, int split_threshold) {
  Derivation d{products.model(), products, products.variables(), graph, scalar, {}, {}, {}, split_threshold};
  d.dynamics = dynamics;
  check_options(d, jacobians, controller);
  split_speeds(d);
  print_prescribed_accelerations(d);
  // Which kernels the model has is the spec's presence rule, decided here only.
  std::vector<KernelCode> kernels;
  for (const KernelSignature& s : kernel_table())
    if (present(s.presence, d.loops(), jacobians, controller))
      kernels.push_back(kDerive[static_cast<std::size_t>(s.kernel)](d));
  if (choice) *choice = d.chosen;
  return kernels;
}

long composite_operations(kane::DerivationContext& products, ExpressionGraph& graph,
                          const ScalarType& scalar) {
  Derivation d{products.model(), products, products.variables(), graph, scalar, {}, {}, {}};
  split_speeds(d);
  print_prescribed_accelerations(d);
  return d.loops() ? constrained_dynamics_kernel(d).operations : composite_dynamics_operations(d);
}

const KernelCode& find_kernel(const std::vector<KernelCode>& kernels, Kernel kernel) {
  for (const KernelCode& k : kernels)
    if (k.kernel == kernel) return k;
  throw std::logic_error(std::string("kernel not derived: ") + signature(kernel).name);
}

}  // namespace kanegen::codegen
