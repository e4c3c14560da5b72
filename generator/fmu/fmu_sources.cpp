// SPDX-License-Identifier: GPL-2.0-or-later
#include "fmu/fmu_sources.hpp"

#include <cstdio>
#include <stdexcept>

#include "codegen/cpp_text.hpp"
#include "fmu/embedded_files.hpp"
#include "kanegen/runtime/methods.hpp"

namespace kanegen::fmu {

namespace {

/// Whether an FMU carries the row's method (an alias's, its target's; the runtime's registry,
/// methods.hpp: a row with a reason in not_in_fmu is not carried).
bool in_fmu(const runtime::MethodSpec& row) {
  return runtime::resolved_spec(row.method).not_in_fmu == nullptr;
}

}  // namespace

void check_integrator(const std::string& method) {
  for (const std::string& name : fmu_integrators())
    if (name == method) return;
  std::string known, why;
  for (const std::string& name : fmu_integrators()) known += (known.empty() ? "" : ", ") + name;
  for (const runtime::MethodSpec& row : runtime::kMethods)
    if (row.alias_of == row.method && !in_fmu(row))
      why += std::string(why.empty() ? "" : "; ") + row.name + ": " + row.not_in_fmu;
  throw std::invalid_argument("--integrator " + method + ": an FMU's co-simulation integrates with " + known +
                              " (" + why + ")");
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
  check_integrator(o.method);
  replace_all(text, "@METHOD@", codegen::cpp_string_literal(o.method));
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
  static const std::vector<std::string> names = [] {
    std::vector<std::string> out;
    for (const runtime::MethodSpec& row : runtime::kMethods)
      if (in_fmu(row)) out.push_back(row.name);
    return out;
  }();
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
