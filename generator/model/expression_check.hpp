// SPDX-License-Identifier: GPL-2.0-or-later
// Load-time check of scalar expressions ("m1*l1^2/12") without GiNaC, so a
// bad model fails before any symbolic work, with a caret under the culprit.
// The accepted language is a subset of what GiNaC's parser reads with the
// same meaning; the rules that keep it so are in expression_check.cpp.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace kanegen::model {

/// Functions of one argument usable in expressions (all in GiNaC's parser table).
inline constexpr const char* kExpressionFunctions[] = {"sin", "cos", "tan", "sqrt", "exp", "log"};
/// Named constants; the generator maps "pi" to GiNaC::Pi.
inline constexpr const char* kExpressionConstants[] = {"pi"};

struct ExpressionIssue {
  std::size_t column = 0;  ///< byte offset into the text where the problem starts
  std::string problem;     ///< e.g. "unknown name 'm2' in expression"
  std::string fix;
};

/// Checks tokens, grammar and that every name is a parameter, a constant or
/// a function. Returns the first issue, or nothing.
std::optional<ExpressionIssue> check_expression(const std::string& text,
                                                const std::vector<std::string>& parameters);

/// The issue's problem followed by the expression and a caret line:
/// "unknown name 'm2' in expression\n  m1 + m2\n       ^".
std::string describe_with_caret(const std::string& text, const ExpressionIssue& issue);

}  // namespace kanegen::model
