// SPDX-License-Identifier: GPL-2.0-or-later
#include "model/expression_eval.hpp"

#include <stdexcept>
#include <utility>
#include <vector>

namespace kanegen::model {

ParameterValues default_parameter_values(const Model& model) {
  ParameterValues values;
  for (const Parameter& p : model.parameters) values[p.name] = p.value;
  return values;
}

double evaluate_expression(const std::string& text, const ParameterValues& parameters) {
  std::vector<std::string> names;
  for (const auto& entry : parameters) names.push_back(entry.first);
  ParsedExpression parsed = parse_expression(text, names);
  if (parsed.issue)
    throw std::invalid_argument("cannot evaluate expression '" + text + "' at column " +
                                std::to_string(parsed.issue->column) + ": " + parsed.issue->problem);
  // Without a variable every node folds: the root holds the value.
  return bind_expression(std::move(parsed.tree), parameters).nodes.back().value;
}

double evaluate(const Scalar& scalar, const ParameterValues& parameters) {
  return scalar.is_literal ? scalar.value : evaluate_expression(scalar.text, parameters);
}

}  // namespace kanegen::model
