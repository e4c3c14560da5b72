// SPDX-License-Identifier: GPL-2.0-or-later
// The part of every FMU's sources/ that does not depend on the model (the runtime's sources and the FMI
// wrapper's instance), compiled once into one relocatable object in the runner cache, keyed by its text,
// the compiler and the flags, so that an export compiles only the model and its FMI entry points. The
// binary is still built from exactly the files of sources/ with the same flags.
#pragma once

#include <map>
#include <string>
#include <vector>

namespace kanegen::fmu {

/// Whether `file` (relative to sources/) is compiled into the shared object.
bool is_shared(const std::string& file);

/// The path of the cached object compiled from the shared files of `sources` (path -> text) with
/// `flags`; compiled under the entry's lock if the cache has none. Throws std::runtime_error (as the
/// runner cache does: a cache others may write, a compiler error), runner::Interrupted.
std::string shared_object(const std::map<std::string, std::string>& sources,
                          const std::vector<std::string>& flags, bool verbose);

}  // namespace kanegen::fmu
