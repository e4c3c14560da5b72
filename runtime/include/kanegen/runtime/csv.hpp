// SPDX-License-Identifier: MIT
// A CSV writer that puts every row on disk as soon as it is written, so a
// run that stops with an error keeps all rows up to that point.
#pragma once

#include <cstdio>
#include <string>
#include <vector>

namespace kanegen::runtime {

class CsvWriter {
 public:
  /// Writes to `stream` (e.g. stdout), which the writer does not close.
  explicit CsvWriter(std::FILE* stream) : stream_(stream) {}
  /// Opens `path` for writing, truncating it; "-" means stdout. On failure
  /// ok() is false and error() says why.
  explicit CsvWriter(const std::string& path);
  ~CsvWriter();
  CsvWriter(const CsvWriter&) = delete;
  CsvWriter& operator=(const CsvWriter&) = delete;

  /// Column names; names with a comma, quote or line break are quoted.
  bool write_header(const std::vector<std::string>& names);
  /// One row of numbers in "%.17g" (round-trip), then a flush.
  bool write_row(const double* values, int n);
  /// Closes an owned file; reports errors of the final flush.
  bool close();

  bool ok() const { return stream_ != nullptr && error_.empty(); }
  const std::string& error() const { return error_; }

 private:
  bool finish_line();

  std::FILE* stream_ = nullptr;
  bool owned_ = false;
  std::string path_ = "<stream>";
  std::string error_;
};

}  // namespace kanegen::runtime
