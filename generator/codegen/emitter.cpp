// SPDX-License-Identifier: GPL-2.0-or-later
#include "codegen/emitter.hpp"

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <vector>

#include "codegen/cpp_printer.hpp"
#include "codegen/expression_graph.hpp"

namespace kanegen::embedded {
extern const char* const model_hpp_template;
extern const char* const model_cpp_template;
extern const char* const runner_cpp_template;
}  // namespace kanegen::embedded

namespace kanegen::codegen {
namespace {

std::string quoted_list(const std::vector<std::string>& names) {
  std::string s;
  for (const std::string& n : names) {
    std::string escaped;  // URDF names may hold any character
    for (char c : n) escaped += (c == '"' || c == '\\') ? std::string("\\") + c : std::string(1, c);
    s += (s.empty() ? "\"" : ", \"") + escaped + "\"";
  }
  return s;
}

std::string number_list(const std::vector<double>& values) {
  std::string s;
  for (double v : values) s += (s.empty() ? "" : ", ") + format_double(v);
  return s.empty() ? "0.0" : s;
}

std::string array_size(std::size_t n) { return std::to_string(n > 0 ? n : 1); }

struct KernelText {
  std::string body;
  long operations;
};

/// M udot = f solved by an LDL^T unrolled for this model, over the speeds
/// `solved` (those not prescribed): the entries of M are locals m<i>_<j>
/// (i, j indices into `solved`), udot holds the right-hand side on entry;
/// entries that are zero by the tree's structure (and do not fill in) are
/// left out.
KernelText unrolled_ldlt(const std::vector<bool>& nonzero_m, const std::vector<int>& solved) {
  const int n = static_cast<int>(solved.size());
  auto u = [&](int i) { return "udot[" + std::to_string(solved[i]) + "]"; };
  std::vector<bool> nz(nonzero_m);  // structure of L, lower triangle, row-major
  auto m = [](int i, int j) { return "m" + std::to_string(i) + "_" + std::to_string(j); };
  auto l = [](int i, int j) { return "l" + std::to_string(i) + "_" + std::to_string(j); };
  auto d = [](int j) { return "d" + std::to_string(j); };
  auto ld = [](int j, int k) { return "ld" + std::to_string(j) + "_" + std::to_string(k); };
  std::string s = "  // LDL^T of M, unrolled; d<j> are the pivots.\n";
  long ops = 0;
  for (int j = 0; j < n; ++j) {
    std::string pivot = m(j, j);
    for (int k = 0; k < j; ++k)
      if (nz[j * n + k]) {
        s += "  const double " + ld(j, k) + " = " + l(j, k) + "*" + d(k) + ";\n";
        pivot += " - " + l(j, k) + "*" + ld(j, k);
        ops += 3;
      }
    s += "  const double " + d(j) + " = " + pivot + ";\n";
    s += "  if (!(" + d(j) + " > 0.0)) return " + std::to_string(j + 1) + ";\n";
    s += "  const double inv_" + d(j) + " = 1.0/" + d(j) + ";\n";
    ops += 1;
    for (int i = j + 1; i < n; ++i) {
      std::string entry = nonzero_m[i * n + j] ? m(i, j) : "";
      for (int k = 0; k < j; ++k)
        if (nz[i * n + k] && nz[j * n + k]) {
          entry += (entry.empty() ? "-" : " - ") + l(i, k) + "*" + ld(j, k);
          ops += 2;
        }
      if (entry.empty()) continue;
      nz[i * n + j] = true;
      s += "  const double " + l(i, j) + " = (" + entry + ")*inv_" + d(j) + ";\n";
      ops += 1;
    }
  }
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < i; ++k)
      if (nz[i * n + k]) {
        s += "  " + u(i) + " -= " + l(i, k) + "*" + u(k) + ";\n";
        ops += 2;
      }
  for (int i = 0; i < n; ++i) s += "  " + u(i) + " *= inv_" + d(i) + ";\n";
  ops += n;
  for (int i = n - 1; i >= 0; --i)
    for (int k = i + 1; k < n; ++k)
      if (nz[k * n + i]) {
        s += "  " + u(i) + " -= " + l(k, i) + "*" + u(k) + ";\n";
        ops += 2;
      }
  return {s, ops};
}

KernelText kernel(const ExpressionGraph& graph, const std::vector<Assignment>& assignments) {
  const PrintedKernel printed = print_kernel(graph, assignments);
  return {printed.body, printed.operations};
}

// The saddle-point solve of a model with closed loops, by the range-space
// method: M = L L^T (Cholesky), Y = L^-1 C^T, S = Y^T Y = C M^-1 C^T,
// S lambda = g - Y^T L^-1 b, then udot = L^-T (L^-1 b + Y lambda). Where
// loop equations become dependent (a parallelogram's cranks in line, a dead
// point, or a loop that repeats a constraint) S loses rank; that is
// reported, not smoothed over: near such a point the loop forces grow
// without bound and the motion may leave its branch. Loops over the fixed
// sizes, no allocation.
const char* const kSaddleSolver = R"(namespace {

constexpr int NS = {{NS}};  // speeds solved for (not prescribed)

// M: NS*NS (overwritten by L), b: NS (the right-hand side; udot on return),
// C: NC*NS (overwritten by Y^T), g: NC. Returns 0, k > 0 for a non-positive
// k-th pivot of M, -k when the k-th loop equation is (nearly) a combination
// of the earlier ones.
int solve_saddle(double* M, double* b, double* C, const double* g, double* lambda) {
  for (int j = 0; j < NS; ++j) {
    double s = M[j * NS + j];
    for (int k = 0; k < j; ++k) s -= M[j * NS + k] * M[j * NS + k];
    if (!(s > 0.0)) return j + 1;
    const double l = std::sqrt(s);
    M[j * NS + j] = l;
    for (int i = j + 1; i < NS; ++i) {
      double v = M[i * NS + j];
      for (int k = 0; k < j; ++k) v -= M[i * NS + k] * M[j * NS + k];
      M[i * NS + j] = v / l;
    }
  }
  const auto forward = [M](double* x) {
    for (int i = 0; i < NS; ++i) {
      for (int k = 0; k < i; ++k) x[i] -= M[i * NS + k] * x[k];
      x[i] /= M[i * NS + i];
    }
  };
  forward(b);
  for (int c = 0; c < NC; ++c) forward(C + c * NS);
  double S[NC * NC];
  for (int c = 0; c < NC; ++c) {
    lambda[c] = g[c];
    for (int i = 0; i < NS; ++i) lambda[c] -= C[c * NS + i] * b[i];
    for (int d = 0; d <= c; ++d) {
      double v = 0.0;
      for (int i = 0; i < NS; ++i) v += C[c * NS + i] * C[d * NS + i];
      S[c * NC + d] = v;
    }
  }
  // A pivot small against the largest diagonal entry: a row that is
  // (nearly) a combination of the others, or one whose Jacobian vanishes
  // (a parallelogram's cranks in line).
  double largest = 0.0;
  for (int j = 0; j < NC; ++j)
    if (S[j * NC + j] > largest) largest = S[j * NC + j];
  for (int j = 0; j < NC; ++j) {
    double s = S[j * NC + j];
    for (int k = 0; k < j; ++k) s -= S[j * NC + k] * S[j * NC + k];
    if (!(s > 1e-6 * largest)) return -(j + 1);
    const double l = std::sqrt(s);
    S[j * NC + j] = l;
    for (int i = j + 1; i < NC; ++i) {
      double v = S[i * NC + j];
      for (int k = 0; k < j; ++k) v -= S[i * NC + k] * S[j * NC + k];
      S[i * NC + j] = v / l;
    }
  }
  for (int i = 0; i < NC; ++i) {
    for (int k = 0; k < i; ++k) lambda[i] -= S[i * NC + k] * lambda[k];
    lambda[i] /= S[i * NC + i];
  }
  for (int i = NC - 1; i >= 0; --i) {
    for (int k = i + 1; k < NC; ++k) lambda[i] -= S[k * NC + i] * lambda[k];
    lambda[i] /= S[i * NC + i];
  }
  for (int i = 0; i < NS; ++i)
    for (int c = 0; c < NC; ++c) b[i] += C[c * NS + i] * lambda[c];
  for (int i = NS - 1; i >= 0; --i) {
    for (int k = i + 1; k < NS; ++k) b[i] -= M[k * NS + i] * b[k];
    b[i] /= M[i * NS + i];
  }
  return 0;
}

}  // namespace

)";

