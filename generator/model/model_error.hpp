// SPDX-License-Identifier: GPL-2.0-or-later
// The one error type of model loading: it names the file, the place in it
// and what to do, so every bad input ends in one clear line.
#pragma once

#include <stdexcept>
#include <string>

namespace kanegen::model {

class ModelError : public std::runtime_error {
 public:
  /// file: the model file; place: a JSON pointer ("/joints/2/axis"), an URDF
  /// element ("<joint name=\"j1\">/axis") or an expression with a caret;
  /// problem: what is wrong; fix: how to fix it.
  ModelError(std::string file, std::string place, std::string problem, std::string fix)
      : std::runtime_error(printable(file) + ": " + (place.empty() ? std::string("/") : printable(place)) +
                           ": " + printable_problem(problem) +
                           (fix.empty() ? std::string() : "; " + printable(fix))),
        file_(std::move(file)),
        place_(std::move(place)) {}

  const std::string& file() const { return file_; }
  const std::string& place() const { return place_; }

  /// Text of the file quoted in a message with its control characters
  /// written as JSON escapes ("\u0000", "\u000a"), so that the message is
  /// one readable line (a NUL would cut it short, a newline split it).
  static std::string printable(const std::string& text) {
    std::string out;
    for (const char c : text) {
      const auto byte = static_cast<unsigned char>(c);
      if (byte >= 0x20 && byte != 0x7f) {
        out += c;
      } else {
        const char* hex = "0123456789abcdef";
        out += std::string("\\u00") + hex[byte >> 4] + hex[byte & 15];
      }
    }
    return out;
  }

  /// The problem, printable; an expression shown with a caret under the
  /// culprit (describe_with_caret: "...\n  TEXT\n  ^") keeps its two lines.
  static std::string printable_problem(const std::string& problem) {
    const auto last = problem.rfind('\n');
    const auto middle =
        last == std::string::npos || last == 0 ? std::string::npos : problem.rfind('\n', last - 1);
    if (middle != std::string::npos) {
      const std::string text = problem.substr(middle + 1, last - middle - 1);
      const std::string caret = problem.substr(last + 1);
      const bool shown = text.rfind("  ", 0) == 0 && text.find('\n') == std::string::npos &&
                         caret.size() >= 3 && caret.back() == '^' &&
                         caret.find_first_not_of(' ') == caret.size() - 1;
      if (shown) return printable(problem.substr(0, middle)) + "\n" + printable(text) + "\n" + caret;
    }
    return printable(problem);
  }

 private:
  std::string file_;
  std::string place_;
};

}  // namespace kanegen::model
