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
/// model::ModelError, or kanegen::runtime::UsageError for an unknown name
/// (unless !refuse_unknown: then it is skipped, for a caller that reports it).
void check_sets(const std::string& model_path, const model::LoadOptions& load,
                const std::vector<std::string>& sets, bool refuse_unknown = true);

/// Checks that FILE can be written before the work that produces it: not a
/// directory, and its directory exists or can be created and is writable.
/// "" and "-" (stdout) pass. Throws std::runtime_error.
void check_output_file(const std::string& file);

/// Creates the missing directories of FILE (after the checks, just before
/// it is written), as generate -o creates its directory.
void create_output_directory(const std::string& file);

/// The check of check_output_file for an output directory.
void check_output_directory(const std::string& dir);

}  // namespace kanegen::cli
