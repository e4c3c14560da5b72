// SPDX-License-Identifier: GPL-2.0-or-later
#include "fmu/xml_text.hpp"

#include <cstdio>

namespace kanegen::fmu {

namespace {

std::string byte_text(unsigned char c) {
  char buffer[8];
  std::snprintf(buffer, sizeof buffer, "0x%02X", c);
  return buffer;
}

/// The length of the UTF-8 sequence that starts at text[at], or 0 if it is not one (overlong forms,
/// surrogates and code points past U+10FFFF are not UTF-8 either).
std::size_t utf8_length(const std::string& text, std::size_t at) {
  const auto byte = [&](std::size_t i) { return static_cast<unsigned char>(text[i]); };
  const unsigned char c = byte(at);
  std::size_t length = c >= 0xF0 ? 4 : c >= 0xE0 ? 3 : c >= 0xC2 ? 2 : 0;
  if (c >= 0xF5 || length == 0 || at + length > text.size()) return 0;
  for (std::size_t i = 1; i < length; ++i)
    if ((byte(at + i) & 0xC0) != 0x80) return 0;
  const unsigned char next = byte(at + 1);
  if (c == 0xE0 && next < 0xA0) return 0;                           // overlong
  if (c == 0xED && next >= 0xA0) return 0;                          // surrogate
  if (c == 0xF0 && next < 0x90) return 0;                           // overlong
  if (c == 0xF4 && next >= 0x90) return 0;                          // past U+10FFFF
  if (c == 0xEF && next == 0xBF && byte(at + 2) >= 0xBE) return 0;  // U+FFFE, U+FFFF: not XML characters
  return length;
}

}  // namespace

std::string xml_attribute(const std::string& text, const std::string& what) {
  std::string out;
  out.reserve(text.size());
  for (std::size_t at = 0; at < text.size();) {
    const auto c = static_cast<unsigned char>(text[at]);
    if (c >= 0x80) {
      const std::size_t length = utf8_length(text, at);
      if (length == 0)
        throw XmlTextError(what + " is not UTF-8 (byte " + byte_text(c) + " at offset " + std::to_string(at) +
                           "); FMI's modelDescription.xml is UTF-8: rename it in the model file");
      out.append(text, at, length);
      at += length;
      continue;
    }
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&apos;";
        break;
      case '\t':
        out += "&#9;";
        break;
      case '\n':
        out += "&#10;";
        break;
      case '\r':
        out += "&#13;";
        break;
      default:
        if (c < 0x20 || c == 0x7F)
          throw XmlTextError(what + " holds the control character " + byte_text(c) + " at offset " +
                             std::to_string(at) +
                             ", which XML 1.0 cannot carry; rename it in the model file");
        out += static_cast<char>(c);
    }
    ++at;
  }
  return out;
}

}  // namespace kanegen::fmu
