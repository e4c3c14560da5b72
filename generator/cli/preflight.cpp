// SPDX-License-Identifier: GPL-2.0-or-later
#include "cli/preflight.hpp"

#include <unistd.h>

#include <CLI/CLI.hpp>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <stdexcept>

#include "kanegen/runtime/options.hpp"
#include "model/expression_eval.hpp"
#include "model/model_check.hpp"
#include "model/names.hpp"

namespace kanegen::cli {
namespace fs = std::filesystem;

std::string unknown_arguments_message(const CLI::App& command) {
  const std::vector<std::string> extras = command.remaining();
  if (extras.empty()) return "";
  std::vector<std::string> known;
  for (const CLI::Option* option : command.get_options())
    for (const std::string& name : option->get_lnames()) known.push_back("--" + name);
  std::string message;
  for (const std::string& extra : extras) {
    if (extra.rfind("-", 0) != 0) continue;  // an option's stray value: the option says enough
    const std::string name = extra.substr(0, extra.find('='));
    message += (message.empty() ? "" : "; ") + std::string("unknown option ") + name;
    if (const std::string guess = model::nearest(name, known); !guess.empty())
      message += "; did you mean " + guess + "?";
  }
  if (message.empty()) message = "unexpected argument '" + extras.front() + "'";
  return message + " (kanegen " + command.get_name() + " --help lists the options)";
}

void check_gravity_option(const std::string& model_path, bool gravity_given) {
  if (!gravity_given || fs::path(model_path).extension() == ".urdf") return;
  throw runtime::UsageError(
      "--gravity applies to URDF models only; " + model_path +
      " sets gravity in its \"gravity\" field: edit it there (or write it with a parameter and use --set)");
}

void check_sets(const std::string& model_path, const model::LoadOptions& load,
                const std::vector<std::string>& sets, bool refuse_unknown) {
  if (sets.empty()) return;
  const model::Model m = model::load_model(model_path, load);
  model::ParameterValues values = model::default_parameter_values(m);
  std::vector<std::string> names;
  for (const model::Parameter& p : m.parameters) names.push_back(p.name);
  for (const std::string& set : sets) {
    const auto equals = set.find('=');
    const std::string name = set.substr(0, equals);
    if (!values.count(name) && !refuse_unknown) continue;  // the caller's own parser names it
    if (!values.count(name)) {
      // As the runner says it (tests/reliability), so that the message does
      // not depend on whether kanegen or the runner finds it.
      throw runtime::UsageError("unknown parameter '" + name + "' in --set; " +
                                (names.empty() ? std::string("the model has no parameters")
                                               : "known parameters: " + model::join(names, ", ")));
    }
    // A malformed one is left to the runner's or modes' parser, which names it.
    if (equals == std::string::npos) continue;
    char* end = nullptr;
    const double value = std::strtod(set.c_str() + equals + 1, &end);
    if (end != set.c_str() + equals + 1 && *end == '\0') values[name] = value;  // else the parser refuses it
  }
  model::check_parameter_values(m, values, "from --set");
}

namespace {

/// `dir` can be created (or exists) and written in: its nearest existing
/// ancestor is a directory we may write in. Nothing is created here, so that
/// a model refused later leaves no trace.
void check_writable_directory(const fs::path& dir) {
  std::error_code error;
  fs::path existing = dir;
  while (!existing.empty() && !fs::exists(existing, error)) existing = existing.parent_path();
  if (existing.empty()) existing = ".";
  if (!fs::is_directory(existing, error))
    throw std::runtime_error(existing.string() + ": exists and is not a directory; give another output path");
  if (access(existing.c_str(), W_OK) != 0)
    throw std::runtime_error(existing.string() + ": cannot write in this directory (" + std::strerror(errno) +
                             "); give another output path");
}

}  // namespace

void check_output_file(const std::string& file) {
  if (file.empty() || file == "-") return;
  const fs::path path(file);
  std::error_code error;
  if (fs::is_directory(path, error))
    throw std::runtime_error(file + ": is a directory; give a file name, e.g. " +
                             (path / "result.csv").string());
  check_writable_directory(path.has_parent_path() ? path.parent_path() : fs::path("."));
  if (fs::exists(path, error) && access(path.c_str(), W_OK) != 0)
    throw std::runtime_error(file + ": cannot be overwritten (" + std::strerror(errno) +
                             "); give another output path");
}

void check_output_directory(const std::string& dir) { check_writable_directory(dir); }

void create_output_directory(const std::string& file) {
  if (file.empty() || file == "-") return;
  const fs::path parent = fs::path(file).parent_path();
  std::error_code error;
  if (!parent.empty()) fs::create_directories(parent, error);
  if (error)
    throw std::runtime_error(parent.string() + ": cannot create the output directory (" + error.message() +
                             "); give another output path");
}

}  // namespace kanegen::cli
