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

  EmittedModel emitted;
  std::string counts;
  for (const char* name : {"mass_matrix", "forcing", "forward_dynamics", "kinetic_energy", "potential_energy",
                           "outputs"}) {
    emitted.operations[name] = kernels[name].operations;
    counts += "//   " + std::string(name) + ": " + std::to_string(kernels[name].operations) +
              (std::string(name) == "forward_dynamics" ? " (" + std::to_string(ldlt) + " of them in LDL^T)" : "") +
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
