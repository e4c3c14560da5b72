// SPDX-License-Identifier: GPL-2.0-or-later
// A model file written from text to a temporary file and loaded, for the
// tests of mesh bodies in model files.
#pragma once

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "model/load.hpp"

namespace kanegen_test {

/// Loads the model `text`, written to a file of its own (ctest runs a test
/// executable's cases in parallel, so the file is per process and `tag`).
inline kanegen::model::Model load_model_text(const std::string& text, const std::string& tag) {
  const std::string path = (std::filesystem::temp_directory_path() /
                            ("kanegen_test_" + tag + "_" + std::to_string(::getpid()) + ".json"))
                               .string();
  std::ofstream(path) << text;
  struct Remove {
    const std::string& path;
    ~Remove() { std::remove(path.c_str()); }
  } remove{path};
  return kanegen::model::load_model(path);
}

}  // namespace kanegen_test
