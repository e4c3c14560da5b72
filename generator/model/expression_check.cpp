// SPDX-License-Identifier: GPL-2.0-or-later
#include "model/expression_check.hpp"

#include <algorithm>

namespace kanegen::model {

std::optional<ExpressionIssue> check_expression(const std::string& text,
                                                const std::vector<std::string>& parameters) {
  return parse_expression(text, parameters).issue;
}

std::string describe_with_caret(const std::string& text, const ExpressionIssue& issue) {
  // Tabs, newlines and other control characters would misplace the caret
  // or break the line; show them as spaces.
  std::string shown = text;
  std::replace_if(
      shown.begin(), shown.end(),
      [](char c) { return static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) == 0x7f; },
      ' ');
  return issue.problem + "\n  " + shown + "\n  " + std::string(std::min(issue.column, shown.size()), ' ') +
         "^";
}

}  // namespace kanegen::model
