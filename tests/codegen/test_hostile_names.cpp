// SPDX-License-Identifier: GPL-2.0-or-later
// Untrusted names in every field of the generated code that carries text:
// tests/data/models/hostile_names.urdf names its joints and links with
// backslashes, quotes, trigraph starts, comment ends, directives, template
// keys and UTF-8. The model is generated and compiled at build time with
// -Werror (under clang++ in CI's sanitizer part too); here the compiled
// arrays must give back the names byte for byte, as written below by hand
// (trigraph starts as "?\?" so that this file has none either).
#include <catch2/catch.hpp>
#include <string>
#include <vector>

#include "codegen/cpp_text.hpp"
#include "hostile_names_.hpp"

namespace {

namespace m = kanegen_models::hostile_names_;

const std::string kJoint1 = "back\\slash \"quoted\" ?\?/ */ end\\";
// U+00E9, U+4E2D, U+1F600 in UTF-8, then a trigraph start, a template key, a comment and a directive.
const std::string kJoint2 = "\xc3\xa9 \xe4\xb8\xad \xf0\x9f\x98\x80 ?\?= {{MODEL_NAME}} // #include <cstdio>";
const std::string kUpper = "upper\\", kLower = "lower ?\?' \\n";

std::vector<std::string> strings(const char* const* array, int n) { return {array, array + n}; }

}  // namespace

TEST_CASE("hostile names come back byte for byte from every compiled name array", "[codegen][security]") {
  REQUIRE(m::NQ == 2);
  CHECK(std::string(m::System::name) ==
        "hostile_names_");  // the robot name "hostile names!" as an identifier
  CHECK(strings(m::coordinate_names, 2) == std::vector<std::string>{kJoint1, kJoint2});
  CHECK(strings(m::speed_names, 2) == std::vector<std::string>{kJoint1 + "_dot", kJoint2 + "_dot"});
  CHECK(strings(m::input_names, 2) == std::vector<std::string>{kJoint1 + "_tau", kJoint2 + "_tau"});
  CHECK(strings(m::coordinate_joints, 2) == std::vector<std::string>{kJoint1, kJoint2});
  CHECK(strings(m::moved_bodies, m::moved_bodies_first[2]) ==
        std::vector<std::string>{kUpper, kLower, kLower});
  // The kernels still compute: the lower link hangs 1 m below the upper one.
  double M[4];
  const double q[2] = {0, 0};
  m::mass_matrix({}, q, M);
  CHECK(M[3] == Approx(0.1 + 0.25));  // I_yy + m (0.5)^2 of the lower link about its joint
}

TEST_CASE("cpp_string_literal escapes what C++ would read otherwise", "[codegen][security]") {
  using kanegen::codegen::cpp_string_literal;
  CHECK(cpp_string_literal("joint_1") == "\"joint_1\"");
  CHECK(cpp_string_literal("a\"b\\c") == "\"a\\\"b\\\\c\"");
  CHECK(cpp_string_literal("a\nb\rc\td") == "\"a\\012b\\015c\\011d\"");
  CHECK(cpp_string_literal(std::string("a\0b", 3)) == "\"a\\000b\"");
  CHECK(cpp_string_literal("\x1b[31m") == "\"\\033[31m\"");
  CHECK(cpp_string_literal("?\?/?\?=???") == "\"?\\?/?\\?=?\\?\\?\"");
  CHECK(cpp_string_literal("*/ /*") == "\"*\\057 /*\"");
  // An octal escape takes at most three digits, so a digit after one stays a digit.
  CHECK(cpp_string_literal("\xc3\xa9"
                           "1") == "\"\\303\\2511\"");
  CHECK(cpp_string_literal("\xff\x7f") == "\"\\377\\177\"");
}

TEST_CASE("cpp_comment_text keeps plain words and quotes everything else", "[codegen][security]") {
  using kanegen::codegen::cpp_comment_text;
  CHECK(cpp_comment_text("arm7.urdf") == "arm7.urdf");
  CHECK(cpp_comment_text("my model, v2-final+.json") == "my model, v2-final+.json");
  for (const std::string hostile : {"a\n#include <x>", "end\\", "*/ int x; /*", "?\?/", "a\rb", ""}) {
    const std::string text = cpp_comment_text(hostile);
    INFO(text);
    CHECK(text.front() == '"');
    CHECK(text.back() == '"');  // so no backslash ends the comment's line and splices the next
    CHECK(text.find('\n') == std::string::npos);
    CHECK(text.find('\r') == std::string::npos);
    CHECK(text.find("*/") == std::string::npos);
    CHECK(text.find("??") == std::string::npos);
  }
}

TEST_CASE("only identifiers are printed as identifiers, and only printable ASCII is emitted",
          "[codegen][security]") {
  using kanegen::codegen::check_emitted_text;
  using kanegen::codegen::cpp_identifier;
  CHECK(cpp_identifier("arm7") == "arm7");
  CHECK_THROWS_AS(cpp_identifier("a b"), std::logic_error);
  CHECK_THROWS_AS(cpp_identifier("x;system"), std::logic_error);
  CHECK_THROWS_AS(cpp_identifier("class"), std::logic_error);
  CHECK_THROWS_AS(cpp_identifier(""), std::logic_error);
  CHECK_NOTHROW(check_emitted_text("m.cpp", "int x = 1;  // ok\n"));
  CHECK_THROWS_AS(check_emitted_text("m.cpp", "// a\rb\n"), std::logic_error);
  CHECK_THROWS_AS(check_emitted_text("m.cpp", "const char* s = \"\xc3\xa9\";\n"), std::logic_error);
  CHECK_THROWS_AS(check_emitted_text("m.cpp", std::string("x\0y", 3)), std::logic_error);
}
