// SPDX-License-Identifier: GPL-2.0-or-later
// libFuzzer target: the kanegen JSON model loader (syntax, schema, format
// rules, model checks), then GiNaC on every expression of an accepted model.
// Checks: fuzz/harness.hpp; running: fuzz/run.sh.
#include <cstddef>
#include <cstdint>

#include "fuzz/harness.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return kanegen::fuzz::run_or_abort(kanegen::fuzz::json_model, data, size);
}
