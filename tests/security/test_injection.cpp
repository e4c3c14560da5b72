// SPDX-License-Identifier: GPL-2.0-or-later
// No text of a model file becomes code (docs/errors.md#security). Each URDF
// below carries odd names (the security issue's `j1&#10;#include
// &lt;/etc/shadow&gt;` and variants); `kanegen generate` must either refuse it
// (exit status 2, one line naming the file and a place) or write code that
// g++ accepts and that, preprocessed, has the very tokens of the same model
// with plain placeholder names, but for string literals: a name that ended a
// literal or a comment, or started a directive, would add or change tokens.
// The names that are accepted must come back exactly as CSV columns of
// `kanegen simulate` (RFC 4180 quoting).
#include <algorithm>
#include <catch2/catch.hpp>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "fuzz/generated_code.hpp"
#include "support/run_kanegen.hpp"

namespace {

namespace fs = std::filesystem;
using kanegen_test::Result;

const std::string kRuntimeInclude = KANEGEN_SOURCE_DIR "/runtime/include";

/// A chain of continuous joints: joints[i] carries links[i + 1] on links[i]
/// (links[0] is the ground). Names are the text the loader should read, or,
/// for `raw`, the attribute text as written in the file.
struct Chain {
  std::string robot;
  std::vector<std::string> links, joints;
  bool raw = false;
};

/// The name as a double-quoted XML attribute: markup characters and control
/// characters as character references, other bytes (UTF-8) as they are.
std::string attribute(const std::string& name, bool raw) {
  if (raw) return "\"" + name + "\"";
  std::string out = "\"";
  for (const char c : name) {
    const auto b = static_cast<unsigned char>(c);
    if (c == '&' || c == '<' || c == '"' || b < 0x20)
      out += "&#" + std::to_string(b) + ";";
    else
      out += c;
  }
  return out + "\"";
}

std::string urdf(const Chain& c) {
  const auto a = [&](const std::string& name) { return attribute(name, c.raw); };
  std::string text =
      "<?xml version=\"1.0\"?>\n<robot name=" + a(c.robot) + ">\n  <link name=" + a(c.links[0]) + "/>\n";
  for (std::size_t i = 1; i < c.links.size(); ++i)
    text +=
        "  <link name=" + a(c.links[i]) +
        "><inertial><origin xyz=\"0 0 -0.5\" rpy=\"0 0 0\"/><mass value=\"1\"/>"
        "<inertia ixx=\"0.1\" ixy=\"0\" ixz=\"0\" iyy=\"0.1\" iyz=\"0\" izz=\"0.1\"/></inertial></link>\n";
  for (std::size_t i = 0; i < c.joints.size(); ++i)
    text += "  <joint name=" + a(c.joints[i]) + " type=\"continuous\"><parent link=" + a(c.links[i]) +
            "/><child link=" + a(c.links[i + 1]) + "/>" +
            (i ? "<origin xyz=\"0 0 -1\" rpy=\"0 0 0\"/>" : "") + "<axis xyz=\"0 1 0\"/></joint>\n";
  return text + "</robot>\n";
}

/// The same chain with every name a placeholder "znameNNNN", numbered in the
/// names' byte order and equal where they are equal; the robot "zmodel".
Chain placeholders(const Chain& c) {
  std::set<std::string> names(c.links.begin(), c.links.end());
  names.insert(c.joints.begin(), c.joints.end());
  const auto placeholder = [&](const std::string& name) {
    char text[16];
    std::snprintf(text, sizeof text, "zname%04d",
                  static_cast<int>(std::distance(names.begin(), names.find(name))));
    return std::string(text);
  };
  Chain p{"zmodel", {}, {}, false};
  for (const std::string& l : c.links) p.links.push_back(placeholder(l));
  for (const std::string& j : c.joints) p.joints.push_back(placeholder(j));
  return p;
}

class Scratch {
 public:
  Scratch() : dir_(kanegen_test::process_scratch(KANEGEN_SCRATCH_DIR)) {}
  const fs::path& dir() const { return dir_; }
  std::string cache() const { return (dir_ / "cache").string(); }
  Result kanegen(const std::string& args) const {
    return kanegen_test::run_kanegen(KANEGEN_EXE, cache(), dir_, args);
  }

