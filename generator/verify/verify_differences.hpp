// SPDX-License-Identifier: GPL-2.0-or-later
// What kanegen verify's checks by differences share (verify_jacobians.cpp,
// verify_controller.cpp): the round-off model of a difference quotient, each
// entry's scale, the runner's numbers as vectors, and the row of an optional
// kernel group that the files do not have.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "verify/verify_report.hpp"

namespace kanegen::verify {

constexpr double kDifferenceEpsilon = 2.2e-16;
/// The differences' round-off is taken as this many eps of the magnitude of
/// the differenced quantity over the step: the Richardson step triples it,
/// the magnitude is itself a sum of terms that partly cancel, and with
/// foreshortening in modes the numeric M and f are a weighted sum of five
/// evaluations (numeric/dynamics.cpp, truncation_samples), whose round-off
/// is larger again (free_strip_modal: 1.3e-10 in d(M a)/dq, where 100 eps
/// allowed as much).
constexpr double kDifferenceNoiseFactor = 1000;

/// The round-off of a difference quotient of a quantity of size `magnitude` with step h.
inline double difference_noise(double magnitude, double h) {
  return kDifferenceNoiseFactor * kDifferenceEpsilon * magnitude / h;
}

/// A JSON array of numbers (null: NaN, which no comparison passes).
std::vector<double> json_numbers(const nlohmann::json& array);
/// A JSON array of rows, row after row.
std::vector<double> json_rows_flat(const nlohmann::json& rows);

/// Each entry's scale for a matrix of `columns` columns, row-major: its size,
/// not below 1e-3 of the largest entry of its row nor 1e-6 of the largest
/// overall (an entry that is zero by structure is held to the round-off of
/// its row); plus the differences' round-off over the tolerance, so that
/// error <= tolerance * scale means |generated - reference| <= tolerance *
/// size + round-off.
std::vector<double> difference_scales(const std::vector<double>& reference, const std::vector<double>& noise,
                                      int columns, double tolerance);

/// The row of an optional kernel group (`title`, e.g. "Jacobians", checked
/// against `reference`) that the kernels do not have: `requested` with its
/// `flag` (e.g. "--jacobians") or not.
Row optional_kernels_absent_row(const std::string& title, const std::string& reference,
                                const std::string& flag, bool requested);

}  // namespace kanegen::verify
