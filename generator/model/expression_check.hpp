// SPDX-License-Identifier: GPL-2.0-or-later
// Load-time check of scalar expressions ("m1*l1^2/12") without GiNaC, so a
// bad model fails before any symbolic work, with a caret under the culprit.
// The parser and the rules that keep the language a subset of what GiNaC
// reads with the same meaning are in expression.cpp.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "model/expression.hpp"

namespace kanegen::model {

/// Checks tokens, grammar and that every name is a parameter, a constant or
/// a function. Returns the first issue, or nothing.
std::optional<ExpressionIssue> check_expression(const std::string& text,
                                                const std::vector<std::string>& parameters);

/// The issue's problem followed by the expression and a caret line:
/// "unknown name 'm2' in expression\n  m1 + m2\n       ^".
std::string describe_with_caret(const std::string& text, const ExpressionIssue& issue);

}  // namespace kanegen::model
