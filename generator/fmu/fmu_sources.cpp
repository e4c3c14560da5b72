// SPDX-License-Identifier: GPL-2.0-or-later
#include "fmu/fmu_sources.hpp"

#include <cstdio>
#include <stdexcept>

#include "codegen/cpp_text.hpp"
#include "fmu/embedded_files.hpp"

namespace kanegen::fmu {

namespace {

/// The runtime's Method enumerator of an FMU integrator: the ones that need no library beyond the
/// standard one and step from any t0 (templates/fmu/absent_methods.cpp stands in for the others).
const char* method_enumerator(const std::string& method) {
  check_integrator(method);
  if (method == "rk4") return "kRk4";
  if (method == "dopri5") return "kDopri5";
  return "kRadau";  // radau, or implicit, which selects it
}

}  // namespace

void check_integrator(const std::string& method) {
  for (const std::string& name : fmu_integrators())
    if (name == method) return;
  std::string known;
  for (const std::string& name : fmu_integrators()) known += (known.empty() ? "" : ", ") + name;
  throw std::invalid_argument(
      "--integrator " + method + ": an FMU's co-simulation integrates with " + known +
      " (bdf needs SUNDIALS, which an FMU does not carry; genalpha steps whole runs)");
}

namespace {

std::string number(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.17g", value);
  return buffer;
}

void replace_all(std::string& text, const std::string& from, const std::string& to) {
  for (std::size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size()))
    text.replace(at, from.size(), to);
}

std::string fmu_model_source(const SourceOptions& o) {
  std::string text = embedded::fmu_model_template;
  replace_all(text, "@NAME@", codegen::cpp_identifier(o.identifier));
  replace_all(text, "@TOKEN@", codegen::cpp_string_literal(o.token));
  replace_all(text, "@METHOD@", method_enumerator(o.method));
  replace_all(text, "@RTOL@", number(o.rtol));
  replace_all(text, "@ATOL@", number(o.atol));
  replace_all(text, "@MAX_STEP@", number(o.max_step));
  codegen::check_emitted_text("fmu/fmu_model.cpp", text);
  return text;
}

bool ends_with(const std::string& text, const std::string& end) {
  return text.size() >= end.size() && text.compare(text.size() - end.size(), end.size(), end) == 0;
}

}  // namespace

const std::vector<std::string>& fmu_integrators() {
  static const std::vector<std::string> names = {"dopri5", "rk4", "radau", "implicit"};
  return names;
}

std::map<std::string, std::string> fmu_sources(const std::map<std::string, std::string>& generated,
                                               const SourceOptions& o) {
  std::map<std::string, std::string> sources;
  const std::string name = codegen::cpp_identifier(o.identifier);
  for (const char* part : {".hpp", ".cpp"}) sources["model/" + name + part] = generated.at(name + part);
  const std::string other_version = o.fmi_version == 2 ? "fmi3" : "fmi2";
  for (const embedded::EmbeddedFile* file = embedded::fmu_files; file->path != nullptr; ++file) {
    const std::string path = file->path;
    if (path.find("/" + other_version) == std::string::npos &&
        path.find("kanegen_" + other_version) == std::string::npos)
      sources[path] = file->text;
  }
  sources["fmu/fmu_model.cpp"] = fmu_model_source(o);
  return sources;
}

std::vector<std::string> compiled_files(const std::map<std::string, std::string>& sources) {
  std::vector<std::string> files;
  for (const auto& [path, text] : sources)
    if (ends_with(path, ".cpp")) files.push_back(path);
  return files;
}

}  // namespace kanegen::fmu
