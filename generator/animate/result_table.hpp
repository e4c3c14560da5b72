// SPDX-License-Identifier: GPL-2.0-or-later
// A result CSV as written by `kanegen simulate` (a header starting with t,
// then one row of numbers per output time), read for `kanegen animate`.
#pragma once

#include <string>
#include <vector>

namespace kanegen::animate {

struct ResultTable {
  std::string file;
  std::vector<std::string> columns;       ///< the header, "t" first
  std::vector<std::vector<double>> rows;  ///< one per time, as many numbers as columns

  /// The index of a column, or -1.
  int column(const std::string& name) const;
};

/// Reads the CSV. Throws std::runtime_error naming the file, the line and
/// the fix for a missing or bad header, a short or long row, or a cell that
/// is not a finite number; and for a file without rows.
ResultTable read_result_table(const std::string& path);

/// The rows to draw: all of them if there are at most `frames`, else
/// `frames` rows spread evenly over the table (the first and the last kept;
/// frames < 2 keeps all).
std::vector<std::size_t> chosen_rows(std::size_t row_count, std::size_t frames);

}  // namespace kanegen::animate
