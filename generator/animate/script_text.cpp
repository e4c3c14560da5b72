// SPDX-License-Identifier: GPL-2.0-or-later
#include "animate/script_text.hpp"

#include <algorithm>
#include <cctype>
#include <cstdio>

namespace kanegen::animate {
namespace {

/// The code point of the UTF-8 sequence at text[i] and its length, or
/// (-1, 1) for a byte that does not start a well-formed one.
std::pair<long, std::size_t> decode(std::string_view text, std::size_t i) {
  const unsigned char lead = static_cast<unsigned char>(text[i]);
  if (lead < 0x80) return {lead, 1};
  std::size_t length = 0;
  long code = 0, least = 0;
  if ((lead & 0xE0) == 0xC0)
    length = 2, code = lead & 0x1F, least = 0x80;
  else if ((lead & 0xF0) == 0xE0)
    length = 3, code = lead & 0x0F, least = 0x800;
  else if ((lead & 0xF8) == 0xF0)
    length = 4, code = lead & 0x07, least = 0x10000;
  else
    return {-1, 1};
  if (i + length > text.size()) return {-1, 1};
  for (std::size_t k = 1; k < length; ++k) {
    const unsigned char next = static_cast<unsigned char>(text[i + k]);
    if ((next & 0xC0) != 0x80) return {-1, 1};
    code = (code << 6) | (next & 0x3F);
  }
  if (code < least || code > 0x10FFFF || (code >= 0xD800 && code <= 0xDFFF)) return {-1, 1};
  return {code, length};
}

void append_escape(std::string& out, long code) {
  char buffer[16];
  std::snprintf(buffer, sizeof buffer, "\\u%04lx", code);
  out += buffer;
}

}  // namespace

std::string script_json_string(std::string_view text) {
  std::string out = "\"";
  for (std::size_t i = 0; i < text.size();) {
    const auto [code, length] = decode(text, i);
    if (code == '"')
      out += "\\\"";
    else if (code == '\\')
      out += "\\\\";
    else if (code == '\n')
      out += "\\n";
    else if (code == '\t')
      out += "\\t";
    else if (code < 0)
      out += "\xEF\xBF\xBD";  // U+FFFD in place of a byte that is not UTF-8
    else if (code < 0x20 || code == 0x7F || code == '<' || code == '>' || code == '&' || code == '\'' ||
             code == 0x2028 || code == 0x2029)
      append_escape(out, code);
    else
      out.append(text.substr(i, length));
    i += length;
  }
  return out + "\"";
}

bool script_safe(std::string_view code) {
  std::string lower(code);
  std::transform(lower.begin(), lower.end(), lower.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return lower.find("</script") == std::string::npos && lower.find("<!--") == std::string::npos;
}

}  // namespace kanegen::animate