const char* const kConstraintDeclarations = R"(constexpr int NC = {{NC}};  ///< loop-closure equations

extern const char* const constraint_names[NC];
/// Per coordinate: 0 free, 1 an independent coordinate chosen in the model
/// (assembly keeps it), 2 prescribed.
extern const int coordinate_roles[{{NQ_ARRAY}}];

/// phi: NC, the loop-closure residuals Phi(q) (position rows in m; the hinge
/// alignment rows of a spatial revolute are cosines).
void constraints(const Params& p, const double* q, double* phi);
/// C: NC*NU, row-major, the Jacobian dPhi/dq (q_dot = u).
void constraint_jacobian(const Params& p, const double* q, double* C);
/// gamma: NC, the acceleration level C udot = gamma = -(dC/dt) u.
void constraint_bias(const Params& p, const double* q, const double* u, double* gamma);
/// udot: NU and lambda: NC from M udot = f + C^T lambda, C udot = gamma, the
/// prescribed speeds taking their given acceleration. lambda are the loop
/// forces (see constraint_names). Returns 0; k > 0 when the k-th pivot of M
/// is not positive; -k when the loop equations are dependent at q (a
/// singular configuration: the k-th pivot of C M^-1 C^T vanished).
int constrained_dynamics(const Params& p, double t, const double* q, const double* u, const double* tau,
                         double* udot, double* lambda);

)";

