// SPDX-License-Identifier: GPL-2.0-or-later
// script_json_string and script_safe (animate/script_text.hpp): what keeps
// model and column names from ending the viewer page's <script> elements.
// The reference reading is nlohmann-json's parser, not ours.
#include "animate/script_text.hpp"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "model/load.hpp"

using kanegen::animate::script_json_string;
using kanegen::animate::script_safe;

namespace {

/// What a browser could misread in a <script> element's text, or a JS
/// parser in a string: none of it may appear.
void check_inert(const std::string& literal) {
  CAPTURE(literal);
  CHECK(script_safe(literal));
  for (const char* bad : {"<", ">", "&", "'", "\n", "\r", "\xE2\x80\xA8", "\xE2\x80\xA9"})
    CHECK(literal.find(bad) == std::string::npos);
}

std::string decoded(const std::string& literal) { return nlohmann::json::parse(literal).get<std::string>(); }

}  // namespace

TEST_CASE("script_json_string: a plain name is a JSON string of itself") {
  CHECK(script_json_string("link2") == "\"link2\"");
  CHECK(script_json_string("") == "\"\"");
}

TEST_CASE("script_json_string: markup and line terminators become \\u escapes") {
  CHECK(script_json_string("</script>") == "\"\\u003c/script\\u003e\"");
  CHECK(script_json_string("<!--") == "\"\\u003c!--\"");
  CHECK(script_json_string("a & 'b'") == "\"a \\u0026 \\u0027b\\u0027\"");
  CHECK(script_json_string("\"q\" \\") == "\"\\\"q\\\" \\\\\"");
  CHECK(script_json_string("a\nb\tc\r\x01\x7f") == "\"a\\nb\\tc\\u000d\\u0001\\u007f\"");
  CHECK(script_json_string("\xE2\x80\xA8\xE2\x80\xA9") == "\"\\u2028\\u2029\"");
  for (const std::string hostile : {"</script><script>alert(1)</script>", "</SCRIPT >", "<!-- <script>",
                                    "]]> --> <!-- x", "\xE2\x80\xA8 // ", "${x}`"}) {
    check_inert(script_json_string(hostile));
    CHECK(decoded(script_json_string(hostile)) == hostile);
  }
}

TEST_CASE("script_json_string: UTF-8 is kept, bytes that are not UTF-8 become U+FFFD") {
  CHECK(script_json_string("\xC3\xA9 \xE4\xB8\xAD \xF0\x9F\x98\x80") ==
        "\"\xC3\xA9 \xE4\xB8\xAD \xF0\x9F\x98\x80\"");
  const std::string replacement = "\xEF\xBF\xBD";
  CHECK(script_json_string("a\xFF"
                           "b") == "\"a" + replacement + "b\"");
  CHECK(script_json_string("\xC0\xAF") == "\"" + replacement + replacement + "\"");  // overlong '/'
  CHECK(script_json_string("\xED\xA0\x80") ==
        "\"" + replacement + replacement + replacement + "\"");                      // a surrogate
  CHECK(script_json_string("\xE4\xB8") == "\"" + replacement + replacement + "\"");  // cut short
  CHECK(script_json_string("\xF4\x90\x80\x80").find("\xF4") == std::string::npos);   // past U+10FFFF
  CHECK_NOTHROW(decoded(script_json_string("\xC0<\xFF\xFE</script>")));
}

TEST_CASE("script_json_string: the names of tests/data/models/hostile_names.urdf come back byte for byte") {
  const kanegen::model::Model m =
      kanegen::model::load_model(KANEGEN_SOURCE_DIR "/tests/data/models/hostile_names.urdf");
  std::vector<std::string> names{m.name, m.ground};
  for (const auto& b : m.bodies) names.push_back(b.name);
  for (const auto& j : m.joints) names.push_back(j.name);
  REQUIRE(names.size() == 6);
  for (const std::string& name : names) {
    const std::string literal = script_json_string(name);
    check_inert(literal);
    CHECK(decoded(literal) == name);
  }
}

TEST_CASE("script_safe: what would end a script element or start a comment in it") {
  CHECK(script_safe("if (a < b && c > d) x = '<' + '/';"));
  CHECK_FALSE(script_safe("x = '</script>'"));
  CHECK_FALSE(script_safe("x = '</ScRiPt'"));
  CHECK_FALSE(script_safe("<!-- old"));
}
