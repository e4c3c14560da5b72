// SPDX-License-Identifier: GPL-2.0-or-later
// What the fuzz targets check, shared with the regression test that replays
// tests/data/fuzz_regressions/ in the default build (no libFuzzer needed).
// Each check feeds one input to a loader and accepts exactly two outcomes: a
// checked model (whose invariants are then verified) or one ModelError naming
// the file and a place. Anything else (another exception, a broken invariant,
// an expression the load-time check accepts but GiNaC cannot read) throws
// HarnessFailure; crashes, hangs and sanitizer reports are libFuzzer's.
#pragma once

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "model/model_error.hpp"

namespace kanegen::fuzz {

/// A bug found by a harness (the input is a reproducer).
struct HarnessFailure : std::logic_error {
  using std::logic_error::logic_error;
};

/// Throws HarnessFailure unless the message of `e` names `file` and a place
/// and says the problem in one line ("FILE: PLACE: problem[; fix]"), or in
/// three for an expression shown with a caret under the culprit.
void check_error(const model::ModelError& e, const std::string& file);

/// The bytes as a kanegen JSON model; on success every expression of the
/// model is also read by GiNaC (kanegen::symbolic::Variables::scalar).
void json_model(const std::uint8_t* data, std::size_t size);

/// The bytes as a URDF file.
void urdf_model(const std::uint8_t* data, std::size_t size);

/// First line: parameter names separated by blanks or commas (inputs with an
/// invalid or reserved name are skipped, as the loaders reject them); the
/// rest: an expression. It goes through the load-time check; if accepted, the
/// numeric evaluator (model/expression_eval) must read it too, and if its
/// value is finite (the loaders refuse the others) GiNaC's parser must as well.
void expression(const std::uint8_t* data, std::size_t size);

/// For LLVMFuzzerTestOneInput: runs `check`, prints a HarnessFailure and
/// aborts (so libFuzzer keeps the input). Returns 0.
int run_or_abort(void (*check)(const std::uint8_t*, std::size_t), const std::uint8_t* data, std::size_t size);

}  // namespace kanegen::fuzz
