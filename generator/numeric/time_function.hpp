// SPDX-License-Identifier: GPL-2.0-or-later
// A prescribed motion q(t) of the model language ("(Ws/Ts)*(t^2/2 + ...)")
// parsed once, with the parameters' values folded in, and evaluated over any
// scalar type: with Dual<Dual<double>> seeded along t it gives q, q' and q''
// exactly (the prescribed acceleration). The parser and the evaluator are the
// model's (model/expression.hpp), which includes nothing of GiNaC.
#pragma once

#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "model/expression.hpp"
#include "numeric/dual.hpp"

namespace kanegen::numeric {

class TimeFunction {
 public:
  TimeFunction() = default;
  /// Throws std::invalid_argument (naming the expression) on a syntax error
  /// or an unknown name. `variable` is the argument (the time, or x along a
  /// beam for an assumed mode); other names are parameters.
  TimeFunction(const std::string& text, const model::ParameterValues& parameters,
               const std::string& variable = "t")
      : tree_(parse(text, parameters, variable)) {}

  template <class S>
  S operator()(const S& t) const {
    return model::evaluate_tree(tree_, t);
  }

 private:
  static model::ExpressionTree parse(const std::string& text, const model::ParameterValues& parameters,
                                     const std::string& variable) {
    std::vector<std::string> names{variable};
    for (const auto& entry : parameters) names.push_back(entry.first);
    model::ParsedExpression parsed = model::parse_expression(text, names);
    if (parsed.issue)
      throw std::invalid_argument(
          "cannot read " + std::string(variable == "t" ? "prescribed motion" : "expression") + " '" + text +
          "' at column " + std::to_string(parsed.issue->column) + ": " + parsed.issue->problem);
    return model::bind_expression(std::move(parsed.tree), parameters, variable);
  }

  model::ExpressionTree tree_;  ///< bound: only the nodes that depend on t vary
};

}  // namespace kanegen::numeric
