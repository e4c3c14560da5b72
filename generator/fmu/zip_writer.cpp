// SPDX-License-Identifier: GPL-2.0-or-later
#include "fmu/zip_writer.hpp"

#include <array>
#include <limits>
#include <stdexcept>

namespace kanegen::fmu {

namespace {

constexpr std::uint16_t kVersion = 20;        // 2.0: what a stored entry with directories needs
constexpr std::uint16_t kDosDate = 0x0021;    // 1980-01-01
constexpr std::uint16_t kUtf8Names = 0x0800;  // general purpose bit 11: names are UTF-8

void put16(std::string& out, std::uint16_t v) {
  out += static_cast<char>(v & 0xFF);
  out += static_cast<char>(v >> 8);
}

void put32(std::string& out, std::uint32_t v) {
  for (int shift = 0; shift < 32; shift += 8) out += static_cast<char>((v >> shift) & 0xFF);
}

std::array<std::uint32_t, 256> crc_table() {
  std::array<std::uint32_t, 256> table{};
  for (std::uint32_t n = 0; n < 256; ++n) {
    std::uint32_t c = n;
    for (int k = 0; k < 8; ++k) c = (c & 1) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
    table[n] = c;
  }
  return table;
}

std::uint32_t checked_size(std::size_t size, const std::string& what) {
  if (size >= std::numeric_limits<std::uint32_t>::max())
    throw std::invalid_argument(what + " is too large for a ZIP archive without ZIP64 (4 GiB)");
  return static_cast<std::uint32_t>(size);
}

// The fields a local header and a central directory entry share, from "version needed" to the name's length.
void put_common(std::string& out, std::uint32_t crc, std::uint32_t size, std::size_t name_size) {
  put16(out, kVersion);
  put16(out, kUtf8Names);
  put16(out, 0);  // stored
  put16(out, 0);  // time 00:00
  put16(out, kDosDate);
  put32(out, crc);
  put32(out, size);  // compressed
  put32(out, size);  // uncompressed
  put16(out, static_cast<std::uint16_t>(name_size));
}

}  // namespace

std::uint32_t crc32(const std::string& bytes) {
  static const std::array<std::uint32_t, 256> table = crc_table();
  std::uint32_t c = 0xFFFFFFFFu;
  for (char byte : bytes) c = table[(c ^ static_cast<unsigned char>(byte)) & 0xFF] ^ (c >> 8);
  return c ^ 0xFFFFFFFFu;
}

void ZipWriter::add(const std::string& name, const std::string& bytes) {
  if (name.empty() || name.front() == '/' || name.size() > 0xFFFF || name.find('\\') != std::string::npos ||
      ("/" + name + "/").find("/../") != std::string::npos)
    throw std::invalid_argument("ZIP entry name '" + name + "': not a relative path");
  for (const Entry& entry : entries_)
    if (entry.name == name) throw std::invalid_argument("ZIP entry '" + name + "' added twice");
  const std::uint32_t offset = checked_size(data_.size(), "the archive");
  const std::uint32_t size = checked_size(bytes.size(), "ZIP entry '" + name + "'");
  const std::uint32_t crc = crc32(bytes);
  put32(data_, 0x04034b50);  // local file header
  put_common(data_, crc, size, name.size());
  put16(data_, 0);  // extra field length
  data_ += name;
  data_ += bytes;
  checked_size(data_.size(), "the archive");
  entries_.push_back({name, crc, size, offset});
}

std::string ZipWriter::finish() const {
  std::string out = data_;
  const std::uint32_t directory_offset = checked_size(out.size(), "the archive");
  for (const Entry& entry : entries_) {
    put32(out, 0x02014b50);  // central directory file header
    put16(out, kVersion);    // made by: MS-DOS attributes, version 2.0
    put_common(out, entry.crc, entry.size, entry.name.size());
    put16(out, 0);  // extra field length
    put16(out, 0);  // comment length
    put16(out, 0);  // disk number
    put16(out, 0);  // internal attributes
    put32(out, 0);  // external attributes
    put32(out, entry.offset);
    out += entry.name;
  }
  const std::uint32_t directory_size = checked_size(out.size() - directory_offset, "the archive");
  if (entries_.size() > 0xFFFF) throw std::invalid_argument("more than 65535 ZIP entries");
  put32(out, 0x06054b50);  // end of central directory
  put16(out, 0);
  put16(out, 0);
  put16(out, static_cast<std::uint16_t>(entries_.size()));
  put16(out, static_cast<std::uint16_t>(entries_.size()));
  put32(out, directory_size);
  put32(out, directory_offset);
  put16(out, 0);  // comment length
  return out;
}

}  // namespace kanegen::fmu