const char* const kConstraintSystem = R"(  static constexpr int nc = NC;
  static const char* const* constraint_names() { return ::kanegen_models::{{MODEL_NAME}}::constraint_names; }
  static const int* coordinate_roles() { return ::kanegen_models::{{MODEL_NAME}}::coordinate_roles; }
  static void constraints(const Params& p, const double* q, double* phi) {
    ::kanegen_models::{{MODEL_NAME}}::constraints(p, q, phi);
  }
  static void constraint_jacobian(const Params& p, const double* q, double* C) {
    ::kanegen_models::{{MODEL_NAME}}::constraint_jacobian(p, q, C);
  }
  static void constraint_bias(const Params& p, const double* q, const double* u, double* gamma) {
    ::kanegen_models::{{MODEL_NAME}}::constraint_bias(p, q, u, gamma);
  }
  static int constrained_dynamics(const Params& p, double t, const double* q, const double* u, const double* tau,
                                  double* udot, double* lambda) {
    return ::kanegen_models::{{MODEL_NAME}}::constrained_dynamics(p, t, q, u, tau, udot, lambda);
  }
)";

}  // namespace

std::string fill_template(const std::string& text, const std::map<std::string, std::string>& values) {
  std::string out;
  std::size_t pos = 0;
  while (true) {
    const std::size_t open = text.find("{{", pos);
    // "{{{X}}}" is a brace followed by the key {{X}}.
    std::size_t start = open;
    while (start != std::string::npos && start + 2 < text.size() && text[start + 2] == '{') ++start;
    if (start == std::string::npos) break;
    const std::size_t close = text.find("}}", start);
    if (close == std::string::npos) break;
    const std::string key = text.substr(start + 2, close - start - 2);
    auto it = values.find(key);
    if (it == values.end()) throw std::logic_error("template key without a value: " + key);
    out += text.substr(pos, start - pos) + it->second;
    pos = close + 2;
  }
  return out + text.substr(pos);
}

