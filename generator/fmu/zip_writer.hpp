// SPDX-License-Identifier: GPL-2.0-or-later
// A ZIP archive (an .fmu) in memory: stored entries (no compression), each with its CRC-32, a local header,
// a central directory and its end record (PKWARE's APPNOTE, 4.3). Ours, so that exporting an FMU needs no
// zip program nor library; deterministic (every entry dated 1980-01-01 00:00), so an export of the same
// model is byte-identical.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace kanegen::fmu {

/// CRC-32 (ISO 3309, polynomial 0xEDB88320 reflected) of `bytes`, as ZIP stores it.
std::uint32_t crc32(const std::string& bytes);

class ZipWriter {
 public:
  /// Adds the file `name` (a relative path with '/' separators) holding `bytes`. Throws
  /// std::invalid_argument for an empty, absolute or ".."-holding name, a duplicate, or an entry or
  /// archive past ZIP's 4 GiB (no ZIP64).
  void add(const std::string& name, const std::string& bytes);
  /// The archive's bytes.
  std::string finish() const;

 private:
  struct Entry {
    std::string name;
    std::uint32_t crc, size, offset;
  };
  std::string data_;  ///< the local headers and contents so far
  std::vector<Entry> entries_;
};

}  // namespace kanegen::fmu
