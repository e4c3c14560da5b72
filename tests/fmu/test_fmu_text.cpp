// SPDX-License-Identifier: GPL-2.0-or-later
// The two pieces of kanegen fmu that untrusted text and every FMU pass through: the XML escaping of names
// (fmu/xml_text.hpp) and the ZIP writer with its CRC-32 (fmu/zip_writer.hpp); and the variables' units. The
// FMUs themselves are checked by tests/fmu/check_fmu.py (Python's zipfile and xml.etree read them back).
#include <catch2/catch.hpp>
#include <string>
#include <utility>
#include <vector>

#include "fmu/fmu_variables.hpp"
#include "fmu/xml_text.hpp"
#include "fmu/zip_writer.hpp"
#include "model/model.hpp"

using kanegen::fmu::crc32;
using kanegen::fmu::xml_attribute;
using kanegen::fmu::XmlTextError;
using kanegen::fmu::ZipWriter;

TEST_CASE("xml_attribute escapes markup, quotes and the white space that attribute values normalize") {
  CHECK(xml_attribute("plain_name.x", "n") == "plain_name.x");
  CHECK(xml_attribute("a&b", "n") == "a&amp;b");
  CHECK(xml_attribute("<tag>", "n") == "&lt;tag&gt;");
  CHECK(xml_attribute("say \"hi\"", "n") == "say &quot;hi&quot;");
  CHECK(xml_attribute("it's", "n") == "it&apos;s");
  CHECK(xml_attribute("]]>", "n") == "]]&gt;");
  CHECK(xml_attribute("a\tb\nc\rd", "n") == "a&#9;b&#10;c&#13;d");
  CHECK(xml_attribute("&amp;", "n") == "&amp;amp;");  // an entity in a name is text, escaped again
  CHECK(xml_attribute("", "n").empty());
}

TEST_CASE("xml_attribute keeps UTF-8 and refuses what XML 1.0 cannot carry, naming the place") {
  const std::string utf8 = "\xC3\xA9 \xE4\xB8\xAD \xF0\x9F\x98\x80";  // é 中 😀
  CHECK(xml_attribute(utf8, "n") == utf8);
  for (const std::string& bad :
       {std::string("a\x01"), std::string(1, '\0'), std::string("\x1B[0m"), std::string("\x7F")})
    CHECK_THROWS_WITH(xml_attribute(bad, "the output name 'y'"),
                      Catch::Contains("the output name 'y'") && Catch::Contains("control character"));
  for (const std::string& bad :
       {std::string("\xC3"), std::string("\xC0\xAF"), std::string("\xED\xA0\x80"),
        std::string("\xF4\x90\x80\x80"), std::string("\xEF\xBF\xBF"), std::string("\xFF")})
    CHECK_THROWS_WITH(xml_attribute("x" + bad, "the parameter name"),
                      Catch::Contains("the parameter name") && Catch::Contains("not UTF-8"));
  CHECK_THROWS_AS(xml_attribute("\x01", "n"), XmlTextError);
}

TEST_CASE("crc32 is ZIP's CRC-32") {
  CHECK(crc32("") == 0u);
  CHECK(crc32("123456789") == 0xCBF43926u);  // the check value of CRC-32/ISO-HDLC
  CHECK(crc32("The quick brown fox jumps over the lazy dog") == 0x414FA339u);
}

namespace {
std::uint32_t u32(const std::string& s, std::size_t at) {
  std::uint32_t v = 0;
  for (int i = 3; i >= 0; --i) v = (v << 8) | static_cast<unsigned char>(s[at + static_cast<std::size_t>(i)]);
  return v;
}
}  // namespace

TEST_CASE("ZipWriter writes stored entries, a central directory and its end record") {
  ZipWriter zip;
  zip.add("modelDescription.xml", "<x/>");
  zip.add("sources/a.cpp", "int a;\n");
  const std::string bytes = zip.finish();
  CHECK(u32(bytes, 0) == 0x04034b50u);        // the first local header
  const std::size_t end = bytes.size() - 22;  // no archive comment
  CHECK(u32(bytes, end) == 0x06054b50u);
  CHECK(static_cast<unsigned char>(bytes[end + 10]) == 2);  // entries
  const std::uint32_t directory = u32(bytes, end + 16);
  CHECK(u32(bytes, directory) == 0x02014b50u);
  CHECK(u32(bytes, directory + 16) == crc32("<x/>"));
  CHECK(zip.finish() == bytes);  // deterministic
  CHECK_THROWS_AS(zip.add("sources/a.cpp", ""), std::invalid_argument);
  for (const char* bad : {"", "/etc/passwd", "../x", "a/../../x", "a\\b"})
    CHECK_THROWS_AS(zip.add(bad, ""), std::invalid_argument);
}

TEST_CASE("add_units reads each coordinate's, speed's and input's unit from its joint type's row") {
  using kanegen::model::JointType;
  kanegen::model::Model model;
  for (const auto& [name, type] :
       {std::pair{"hinge", JointType::revolute}, std::pair{"rail", JointType::prismatic},
        std::pair{"ball", JointType::spherical}}) {
    kanegen::model::Joint joint;
    joint.name = name;
    joint.type = type;
    model.joints.push_back(joint);
  }
  // q: the speeds' coordinates first (a quaternion's x, y, z among them), the elastic ones, then the w.
  kanegen::fmu::ModelFacts facts;
  facts.coordinates = {"hinge", "rail", "ball_qx", "ball_qy", "ball_qz", "arm.e1", "ball_qw"};
  facts.coordinate_joints = {"hinge", "rail", "ball", "ball", "ball", "", "ball"};
  facts.speeds = {"hinge_dot", "rail_dot", "ball_wx", "ball_wy", "ball_wz", "arm.e1_dot"};
  facts.inputs = {"hinge_tau", "rail_tau", "ball_mx"};
  kanegen::fmu::add_units(model, facts);
  CHECK(facts.coordinate_units == std::vector<std::string>{"rad", "m", "", "", "", "", ""});
  CHECK(facts.speed_units == std::vector<std::string>{"rad/s", "m/s", "rad/s", "rad/s", "rad/s", ""});
  CHECK(facts.input_units == std::vector<std::string>{"N.m", "N", ""});

  facts.q0.assign(facts.coordinates.size(), 0.0);
  facts.u0.assign(facts.speeds.size(), 0.0);
  const kanegen::fmu::FmuVariables variables = kanegen::fmu::fmu_variables(facts);
  const auto unit_of = [&](const std::string& name) {
    for (const kanegen::fmu::Variable& v : variables.all)
      if (v.name == name) return v.unit;
    FAIL("no variable " << name);
    return std::string();
  };
  CHECK(unit_of("rail") == "m");
  CHECK(unit_of("der(rail)") == "m/s");
  CHECK(unit_of("der(rail_dot)") == "m/s2");
  CHECK(unit_of("ball_wz") == "rad/s");
  CHECK(unit_of("der(ball_wz)") == "rad/s2");
  CHECK(unit_of("der(ball_qw)").empty());
  CHECK(unit_of("arm.e1_dot").empty());
}