EmittedModel emit_model(const model::Model& model, const kane::Equations& eq, const symbolic::Variables& vars,
                        const symbolic::Program& program, const std::string& model_hash) {
  ExpressionGraph graph(vars, program);
  const int n = eq.nu;
  std::vector<Assignment> mass, force, dynamics, rates, outputs;
  // Prescribed speeds get their given acceleration; the others are solved for.
  std::vector<int> solved, local(n, -1);
  for (int i = 0; i < n; ++i)
    if (!vars.prescribed_acceleration.count(i)) {
      local[i] = static_cast<int>(solved.size());
      solved.push_back(i);
    }
  const int ns = static_cast<int>(solved.size());
  std::vector<bool> nonzero_m(static_cast<std::size_t>(ns) * ns, false);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const std::string index = std::to_string(i * n + j);
      const int node = graph.add(eq.mass_matrix[i * n + j]);
      mass.push_back({"M[" + index + "]", node});
      const int li = local[i], lj = local[j];
      if (li >= 0 && lj >= 0 && lj <= li) {
        const Node& entry = graph.node(node);
        nonzero_m[li * ns + lj] = !(entry.op == Op::number && entry.value == 0.0);
        if (nonzero_m[li * ns + lj])
          dynamics.push_back({"const double m" + std::to_string(li) + "_" + std::to_string(lj), node});
      }
    }
  for (int i = 0; i < n; ++i) {
    const int node = graph.add(eq.forcing[i]);
    force.push_back({"f[" + std::to_string(i) + "]", node});
    if (local[i] < 0) continue;
    GiNaC::ex rhs = eq.forcing[i];  // f_i - sum_p M_ip a_p over the prescribed speeds p
    for (const auto& [p, a] : vars.prescribed_acceleration) rhs -= eq.mass_matrix[i * n + p] * a;
    dynamics.push_back({"udot[" + std::to_string(i) + "]", vars.prescribed_acceleration.empty() ? node : graph.add(rhs)});
  }
  // The given accelerations, piece by piece, before everything else.
  std::string prescribed_text;
  long prescribed_operations = 0;
  for (const kane::PrescribedSpeed& ps : eq.prescribed) {
    const std::string a = "ap" + std::to_string(ps.speed);
    prescribed_text += "  double " + a + " = 0.0;  // prescribed acceleration of " + eq.speed_names[ps.speed] + "\n";
    for (std::size_t k = 0; k < ps.pieces.size(); ++k) {
      const kane::PrescribedSpeed::Piece& piece = ps.pieces[k];
      const PrintedKernel printed =
          print_kernel(graph, {{a, graph.add(piece.acceleration)}}, "    ", "x" + a + "_" + std::to_string(k) + "_");
      prescribed_operations += printed.operations;
      prescribed_text += std::string(k == 0 ? "  " : " else ") +
                         (piece.has_until ? "if (t < " + format_double(piece.until) + ") " : "") + "{\n" +
                         printed.body + "  }";
    }
    prescribed_text += "\n";
  }
  for (int i = 0; i < eq.nq; ++i) rates.push_back({"qdot[" + std::to_string(i) + "]", graph.add(eq.coordinate_rates[i])});
  for (std::size_t i = 0; i < eq.outputs.size(); ++i)
    outputs.push_back({"y[" + std::to_string(i) + "]", graph.add(eq.outputs[i])});

  std::map<std::string, KernelText> kernels{
      {"mass_matrix", kernel(graph, mass)},
      {"forcing", kernel(graph, force)},
      {"forward_dynamics", kernel(graph, dynamics)},
      {"coordinate_rates", kernel(graph, rates)},
      {"kinetic_energy", kernel(graph, {{"T", graph.add(eq.kinetic_energy)}})},
      {"potential_energy", kernel(graph, {{"V", graph.add(eq.potential_energy)}})},
      {"outputs", kernel(graph, outputs)},
  };
  std::vector<Assignment> initial;
  for (const kane::PrescribedSpeed& ps : eq.prescribed) {
    initial.push_back({"q[" + std::to_string(ps.speed) + "]", graph.add(ps.position0)});
    initial.push_back({"u[" + std::to_string(ps.speed) + "]", graph.add(ps.speed0)});
  }
  const std::string initial_text = kernel(graph, initial).body;
  KernelText solve = unrolled_ldlt(nonzero_m, solved);
  for (const kane::PrescribedSpeed& ps : eq.prescribed)
    solve.body += "  udot[" + std::to_string(ps.speed) + "] = ap" + std::to_string(ps.speed) + ";\n";
  const long ldlt = solve.operations;
  kernels["forward_dynamics"].operations += ldlt + prescribed_operations;
  kernels["forward_dynamics"].body = prescribed_text + kernels["forward_dynamics"].body;

  // Closed loops: the constraint kernels and the saddle-point dynamics.
  const int nc = eq.loops.size();
  std::string dynamics_return = "  return 0;\n", constraint_declarations, constraint_system,
              constraint_definitions, reaction_text;
  if (nc > 0) {
    std::vector<Assignment> phi, jac, bias, saddle;
    for (int c = 0; c < nc; ++c) {
      phi.push_back({"phi[" + std::to_string(c) + "]", graph.add(eq.loops.phi[c])});
      bias.push_back({"gamma[" + std::to_string(c) + "]", graph.add(eq.loops.bias[c])});
      GiNaC::ex g = eq.loops.bias[c];  // gamma - sum_p C_cp a_p over the prescribed speeds p
      for (int i = 0; i < n; ++i) {
        const GiNaC::ex& entry = eq.loops.jacobian[c * n + i];
        jac.push_back({"C[" + std::to_string(c * n + i) + "]", graph.add(entry)});
        if (local[i] >= 0)
          saddle.push_back({"Cs[" + std::to_string(c * ns + local[i]) + "]", graph.add(entry)});
        else
          g -= entry * vars.prescribed_acceleration.at(i);
      }
      saddle.push_back({"g[" + std::to_string(c) + "]", graph.add(g)});
    }
    // M over the solved speeds, and the right-hand side f - M_p a_p.
    for (int i = 0; i < ns; ++i)
      for (int j = 0; j < ns; ++j)
        saddle.push_back(
            {"Ms[" + std::to_string(i * ns + j) + "]", graph.add(eq.mass_matrix[solved[i] * n + solved[j]])});
    for (int i = 0; i < ns; ++i) {
      GiNaC::ex rhs = eq.forcing[solved[i]];
      for (const auto& [pi, a] : vars.prescribed_acceleration) rhs -= eq.mass_matrix[solved[i] * n + pi] * a;
      saddle.push_back({"b[" + std::to_string(i) + "]", graph.add(rhs)});
    }
    kernels["constraints"] = kernel(graph, phi);
    kernels["constraint_jacobian"] = kernel(graph, jac);
    kernels["constraint_bias"] = kernel(graph, bias);
    const KernelText body = kernel(graph, saddle);
    kernels["constrained_dynamics"] = {body.body, body.operations + prescribed_operations};
    std::map<std::string, std::string> sizes{{"NS", std::to_string(ns)},
                                             {"NC", std::to_string(nc)},
                                             {"NQ_ARRAY", array_size(eq.nq)},
                                             {"MODEL_NAME", model.name}};
    constraint_declarations = fill_template(kConstraintDeclarations, sizes);
    constraint_system = fill_template(kConstraintSystem, sizes);
    std::vector<std::string> roles;
    for (int role : eq.coordinate_role) roles.push_back(std::to_string(role));
    std::string roles_text;
    for (const std::string& r : roles) roles_text += (roles_text.empty() ? "" : ", ") + r;
    std::string unpack;  // the solved accelerations back into udot, the prescribed ones given
    for (int i = 0; i < ns; ++i)
      unpack += "  udot[" + std::to_string(solved[i]) + "] = b[" + std::to_string(i) + "];\n";
    for (const kane::PrescribedSpeed& ps : eq.prescribed)
      unpack += "  udot[" + std::to_string(ps.speed) + "] = ap" + std::to_string(ps.speed) + ";\n";
    constraint_definitions =
        "\nconst char* const constraint_names[NC] = {" + quoted_list(eq.loops.names) + "};\n" +
        "const int coordinate_roles[" + array_size(eq.nq) + "] = {" + roles_text + "};\n\n" +
        "void constraints(const Params& p, const double* q, double* phi) {\n  (void)p;\n  (void)q;\n" +
        kernels["constraints"].body + "}\n\n" +
        "void constraint_jacobian(const Params& p, const double* q, double* C) {\n  (void)p;\n  (void)q;\n" +
        kernels["constraint_jacobian"].body + "}\n\n" +
        "void constraint_bias(const Params& p, const double* q, const double* u, double* gamma) {\n"
        "  (void)p;\n  (void)q;\n  (void)u;\n" +
        kernels["constraint_bias"].body + "}\n\n" + fill_template(kSaddleSolver, sizes) +
        "int constrained_dynamics(const Params& p, double t, const double* q, const double* u, const double* "
        "tau,\n"
        "                         double* udot, double* lambda) {\n"
        "  (void)p;\n  (void)t;\n  (void)q;\n  (void)u;\n  (void)tau;\n" +
        prescribed_text + "  double Ms[NS * NS], b[NS], Cs[NC * NS], g[NC];\n" + body.body +
        "  const int status = solve_saddle(Ms, b, Cs, g, lambda);\n" + unpack + "  return status;\n}\n";
    kernels["forward_dynamics"] = {
        "  double lambda[NC];\n  return constrained_dynamics(p, t, q, u, tau, udot, lambda);\n",
        kernels["constrained_dynamics"].operations};
    solve = {"", 0};
    dynamics_return.clear();
    if (!eq.reaction_outputs.empty()) {
      reaction_text =
          "  // Loop forces: lambda of the dynamics at these inputs of zero (NaN where it cannot be "
          "solved).\n"
          "  double reaction_udot[NU], lambda[NC];\n  const double no_inputs[" +
          array_size(eq.input_names.size()) + "] = {};\n" +
          "  const bool solved = constrained_dynamics(p, t, q, u, no_inputs, reaction_udot, lambda) == 0;\n";
      for (const auto& [index, row] : eq.reaction_outputs)
        reaction_text += "  y[" + std::to_string(index) + "] = solved ? lambda[" + std::to_string(row) +
                         "] : std::nan(\"\");\n";
    }
  }

  EmittedModel emitted;
  std::string counts;
  std::vector<std::string> counted{"mass_matrix",    "forcing",          "forward_dynamics",
                                   "kinetic_energy", "potential_energy", "outputs"};
  if (nc > 0) counted.insert(counted.end(), {"constraints", "constraint_jacobian", "constraint_bias"});
  for (const std::string& name : counted) {
    emitted.operations[name] = kernels[name].operations;
    counts += "//   " + name + ": " + std::to_string(kernels[name].operations) +
              (name == "forward_dynamics" && nc == 0 ? " (" + std::to_string(ldlt) + " of them in LDL^T)"
               : name == "forward_dynamics"          ? " (and the saddle-point solve)"
                                                     : "") +
              "\n";
  }

  std::vector<std::string> param_names, output_names = eq.output_names;
  std::string fields, setters, getters;
  for (std::size_t i = 0; i < model.parameters.size(); ++i) {
    const model::Parameter& par = model.parameters[i];
    param_names.push_back(par.name);
    fields += "  double " + par.name + " = " + format_double(par.value) + ";\n";
    setters += "  if (std::strcmp(name, \"" + par.name + "\") == 0) {\n    p." + par.name +
               " = value;\n    return true;\n  }\n";
    getters += "    case " + std::to_string(i) + ": return p." + par.name + ";\n";
  }
  const std::vector<double>& q0 = eq.q0;
  const std::vector<double>& u0 = eq.u0;
  const std::string file = std::filesystem::path(model.source_file).filename().string();
  const std::map<std::string, std::string> values{
      {"MODEL_NAME", model.name},
      {"MODEL_FILE", file},
      {"MODEL_HASH", model_hash},
      {"GENERATOR_VERSION", KANEGEN_VERSION},
      {"OPERATION_COUNTS", counts},
      {"PARAMS_FIELDS", fields},
      {"NQ", std::to_string(eq.nq)},
      {"NU", std::to_string(n)},
      {"NTAU", std::to_string(eq.input_names.size())},
      {"NY", std::to_string(output_names.size())},
      {"NP", std::to_string(param_names.size())},
      {"NQ_ARRAY", array_size(eq.nq)},
      {"NU_ARRAY", array_size(n)},
      {"NTAU_ARRAY", array_size(eq.input_names.size())},
      {"NY_ARRAY", array_size(output_names.size())},
      {"NP_ARRAY", array_size(param_names.size())},
      {"COORDINATE_NAMES", quoted_list(eq.coordinate_names)},
      {"SPEED_NAMES", quoted_list(eq.speed_names)},
      {"INPUT_NAMES", quoted_list(eq.input_names)},
      {"OUTPUT_NAMES", quoted_list(output_names)},
      {"PARAMETER_NAMES", quoted_list(param_names)},
      {"Q0", number_list(q0)},
      {"U0", number_list(u0)},
      {"SET_PARAMETER", setters},
      {"INITIAL_STATE", initial_text},
      {"GET_PARAMETER", getters},
      {"MASS_MATRIX", kernels["mass_matrix"].body},
      {"FORCING", kernels["forcing"].body},
      {"DYNAMICS", kernels["forward_dynamics"].body},
      {"DYNAMICS_RETURN", dynamics_return},
      {"CONSTRAINT_DECLARATIONS", constraint_declarations},
      {"CONSTRAINT_SYSTEM", constraint_system},
      {"CONSTRAINT_DEFINITIONS", constraint_definitions},
      {"REACTION_OUTPUTS", reaction_text},
      {"LDLT_SOLVE", solve.body},
      {"COORDINATE_RATES", kernels["coordinate_rates"].body},
      {"KINETIC_ENERGY", kernels["kinetic_energy"].body},
      {"POTENTIAL_ENERGY", kernels["potential_energy"].body},
      {"OUTPUTS", kernels["outputs"].body},
  };
  emitted.files[model.name + ".hpp"] = fill_template(embedded::model_hpp_template, values);
  emitted.files[model.name + ".cpp"] = fill_template(embedded::model_cpp_template, values);
  emitted.files[model.name + "_runner.cpp"] = fill_template(embedded::runner_cpp_template, values);
  return emitted;
}

void write_files_atomically(const std::string& dir, const std::map<std::string, std::string>& files) {
  namespace fs = std::filesystem;
  std::error_code error;
  fs::create_directories(dir, error);
  if (error) throw std::runtime_error(dir + ": cannot create the output directory (" + error.message() + ")");
  // Write every file first, then rename them all: a failure leaves the old files.
  std::vector<std::pair<fs::path, fs::path>> staged;
  for (const auto& [name, content] : files) {
    const fs::path target = fs::path(dir) / name;
    const fs::path temporary = fs::path(dir) / ("." + name + "." + std::to_string(::getpid()) + ".tmp");
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    out << content;
    out.close();
    if (!out) {
      for (const auto& s : staged) fs::remove(s.first, error);
      fs::remove(temporary, error);
      throw std::runtime_error(target.string() + ": cannot write (disk full or no permission?)");
    }
    staged.emplace_back(temporary, target);
  }
  for (const auto& [temporary, target] : staged) {
    fs::rename(temporary, target, error);
    if (error) throw std::runtime_error(target.string() + ": cannot replace (" + error.message() + ")");
  }
}

}  // namespace kanegen::codegen
