// SPDX-License-Identifier: GPL-2.0-or-later
// The one expression parser (model/expression.hpp) and its evaluator over
// doubles and dual numbers; the check's messages are in expression_check_test.
#include "model/expression.hpp"

#include <catch2/catch.hpp>
#include <cmath>
#include <stdexcept>

#include "model/expression_eval.hpp"
#include "numeric/dual.hpp"

using kanegen::model::bind_expression;
using kanegen::model::evaluate_tree;
using kanegen::model::ExpressionTree;
using kanegen::model::ParameterValues;
using kanegen::model::parse_expression;

namespace {

/// The text parsed over `values` and t, bound with t as the variable.
ExpressionTree bound(const std::string& text, const ParameterValues& values) {
  std::vector<std::string> names{"t"};
  for (const auto& entry : values) names.push_back(entry.first);
  auto parsed = parse_expression(text, names);
  REQUIRE_FALSE(parsed.issue.has_value());
  return bind_expression(std::move(parsed.tree), values, "t");
}

}  // namespace

TEST_CASE("parsed expressions evaluate with GiNaC's reading", "[expression]") {
  const ParameterValues p{{"a", 1.5}, {"b", 4.0}, {"m1", 3.0}};
  const auto at = [&](const std::string& text) { return evaluate_tree(bound(text, p), 0.0); };
  CHECK(at("-a^2") == -2.25);
  CHECK(at("-a*b + m1") == -3.0);
  CHECK(at("b/m1/2") == Approx(2.0 / 3.0));
  CHECK(at("(a^2)^0.5") == 1.5);
  CHECK(at("2*pi") == 2 * 3.14159265358979323846);
  CHECK(at(" .5 + 1e-3 + 2E+1 ") == Approx(20.501));
}

TEST_CASE("bound trees fold everything but the variable", "[expression]") {
  const ExpressionTree constant = bound("a*sqrt(b)", {{"a", 2.0}, {"b", 9.0}});
  CHECK_FALSE(constant.nodes.back().varies);
  CHECK(constant.nodes.back().value == 6.0);

  const ExpressionTree motion = bound("a*t^2 + b", {{"a", 2.0}, {"b", 9.0}});
  CHECK(motion.nodes.back().varies);
  CHECK(evaluate_tree(motion, 3.0) == 27.0);

  auto parsed = parse_expression("a + c", {"a", "c"});
  REQUIRE_FALSE(parsed.issue.has_value());
  CHECK_THROWS_AS(bind_expression(parsed.tree, {{"a", 1.0}}), std::out_of_range);
}

TEST_CASE("dual numbers give exact derivatives along the variable", "[expression]") {
  using D = kanegen::numeric::Dual<double>;
  using DD = kanegen::numeric::Dual<D>;
  const ExpressionTree f = bound("w*t^3 + sin(t) + 2^t", {{"w", 2.0}});
  const double t = 0.5;
  const DD seeded(D(t, 1.0), D(1.0, 0.0));
  const DD r = evaluate_tree(f, seeded);
  CHECK(r.v.v == Approx(2 * t * t * t + std::sin(t) + std::pow(2.0, t)));
  CHECK(r.v.d == Approx(6 * t * t + std::cos(t) + std::log(2.0) * std::pow(2.0, t)));
  CHECK(r.d.d == Approx(12 * t - std::sin(t) + std::log(2.0) * std::log(2.0) * std::pow(2.0, t)));
  CHECK(evaluate_tree(f, D(t, 1.0)).d == Approx(r.v.d));
}

TEST_CASE("parse issues point at the culprit", "[expression]") {
  const std::vector<std::string> names{"a", "b"};
  struct Case {
    const char* text;
    std::size_t column;
    const char* problem;
  };
  const Case cases[] = {
      {"a + c", 4, "unknown name 'c' in expression"},
      {"a*-b", 2, "sign right after an operator in expression"},
      {"(a + 1", 0, "unclosed '(' in expression"},
      {"a^b^2", 3, "chained '^' in expression"},
      {"2^5000", 2, "exponent 5000 out of range in expression"},
      {"1e400", 0, "number '1e400' is too large for a double in expression"},
      {"a +", 3, "expression ends where an operand is expected"},
      {"   ", 0, "empty expression"},
  };
  for (const Case& c : cases) {
    INFO(c.text);
    const auto parsed = parse_expression(c.text, names);
    REQUIRE(parsed.issue.has_value());
    CHECK(parsed.issue->column == c.column);
    CHECK(parsed.issue->problem == c.problem);
    CHECK(parsed.tree.nodes.empty());
  }
}

TEST_CASE("evaluate_expression names the expression and the column", "[expression]") {
  using kanegen::model::evaluate_expression;
  CHECK(evaluate_expression("a*(b - 1)", {{"a", 2.0}, {"b", 4.0}}) == 6.0);
  CHECK_THROWS_WITH(evaluate_expression("a + c", {{"a", 1.0}}),
                    "cannot evaluate expression 'a + c' at column 4: unknown name 'c' in expression");
}