 private:
  fs::path dir_;
};

/// The path in single quotes for the shell (file names hold newlines).
std::string shell_quoted(const fs::path& path) {
  std::string out = "'";
  for (const char c : path.string()) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

fs::path write_model(const fs::path& dir, const std::string& file, const std::string& text) {
  fs::create_directories(dir);
  const fs::path path = dir / file;
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

/// The generated model's name: its header's file name.
std::string model_name(const fs::path& out) {
  for (const auto& e : fs::directory_iterator(out))
    if (e.path().extension() == ".hpp") return e.path().stem().string();
  FAIL("no header generated in " << out);
  return "";
}

/// The tokens of each generated .cpp after `g++ -E -P`, by role ("" for the
/// kernels, "_runner" for the runner), after checking that g++ compiles it.
std::map<std::string, std::vector<kanegen::fuzz::Token>> tokens(const fs::path& out,
                                                                const fs::path& scratch) {
  const std::string name = model_name(out);
  std::map<std::string, std::vector<kanegen::fuzz::Token>> streams;
  for (const std::string role : {"", "_runner"}) {
    const fs::path cpp = out / (name + role + ".cpp");
    const std::string syntax = "g++ -std=c++17 -fsyntax-only -I" + shell_quoted(out) + " -I" +
                               shell_quoted(kRuntimeInclude) + " " + shell_quoted(cpp) + " 2>" +
                               shell_quoted(scratch / "syntax.txt");
    if (std::system(syntax.c_str()) != 0)
      FAIL("g++ -fsyntax-only: " << kanegen_test::slurp(scratch / "syntax.txt"));
    streams[role] = kanegen::fuzz::tokenize(kanegen::fuzz::preprocess(cpp, kRuntimeInclude, scratch));
  }
  return streams;
}

/// `kanegen generate` of the model and of its placeholder twin; the two
/// token streams must agree but for literals (and, when the names the loader
/// reads are known, literals must read as those names). Returns the model's
/// name, or "" if kanegen refused the model, after checking the message.
std::string generate_and_compare(const Scratch& s, const std::string& file, const Chain& chain,
                                 bool names_known) {
  const fs::path model = write_model(s.dir() / "models", file, urdf(chain));
  const fs::path out = s.dir() / "out", twin_out = s.dir() / "twin_out";
  fs::remove_all(out);
  fs::remove_all(twin_out);
  const Result r = s.kanegen("generate " + shell_quoted(model) + " -o " + shell_quoted(out));
  INFO("kanegen generate " << kanegen::fuzz::shown(model.string()) << ": " << r.err);
  if (r.status != 0) {
    // A bad model: status 2 and one line "error: FILE: PLACE: problem; fix".
    CHECK(r.status == 2);
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
    CHECK(r.err.rfind("error: " + model.string() + ": line ", 0) == 0);
    CHECK(!fs::exists(out / "zmodel.hpp"));
    return "";
  }
  const Chain twin = placeholders(chain);
  const fs::path twin_model = write_model(s.dir() / "twin", "twin.urdf", urdf(twin));
  REQUIRE(s.kanegen("generate " + shell_quoted(twin_model) + " -o " + shell_quoted(twin_out)).status == 0);

  kanegen::fuzz::NameMap names{{"zmodel", model_name(out)}};
  for (std::size_t i = 0; i < chain.links.size(); ++i) names[twin.links[i]] = chain.links[i];
  for (std::size_t i = 0; i < chain.joints.size(); ++i) names[twin.joints[i]] = chain.joints[i];
  const auto actual = tokens(out, s.dir()), expected = tokens(twin_out, s.dir());
  for (const auto& [role, stream] : expected) {
    try {
      kanegen::fuzz::compare_tokens(role + ".cpp", stream, actual.at(role), names, names_known);
    } catch (const std::exception& e) {
      FAIL(e.what());
    }
  }
  return model_name(out);
}

/// The header line of an RFC 4180 CSV (a quoted field may hold newlines).
std::vector<std::string> csv_header(const std::string& csv) {
  std::vector<std::string> fields(1);
  bool quoted_field = false;
  for (std::size_t i = 0; i < csv.size(); ++i) {
    const char c = csv[i];
    if (quoted_field) {
      if (c == '"' && i + 1 < csv.size() && csv[i + 1] == '"') {
        fields.back() += '"';
        ++i;
      } else if (c == '"') {
        quoted_field = false;
      } else {
        fields.back() += c;
      }
    } else if (c == '"') {
      quoted_field = true;
    } else if (c == ',') {
      fields.emplace_back();
    } else if (c == '\n') {
      break;
    } else {
      fields.back() += c;
    }
  }
  return fields;
}

/// Accepted names: generated, compared, then simulated; the CSV columns
/// after t are the joint names, then the same with "_dot".
void accepted_and_simulated(const Chain& chain) {
  const Scratch s;
  REQUIRE(!generate_and_compare(s, "names.urdf", chain, true).empty());
  const fs::path model = s.dir() / "models" / "names.urdf";
  const Result r = s.kanegen("simulate " + shell_quoted(model) + " --t-end 0.01");
  INFO(r.err);
  REQUIRE(r.status == 0);
  std::vector<std::string> expected{"t"};
  expected.insert(expected.end(), chain.joints.begin(), chain.joints.end());
  for (const std::string& j : chain.joints) expected.push_back(j + "_dot");
  const std::vector<std::string> header = csv_header(r.out);
  REQUIRE(header.size() >= expected.size());
  CHECK(std::vector<std::string>(header.begin(), header.begin() + static_cast<long>(expected.size())) ==
        expected);
}

/// One joint (and its links) named by `joint`/`link` as written in the file.
Chain one_joint(const std::string& joint, const std::string& link = "bob",
                const std::string& robot = "pendulum") {
  return {robot, {"ground", link}, {joint}, true};
}

}  // namespace

TEST_CASE("names with control characters or that are not UTF-8 are refused", "[security]") {
  const Scratch s;
  const std::vector<std::pair<const char*, Chain>> cases{
      {"the issue's injection", one_joint("j1&#10;#include &lt;/etc/shadow&gt;")},
      {"newline", one_joint("j&#10;x")},
      {"carriage return", one_joint("j&#13;x")},
      {"tab", one_joint("j&#9;x")},
      {"escape", one_joint("j&#27;[31mred")},
      {"raw newline in a link name", one_joint("j", "b\n#define x 1")},
      {"newline in a link name", one_joint("j", "b&#10;#pragma once")},
      {"a lone 0xff", one_joint("j\xff")},
      {"a truncated UTF-8 sequence", one_joint("j\xe2\x82")},
      {"an overlong '/'", one_joint("j\xc0\xaf\xc0\xaf")},
      {"an overlong '/' in a link name", one_joint("j", "b\xc0\xaf*")},
  };
  for (const auto& [what, chain] : cases) {
    INFO(what);
    CHECK(generate_and_compare(s, "refused.urdf", chain, false).empty());
  }
}

TEST_CASE("a NUL character reference is refused or cuts the name (tinyxml2), never reaches code",
          "[security]") {
  const Scratch s;
  generate_and_compare(s, "nul.urdf", one_joint("j&#0;#include x", "b&#0;\"*/"), false);
}

TEST_CASE("the robot's name becomes an identifier whatever it holds", "[security]") {
  const Scratch s;
  for (const std::string robot :
       {"r&#10;#define x 1", "{{MODEL_NAME}}", "*/ /* ?\?= \\", "\xff\xfe", "double"}) {
    INFO(robot);
    CHECK(!generate_and_compare(s, "robot.urdf", one_joint("j", "b", robot), false).empty());
  }
}

TEST_CASE("the model file's name stays in its comment", "[security]") {
  const Scratch s;
  for (const std::string file : {"inj\n#include <x>\n.urdf", "star*\\ ?\?=\n.urdf", "\xff\xc0\xaf*.urdf"}) {
    INFO(kanegen::fuzz::shown(file));
    CHECK(!generate_and_compare(s, file, one_joint("hinge"), true).empty());
  }
}

TEST_CASE("escapes, comment marks and trigraphs stay in string literals", "[security]") {
  accepted_and_simulated({"r\n#include </etc/shadow>",
                          {"ground", "l\\", "l*/", "/*l", "l\"q"},
                          {"j\\", "j\"q\"", "a*/b/*c//d", "x?\?/y?\?=z?\?'w?\?-"},
                          false});
}

TEST_CASE("UTF-8, template syntax, spaces and long names come back as CSV columns", "[security]") {
  accepted_and_simulated(
      {"{{MODEL_NAME}}",
       {"ground", "\xc3\xa9l\xc3\xa9ment", "\xe8\x85\x95", "{{SPEED_NAMES}}", "   ", "l, \"5\""},
       {"\xc3\xa9", "\xe8\x85\x95\xf0\x9f\x98\x80", "{{MODEL_NAME}}", "   ", std::string(3000, 'n')},
       false});
}
