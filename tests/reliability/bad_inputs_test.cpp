// SPDX-License-Identifier: GPL-2.0-or-later
// Bad inputs added with the reliability work (tests/data/bad_models and the
// fuzzers' findings): each fails with one ModelError naming the file, the
// exact place and a fix.
#include <catch2/catch.hpp>
#include <string>

#include "model/expression_check.hpp"
#include "model/model_error.hpp"
#include "test_support.hpp"

using kanegen::model::ModelError;
using kanegen::model::test::bad_model;
using kanegen::model::test::expect_model_error;
using kanegen::model::test::source_path;

TEST_CASE("bad model: an expression naming a parameter that is never defined", "[bad][expression]") {
  expect_model_error(bad_model("undefined_parameter.json"), "/bodies/0/com/2",
                     "unknown name 'length' in expression\n  -length/2\n   ^",
                     "define it under /parameters or fix the spelling");
}

TEST_CASE("bad model: a parameter without a value", "[bad][json]") {
  expect_model_error(bad_model("parameter_without_value.json"), "/parameters/l",
                     "wrong type: expected a number, found null", "write a number");
}

TEST_CASE("bad model: an expression that is NaN at the default parameter values", "[bad][expression]") {
  expect_model_error(bad_model("expression_nan.json"), "/bodies/0/com/2",
                     "expression '-sqrt(l - 2)' is not a real number (NaN) at the parameters' default values",
                     "the square root or logarithm of a negative number");
}

TEST_CASE("bad model: an expression that is infinite at the default parameter values", "[bad][expression]") {
  expect_model_error(bad_model("expression_infinite.json"), "/joints/0/spring/stiffness",
                     "expression '1/l' is infinite at the parameters' default values", "a division by zero");
}

TEST_CASE("bad URDF: joints forming a cycle", "[bad][urdf]") {
  expect_model_error(bad_model("cycle.urdf"), "line 18: <joint name=\"j2\">/parent",
                     "joints form a cycle: a -> b -> a", "must end at the root link");
}

TEST_CASE("bad URDF: a link that is its own parent", "[bad][urdf]") {
  expect_model_error(bad_model("self_parent.urdf"), "line 11: <joint name=\"j2\">/child",
                     "joint 'j2' connects link 'a' to itself", "give it another parent link");
}

TEST_CASE("bad URDF: a link with two parent joints", "[bad][urdf]") {
  expect_model_error(bad_model("two_parents.urdf"), "line 18: <joint name=\"j3\">/child",
                     "link 'b' is already the child of joint 'j2' (line 14)", "remove one of the joints");
}

TEST_CASE("fuzz finding: a name the two XML readers read differently", "[bad][urdf]") {
  expect_model_error(source_path("tests/data/fuzz_regressions/urdf/ampersand_in_name.urdf"),
                     "line 21: <joint name=\"hinge&\">/name", "urdfdom reads this name differently",
                     "write names without '&'");
}

TEST_CASE("fuzz finding: control characters in a message are escaped", "[bad][json]") {
  // A key with a NUL cut the message short; a newline would split it.
  const std::string file = source_path("tests/data/fuzz_regressions/json/nul_in_key.json");
  try {
    kanegen::model::load_model(file);
    FAIL("no error");
  } catch (const ModelError& e) {
    CHECK(std::string(e.what()) ==
          file + ": /joints/1/typ\\u0000e: unknown key 'typ\\u0000e'; did you mean 'type'?");
  }
  CHECK(std::string(ModelError("f", "a\nb", "x\ty", "z\n").what()) == "f: a\\u000ab: x\\u0009y; z\\u000a");
  // The expression and its caret keep their lines.
  const std::string caret =
      kanegen::model::describe_with_caret("a +\n b", *kanegen::model::check_expression("a +\n b", {"a"}));
  CHECK(std::string(ModelError("f", "/p", caret, "fix").what()) ==
        "f: /p: unknown name 'b' in expression\n  a +  b\n       ^; fix");
}

TEST_CASE("fuzz finding: a malformed XML message stays on one line", "[bad][urdf]") {
  const std::string file = source_path("tests/data/fuzz_regressions/urdf/multiline_xml_error.urdf");
  try {
    kanegen::model::load_model(file);
    FAIL("no error");
  } catch (const ModelError& e) {
    const std::string message = e.what();
    INFO(message);
    CHECK(message.find('\n') == std::string::npos);
    CHECK_THAT(message, Catch::Contains("malformed or misplaced <?...?> declaration"));
    CHECK(message.size() < 300);
  }
}

TEST_CASE("fuzz finding: numbers in expressions stay within the range of doubles", "[bad][expression]") {
  // GiNaC reads numbers exactly: it did not finish 5555e-5555555555555555555555.
  using kanegen::model::check_expression;
  struct Case {
    std::string text;
    const char* problem;
    std::size_t column;
  };
  for (const Case& c : {Case{"5555e-5555555555555555555555", "exponent of number", 0},
                        Case{"a*0e-9999", "exponent of number '0e-9999' out of range", 2},
                        Case{"2*1e400", "number '1e400' is too large for a double", 2},
                        Case{"1e-400 + a", "number '1e-400' is too small for a double (it would be 0)", 0},
                        Case{"1" + std::string(400, '0'), "is too large for a double", 0}}) {
    INFO(c.text);
    const auto issue = check_expression(c.text, {"a"});
    REQUIRE(issue.has_value());
    CHECK_THAT(issue->problem, Catch::Contains(c.problem));
    CHECK(issue->column == c.column);
    CHECK_THAT(issue->fix, Catch::Contains("doubles reach from about 1e-308 to 1e308"));
  }
  for (const char* text : {"4.9e-324", "1.7e308", "0e-400", "2.5E-3", "000000000001e-3"}) {
    INFO(text);
    CHECK_FALSE(check_expression(text, {}).has_value());
  }
}
