// SPDX-License-Identifier: GPL-2.0-or-later
// kanegen verify's bookkeeping: the largest error of each compared quantity
// over all samples, where it occurred, and the table / JSON report.
#pragma once

#include <cstdio>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

namespace kanegen::verify {

/// The worst comparison of a quantity so far.
struct Worst {
  double abs = 0;                     ///< largest absolute difference
  double rel = 0;                     ///< the error measure that is held against the tolerance
  int where = -1;                     ///< sample (or trajectory) index; -1 if nothing compared
  std::string entry;                  ///< e.g. "[1,0] (elbow, shoulder)"
  double generated = 0, numeric = 0;  ///< the two values at that entry
};

/// One line of the report.
struct Row {
  Row(std::string quantity_, std::string against_, double tolerance_)
      : quantity(std::move(quantity_)), against(std::move(against_)), tolerance(tolerance_) {}

  std::string quantity;  ///< e.g. "mass_matrix"
  std::string against;   ///< what it is compared with, e.g. "numeric M"
  double tolerance = 0;
  Worst worst;
  long compared = 0;                  ///< number of comparisons (states or trajectory points)
  std::string note;                   ///< extra information, e.g. the smallest eigenvalue ratio
  std::string failure;                ///< what went wrong, when "generated x, reference y" does not fit
  bool applicable = true;             ///< false: nothing to compare for this model (shown as such, passes)
  std::string where_kind = "sample";  ///< what Worst::where counts

  bool passed() const { return !applicable || worst.rel <= tolerance; }  // NaN fails
  /// Keeps `candidate` if it is worse (NaN is worst of all).
  void consider(const Worst& candidate);
};

/// Names entry i of a compared vector.
using EntryName = std::function<std::string(int)>;

/// Compares a generated vector with a reference: abs = max|a - b|, rel =
/// abs / scale, entry = the index of the largest difference.
Worst compare(const std::vector<double>& generated, const std::vector<double>& reference, double scale,
              const EntryName& name, int where);

/// Entry by entry, each against its own scale: rel = max |a_i - b_i| /
/// scale_i; entry, values and abs = |a_i - b_i| where that is largest.
Worst compare_entries(const std::vector<double>& generated, const std::vector<double>& reference,
                      const std::vector<double>& scale, const EntryName& name, int where);

/// max |x_i| (0 for an empty vector); NaN if any entry is NaN.
double max_abs(const std::vector<double>& x);

struct ReportHeader {
  std::string model;
  int coordinates = 0, parameters = 0, samples = 0;
  unsigned long seed = 0;
  double rtol = 0;
  double seconds = 0;
};

void print_table(std::FILE* out, const ReportHeader& header, const std::vector<Row>& rows);
nlohmann::json report_json(const ReportHeader& header, const std::vector<Row>& rows,
                           const std::vector<std::string>& failures);

}  // namespace kanegen::verify
