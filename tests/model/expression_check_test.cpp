// SPDX-License-Identifier: GPL-2.0-or-later
// The load-time expression check: what it accepts GiNaC reads, and what it
// rejects is either invalid or read by GiNaC other than it looks.
#include "model/expression_check.hpp"

#include <ginac/ginac.h>

#include <catch2/catch.hpp>

using kanegen::model::check_expression;
using kanegen::model::describe_with_caret;

namespace {

const std::vector<std::string> kParameters{"m1", "l1", "a", "b", "c", "k_2"};

GiNaC::ex ginac_read(const std::string& text, GiNaC::symtab& table) {
  GiNaC::parser reader(table, /*strict=*/true);
  return reader(text);
}

GiNaC::symtab ginac_table() {
  GiNaC::symtab table;
  for (const std::string& p : kParameters) table[p] = GiNaC::symbol(p);
  table["pi"] = GiNaC::Pi;
  return table;
}

}  // namespace

TEST_CASE("accepted expressions are read by GiNaC", "[expression]") {
  GiNaC::symtab table = ginac_table();
  for (const std::string text : {"m1",
                                 "2",
                                 "0.5",
                                 ".5",
                                 "1e-3",
                                 "2.5E+2",
                                 "m1*l1^2/12",
                                 "-l1",
                                 "+l1",
                                 "-(a + b)",
                                 "a - b + c",
                                 "a/b/c",
                                 "sqrt(a^2 + b^2)",
                                 "sin(pi/6)*cos(a) - tan(b)",
                                 "exp(-a)",
                                 "log(2*a)",
                                 "(a^b)^c",
                                 "a^(b^c)",
                                 "a*(-b)",
                                 "a^(-2)",
                                 "  m1 *  l1 ",
                                 "k_2*a",
                                 "-a^2"}) {
    INFO(text);
    CHECK_FALSE(check_expression(text, kParameters).has_value());
    CHECK_NOTHROW(ginac_read(text, table));
  }
}

TEST_CASE("rejected expressions point at the culprit", "[expression]") {
  struct Case {
    const char* text;
    std::size_t column;
    const char* problem;
  };
  for (const Case& c : std::vector<Case>{
           {"m1 + m2", 5, "unknown name 'm2'"},
           {"", 0, "empty expression"},
           {"   ", 0, "empty expression"},
           {"a *", 3, "ends where an operand is expected"},
           {"(a + b", 0, "unclosed '('"},
           {"sqrt(a", 4, "unclosed '('"},
           {"a + b)", 5, "unmatched ')'"},
           {"2m1", 1, "malformed number"},
           {"1e", 0, "malformed number"},
           {"1.2.3", 3, "malformed number"},
           {"a**2", 1, "'**'"},
           {"a^b^c", 3, "chained '^'"},
           {"a*-b", 2, "sign right after an operator"},
           {"a^-2", 2, "sign right after an operator"},
           {"--a", 1, "sign right after an operator"},
           {"sin a", 0, "'sin' is a function"},
           {"a(b)", 1, "'a' is not a function"},
           {"pow(a, 2)", 0, "unknown name 'pow'"},
           {"sqrt(a, b)", 6, "','"},
           {"Pi", 0, "unknown name 'Pi'"},
           {"_a", 0, "unexpected '_'"},
           {"a # b", 2, "unexpected '#'"},
           {"a b", 2, "unexpected 'b' after a complete operand"},
           {"{a}", 0, "unexpected '{'"},
           {"\xc2\xb5", 0, "non-ASCII"},
       }) {
    INFO(c.text);
    const auto issue = check_expression(c.text, kParameters);
    REQUIRE(issue.has_value());
    CHECK(issue->column == c.column);
    CHECK_THAT(issue->problem, Catch::Contains(c.problem));
    CHECK_FALSE(issue->fix.empty());
  }
}

TEST_CASE("suggestions for misspelt names", "[expression]") {
  CHECK_THAT(check_expression("2*l", kParameters)->fix, Catch::Contains("did you mean 'l1'?"));
  CHECK_THAT(check_expression("sine(a)", kParameters)->fix, Catch::Contains("did you mean 'sin'?"));
  CHECK_THAT(check_expression("Pi", kParameters)->fix, Catch::Contains("did you mean 'pi'?"));
  CHECK_THAT(check_expression("zz", kParameters)->fix, Catch::Contains("define it under /parameters"));
}

TEST_CASE("the caret sits under the culprit", "[expression]") {
  const std::string text = "m1 + m2";
  CHECK(describe_with_caret(text, *check_expression(text, kParameters)) ==
        "unknown name 'm2' in expression\n  m1 + m2\n       ^");
}

TEST_CASE("why a sign after an operator is rejected: GiNaC's reading", "[expression]") {
  // GiNaC parses "a*-b+c" as a*(-b+c), not (a*(-b))+c as it looks.
  GiNaC::symtab table = ginac_table();
  const GiNaC::ex a = table["a"], b = table["b"], c = table["c"];
  CHECK((ginac_read("a*-b+c", table) - a * (-b + c)).expand().is_zero());
  CHECK_THROWS(ginac_read("a^b^c", table));
  // The accepted spellings mean what they say.
  CHECK((ginac_read("a*(-b)+c", table) - (-a * b + c)).expand().is_zero());
  CHECK((ginac_read("-a^2", table) + GiNaC::pow(a, 2)).is_zero());
  CHECK((ginac_read("a - b + c", table) - (a - b + c)).is_zero());
}
