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
  for (const std::string& n : names) s += (s.empty() ? "\"" : ", \"") + n + "\"";
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
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const std::string index = std::to_string(i * n + j);
      const int node = graph.add(eq.mass_matrix[i * n + j]);
      mass.push_back({"M[" + index + "]", node});
      if (j <= i) dynamics.push_back({"M[" + index + "]", node});
    }
  for (int i = 0; i < n; ++i) {
    const int node = graph.add(eq.forcing[i]);
    force.push_back({"f[" + std::to_string(i) + "]", node});
    dynamics.push_back({"udot[" + std::to_string(i) + "]", node});
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
  // The LDL^T solve of forward_dynamics, counted by its loop structure.
  const long ldlt = static_cast<long>(n) * n * n / 3 + 2L * n * n;
  kernels["forward_dynamics"].operations += ldlt;

  EmittedModel emitted;
  std::string counts;
  for (const char* name : {"mass_matrix", "forcing", "forward_dynamics", "kinetic_energy", "potential_energy",
                           "outputs"}) {
    emitted.operations[name] = kernels[name].operations;
    counts += "//   " + std::string(name) + ": " + std::to_string(kernels[name].operations) +
              (std::string(name) == "forward_dynamics" ? " (with about " + std::to_string(ldlt) + " in LDL^T)" : "") +
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
  std::vector<double> q0, u0;
  for (const model::Joint& j : model.joints)
    if (j.moves()) {
      q0.push_back(j.q0);
      u0.push_back(j.u0);
    }
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
      {"NTAU", std::to_string(n)},
      {"NY", std::to_string(output_names.size())},
      {"NP", std::to_string(param_names.size())},
      {"NQ_ARRAY", array_size(eq.nq)},
      {"NU_ARRAY", array_size(n)},
      {"NU2_ARRAY", array_size(static_cast<std::size_t>(n) * n)},
      {"NTAU_ARRAY", array_size(n)},
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
      {"GET_PARAMETER", getters},
      {"MASS_MATRIX", kernels["mass_matrix"].body},
      {"FORCING", kernels["forcing"].body},
      {"DYNAMICS", kernels["forward_dynamics"].body},
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
