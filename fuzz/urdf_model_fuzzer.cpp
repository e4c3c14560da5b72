// SPDX-License-Identifier: GPL-2.0-or-later
// libFuzzer target: the URDF loader (tinyxml2, urdfdom, model checks).
// Checks: fuzz/harness.hpp; running: fuzz/run.sh.
#include <cstddef>
#include <cstdint>

#include "fuzz/harness.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return kanegen::fuzz::run_or_abort(kanegen::fuzz::urdf_model, data, size);
}
