// SPDX-License-Identifier: GPL-2.0-or-later
#include "codegen/emitter.hpp"

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <vector>

#include "codegen/batch_kernels.hpp"
#include "codegen/cpp_printer.hpp"
#include "codegen/cpp_text.hpp"
#include "codegen/embedded_templates.hpp"
#include "codegen/expression_graph.hpp"
#include "codegen/kernel_printer.hpp"
#include "codegen/model_kernels.hpp"

namespace kanegen::codegen {
namespace {

using TemplateValues = std::map<std::string, std::string>;

std::string quoted_list(const std::vector<std::string>& names) {
  std::string s;
  for (const std::string& n : names) s += (s.empty() ? "" : ", ") + cpp_string_literal(n);
  return s;
}

std::string number_list(const std::vector<double>& values, const ScalarType& scalar) {
  std::string s;
  for (double v : values) s += (s.empty() ? "" : ", ") + scalar.literal(v);
  return s.empty() ? scalar.literal(0.0) : s;
}

std::string array_size(std::size_t n) { return std::to_string(n > 0 ? n : 1); }

/// The bodies each coordinate moves as one list and where each
/// coordinate's part starts (nq + 1 offsets).
void add_moved_bodies(TemplateValues& values, const kane::Coordinates& eq, int nq) {
  std::vector<std::string> bodies;
  std::string first = "0";
  for (const std::vector<std::string>& moved : eq.moved_bodies) {
    bodies.insert(bodies.end(), moved.begin(), moved.end());
    first += ", " + std::to_string(bodies.size());
  }
  values["COORDINATE_JOINTS"] = quoted_list(eq.coordinate_joints);
  values["MOVED_BODIES_FIRST"] = first;
  values["MOVED_BODIES"] = bodies.empty() ? "nullptr" : quoted_list(bodies);
  values["MOVED_BODIES_ARRAY"] = array_size(bodies.size());
  values["NQ1_ARRAY"] = std::to_string(nq + 1);
}

/// The sections of a template file whose lines "//== KEY" start each one;
/// the text before the first is the file's comment.
TemplateValues template_sections(const std::string& text) {
  TemplateValues sections;
  const std::string marker = "//== ";
  std::size_t at = text.find(marker);
  while (at != std::string::npos) {
    const std::size_t key_end = text.find('\n', at);
    const std::size_t next = text.find(marker, key_end);
    sections[text.substr(at + marker.size(), key_end - at - marker.size())] =
        text.substr(key_end + 1, (next == std::string::npos ? text.size() : next) - key_end - 1);
    at = next;
  }
  return sections;
}

/// The lines of a compilable helper file between its embed markers.
std::string embedded_region(const std::string& text) {
  const std::string begin = "// kanegen:embed-begin\n", end = "// kanegen:embed-end\n";
  const std::size_t from = text.find(begin), to = text.find(end);
  if (from == std::string::npos || to == std::string::npos || to < from)
    throw std::logic_error("helper template without its embed markers");
  return text.substr(from + begin.size(), to - from - begin.size());
}

/// Names, sizes, initial state and parameters: everything but the kernels.
/// A float model is named <name>_float (files and namespace), so that a
/// program can hold both precisions of one model.
TemplateValues model_values(kane::DerivationContext& products, const std::string& model_hash,
                            const ScalarType& scalar) {
  const model::Model& model = products.model();
  const kane::Coordinates& eq = products.coordinates();
  const std::vector<std::string>& output_names = products.outputs().names;
  std::vector<std::string> parameter_names;
  std::string fields;
  for (const model::Parameter& par : model.parameters) {
    parameter_names.push_back(par.name);
    fields += "  " + std::string(scalar.name()) + " " + cpp_identifier(par.name) + " = " +
              scalar.literal(par.value) + ";\n";
  }
  const std::size_t ntau = eq.input_names.size(), ny = output_names.size();
  return {
      {"MODEL_NAME", cpp_identifier(emitted_name(model.name, scalar))},
      {"SCALAR", scalar.name()},
      {"PRECISION_NOTE", scalar.is_double()
                             ? ""
                             : "// Single precision (kanegen generate --precision float): every "
                               "argument, local and literal is float.\n"},
      {"MODEL_FILE", cpp_comment_text(std::filesystem::path(model.source_file).filename().string())},
      {"MODEL_HASH", model_hash},
      {"GENERATOR_VERSION", KANEGEN_VERSION},
      {"PARAMS_FIELDS", fields},
      {"NQ", std::to_string(products.nq())},
      {"NU", std::to_string(products.nu())},
      {"NTAU", std::to_string(ntau)},
      {"NONCONSERVATIVE", products.energies().nonconservative ? "true" : "false"},
      {"NY", std::to_string(ny)},
      {"NP", std::to_string(parameter_names.size())},
      {"NQ_ARRAY", array_size(products.nq())},
      {"NU_ARRAY", array_size(products.nu())},
      {"NTAU_ARRAY", array_size(ntau)},
      {"NY_ARRAY", array_size(ny)},
      {"NP_ARRAY", array_size(parameter_names.size())},
      {"COORDINATE_NAMES", quoted_list(eq.coordinate_names)},
      {"SPEED_NAMES", quoted_list(eq.speed_names)},
      {"INPUT_NAMES", quoted_list(eq.input_names)},
      {"OUTPUT_NAMES", quoted_list(output_names)},
      {"PARAMETER_NAMES", quoted_list(parameter_names)},
      {"Q0", number_list(eq.q0, scalar)},
      {"U0", number_list(eq.u0, scalar)},
  };
}

/// The loop parts (templates/loop_parts.in and the saddle-point solver, in
/// the model's precision), or nothing for an open tree.
void add_loop_values(TemplateValues& values, kane::DerivationContext& products, const ScalarType& scalar) {
  const bool loops = products.has_loops();
  TemplateValues sections = template_sections(embedded::loop_parts_template);
  std::string roles;
  for (int role : products.coordinates().roles) roles += (roles.empty() ? "" : ", ") + std::to_string(role);
  TemplateValues loop_values = values;
  if (loops) {
    loop_values["NC"] = std::to_string(products.loops().size());
    loop_values["CONSTRAINT_NAMES"] = quoted_list(products.loops().names);
  }
  loop_values["COORDINATE_ROLES"] = roles;
  for (const auto& [key, text] : sections) values[key] = loops ? fill_template(text, loop_values) : "";
  values["HELPERS"] = loops ? "namespace {\n\n" +
                                  scalar.in_code(embedded_region(embedded::solve_saddle_template)) +
                                  "\n}  // namespace\n\n"
                            : "";
}

/// Declarations, definitions, System forwarders, the function-pointer table
/// and the operation counts, each kernel printed from its table entry.
void add_kernel_values(TemplateValues& values, const std::vector<KernelCode>& kernels,
                       const std::string& model_name, const ScalarType& scalar) {
  std::string declarations, definitions, forwarders, table, counts;
  for (const KernelCode& code : kernels) {
    const KernelSignature& s = signature(code.kernel);
    declarations += declaration(s, scalar) + "\n";
    definitions += "\n" + definition(s, code.body, scalar);
    forwarders += system_forwarder(s, model_name);
    if (s.in_runtime_table) table += table_entry(s);
    if (s.counted)
      counts +=
          "//   " + std::string(s.name) + ": " + std::to_string(code.operations) + code.count_note + "\n";
  }
  values["KERNEL_DECLARATIONS"] = declarations;
  values["KERNEL_DEFINITIONS"] = definitions;
  values["SYSTEM_FORWARDERS"] = forwarders;
  values["TABLE_ENTRIES"] = table;
  values["OPERATION_COUNTS"] = counts;
  // The runtime's face (kernel_table, System) is double: a float model has none.
  values["RUNTIME_FACE"] =
      scalar.is_double()
          ? fill_template(template_sections(embedded::runtime_face_template).at("RUNTIME_FACE"), values)
          : "";
}

}  // namespace

std::string emitted_name(const std::string& model_name, const ScalarType& scalar) {
  return scalar.is_double() ? model_name : model_name + "_float";
}

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

EmittedModel emit_model(kane::DerivationContext& products, ExpressionGraph& graph,
                        const std::string& model_hash, const EmitOptions& options) {
  const model::Model& model = products.model();
  const ScalarType scalar(options.precision);
  // The Jacobian kernels (and linearize, which calls them) are written in double.
  if (!scalar.is_double() && options.jacobians) throw std::logic_error("float kernels with Jacobians");
  DynamicsChoice dynamics;
  const std::vector<KernelCode> kernels =
      derive_kernels(products, graph, options.jacobians, options.controller, scalar, options.dynamics,
                     &dynamics, options.split_threshold);
  TemplateValues values = model_values(products, model_hash, scalar);
  add_moved_bodies(values, products.coordinates(), products.nq());
  add_loop_values(values, products, scalar);
  add_kernel_values(values, kernels, model.name, scalar);
  EmittedModel emitted;
  emitted.dynamics = dynamics;
  for (const KernelCode& code : kernels)
    if (signature(code.kernel).counted) emitted.operations[code.kernel] = code.operations;
  const std::string name = emitted_name(model.name, scalar);
  emitted.files[name + ".hpp"] = fill_template(embedded::model_hpp_template, values);
  emitted.files[name + ".cpp"] = fill_template(embedded::model_cpp_template, values);
  if (scalar.is_double())  // the runner is the runtime's, which is double
    emitted.files[name + "_runner.cpp"] = fill_template(embedded::runner_cpp_template, values);
  if (options.batch > 0) {
    if (!scalar.is_double() || products.has_loops() || !products.coordinates().prescribed.empty())
      throw std::logic_error("batched kernels need double, no loops and no prescribed motions");
    for (auto& [file, code] : batch_files(kernels, values, options.batch)) emitted.files[file] = code;
  }
  for (const auto& [file, code] : emitted.files) check_emitted_text(file, code);
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
