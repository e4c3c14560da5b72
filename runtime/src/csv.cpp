// SPDX-License-Identifier: MIT
#include "kanegen/runtime/csv.hpp"

#include <cerrno>
#include <cstring>

namespace kanegen::runtime {

CsvWriter::CsvWriter(const std::string& path) : path_(path) {
  if (path == "-") {
    stream_ = stdout;
    return;
  }
  stream_ = std::fopen(path.c_str(), "w");
  if (!stream_) {
    error_ = "cannot open " + path + " for writing: " + std::strerror(errno);
    return;
  }
  owned_ = true;
}

CsvWriter::~CsvWriter() { close(); }

bool CsvWriter::close() {
  if (!stream_) return ok();
  if (owned_ && std::fclose(stream_) != 0 && error_.empty()) {
    error_ = "cannot write " + path_ + ": " + std::strerror(errno);
  }
  stream_ = nullptr;
  return error_.empty();
}

bool CsvWriter::write_header(const std::vector<std::string>& names) {
  if (!ok()) return false;
  std::string line;
  for (size_t i = 0; i < names.size(); ++i) {
    if (i) line += ',';
    const std::string& s = names[i];
    if (s.find_first_of(",\"\r\n") == std::string::npos) {
      line += s;
      continue;
    }
    line += '"';
    for (char c : s) line += c == '"' ? std::string("\"\"") : std::string(1, c);
    line += '"';
  }
  std::fputs(line.c_str(), stream_);
  return finish_line();
}

bool CsvWriter::write_row(const double* values, int n) {
  if (!ok()) return false;
  for (int i = 0; i < n; ++i) {
    std::fprintf(stream_, i ? ",%.17g" : "%.17g", values[i]);
  }
  return finish_line();
}

bool CsvWriter::finish_line() {
  std::fputc('\n', stream_);
  if (std::fflush(stream_) != 0 || std::ferror(stream_)) {
    error_ = "cannot write " + path_ + ": " + std::strerror(errno);
    return false;
  }
  return true;
}

}  // namespace kanegen::runtime
