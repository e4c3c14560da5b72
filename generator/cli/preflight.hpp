// SPDX-License-Identifier: GPL-2.0-or-later
// Checks of the command line made before anything is generated or compiled,
// so that a mistake costs a fraction of a second rather than a build: the
// options given, the --set values against the model's physics and the
// output path.
#pragma once

#include <string>
#include <vector>

#include "model/load.hpp"

namespace CLI {
class App;
}

namespace kanegen::cli {

/// The arguments a subcommand did not recognise (its remaining()), as one
/// message: "unknown option --tend; did you mean --t-end?", or "" if none.
std::string unknown_arguments_message(const CLI::App& command);

/// Refuses --gravity for a model whose format sets gravity itself (JSON):
/// ignoring it would run another model than the one asked for. Throws
/// kanegen::runtime::UsageError.
void check_gravity_option(const std::string& model_path, bool gravity_given);

/// Loads the model and checks its physical conditions (positive masses,
/// valid inertias, ...) with each NAME=VALUE of `sets` applied. Throws
/// model::ModelError, or kanegen::runtime::UsageError for an unknown name.
void check_sets(const std::string& model_path, const model::LoadOptions& load,
                const std::vector<std::string>& sets);

/// Makes sure FILE can be written before the work that produces it:
/// creates its missing directories, refuses a directory or an unwritable
/// place. "" and "-" (stdout) pass. Throws std::runtime_error.
void prepare_output_file(const std::string& file);

/// The same for an output directory (created if needed).
void prepare_output_directory(const std::string& dir);

}  // namespace kanegen::cli
