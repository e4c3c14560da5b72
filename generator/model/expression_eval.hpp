// SPDX-License-Identifier: GPL-2.0-or-later
// Numeric value of a model Scalar at given parameter values, without GiNaC:
// for the independent numeric derivation (kanegen verify), which must not
// share code with the symbolic path beyond the parsed model. The parser is
// the load-time check's (expression.hpp), with GiNaC's meaning (a leading
// sign applies to the first term, '^' binds tighter than a sign: -a^2 = -(a^2)).
#pragma once

#include <string>

#include "model/expression.hpp"
#include "model/model.hpp"

namespace kanegen::model {

/// The defaults of the model's parameters.
ParameterValues default_parameter_values(const Model& model);

/// Evaluates an expression such as "m1*l1^2/12". Throws std::invalid_argument
/// (naming the expression) on a syntax error or an unknown name; expressions
/// of a loaded model have been checked already.
double evaluate_expression(const std::string& text, const ParameterValues& parameters);

/// The value of a Scalar: the literal, or its expression evaluated.
double evaluate(const Scalar& scalar, const ParameterValues& parameters);

}  // namespace kanegen::model
