// SPDX-License-Identifier: GPL-2.0-or-later
// libFuzzer target: the load-time expression check and GiNaC's parser on what it accepts.
// Checks: fuzz/harness.hpp; running: fuzz/run.sh.
#include <cstddef>
#include <cstdint>

#include "fuzz/harness.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return kanegen::fuzz::run_or_abort(kanegen::fuzz::expression, data, size);
}
