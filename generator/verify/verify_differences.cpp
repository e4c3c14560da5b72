// SPDX-License-Identifier: GPL-2.0-or-later
#include "verify/verify_differences.hpp"

#include <algorithm>
#include <cmath>

namespace kanegen::verify {

std::vector<double> json_numbers(const nlohmann::json& array) {
  std::vector<double> v;
  for (const nlohmann::json& x : array) v.push_back(x.is_null() ? std::nan("") : x.get<double>());
  return v;
}

std::vector<double> json_rows_flat(const nlohmann::json& rows) {
  std::vector<double> v;
  for (const nlohmann::json& row : rows)
    for (const nlohmann::json& x : row) v.push_back(x.is_null() ? std::nan("") : x.get<double>());
  return v;
}

std::vector<double> difference_scales(const std::vector<double>& reference, const std::vector<double>& noise,
                                      int columns, double tolerance) {
  std::vector<double> s(reference.size());
  double all = 0;
  for (double x : reference) all = std::max(all, std::abs(x));
  for (int r = 0; columns > 0 && r * columns < static_cast<int>(reference.size()); ++r) {
    double row = 0;
    for (int c = 0; c < columns; ++c) row = std::max(row, std::abs(reference[r * columns + c]));
    for (int c = 0; c < columns; ++c) {
      const int k = r * columns + c;
      double size = std::max({std::abs(reference[k]), 1e-3 * row, 1e-6 * all});
      if (size == 0) size = 1.0;
      s[k] = size + noise[k] / tolerance;
    }
  }
  return s;
}

Row optional_kernels_absent_row(const std::string& title, const std::string& reference,
                                const std::string& flag, bool requested) {
  Row row(title, reference, 0.0);
  row.applicable = false;
  row.note = requested ? "the kernels have none (generate them with " + flag + ")"
                       : "not generated (kanegen verify " + flag + " checks them)";
  return row;
}

}  // namespace kanegen::verify
