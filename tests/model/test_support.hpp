// SPDX-License-Identifier: GPL-2.0-or-later
// Helpers shared by the model tests.
#pragma once

#include <catch2/catch.hpp>
#include <string>

#include "model/load.hpp"

namespace kanegen::model::test {

inline std::string source_path(const std::string& relative) {
  return std::string(KANEGEN_SOURCE_DIR) + "/" + relative;
}
inline std::string bad_model(const std::string& name) { return source_path("tests/data/bad_models/" + name); }
inline std::string test_data(const std::string& name) {
  return std::string(KANEGEN_MODEL_TEST_DATA) + "/" + name;
}

/// Loading `file` fails with one ModelError "FILE: PLACE: problem; fix"
/// that names the file and the exact place and contains the problem and the
/// fix hint. Any other exception fails the test.
inline void expect_model_error(const std::string& file, const std::string& place, const std::string& problem,
                               const std::string& fix) {
  try {
    load_model(file);
    FAIL("no error for " << file);
  } catch (const ModelError& e) {
    const std::string message = e.what();
    INFO(message);
    CHECK(e.file() == file);
    CHECK(e.place() == place);
    CHECK(message.rfind(file + ": " + place + ": ", 0) == 0);
    CHECK_THAT(message, Catch::Contains(problem));
    const auto separator = message.rfind("; ");
    REQUIRE(separator != std::string::npos);
    CHECK_THAT(message.substr(separator + 2), Catch::Contains(fix));
  }
}

}  // namespace kanegen::model::test
