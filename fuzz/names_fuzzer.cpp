// SPDX-License-Identifier: GPL-2.0-or-later
// libFuzzer target: model text in generated code (docs/errors.md#security).
// Every name and free-text field of a small fixed model comes from the input,
// in a URDF or a JSON model; the model must either be refused with one clear
// ModelError, or give code whose every input-derived token is either inside a
// string literal that reads back as the name, or the name itself where the
// model's identifiers go (model name, parameters). This is checked against
// the same model with the names replaced by placeholders: both sets of files
// go through `g++ -E -P` and their token streams must be the same but for
// string literals (an injected directive, token or comment end would differ),
// and each string literal must decode to the placeholder's one with the
// placeholders replaced by the names the loader read.
//
// Input: one byte choosing the format and how names are written, then the
// fields separated by the byte 0xfe (missing fields stay empty):
//   0: URDF, every byte as an XML character reference &#N; (any byte, NUL
//      included, reaches the XML reader as a character)
//   1: URDF, bytes as they are (only " & < written as references)
//   2: JSON, every byte as a \u00XX escape
//   3: JSON, bytes as they are (only " and \ escaped): invalid UTF-8 and raw
//      control characters reach the JSON parser
// URDF fields: robot name, 3 link names, 2 joint names, the file's name.
// JSON fields: model name, description, 2 body names, 2 joint names,
//   2 parameter names, 2 output names, the file's name.
// g++ runs per accepted input (a few per second); a refused model costs none.
#include <unistd.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "fuzz/generated_code.hpp"
#include "fuzz/harness.hpp"
#include "model/load.hpp"
#include "model/names.hpp"
#include "pipeline/pipeline.hpp"

namespace kanegen::fuzz {
namespace {

namespace fs = std::filesystem;
using Files = std::map<std::string, std::string>;

[[noreturn]] void failure(const std::string& what) { throw HarnessFailure(what); }

enum Format { urdf_references, urdf_raw, json_escapes, json_raw };

constexpr std::size_t kUrdfFields = 7, kJsonFields = 11;
constexpr unsigned char kSeparator = 0xfe;

// ---------------------------------------------------------------------------
// The model files.

/// A field inside a double-quoted XML attribute.
std::string xml_attribute(const std::string& text, Format format) {
  std::string out;
  for (const char c : text) {
    const auto b = static_cast<unsigned char>(c);
    if (format == urdf_references || c == '"' || c == '&' || c == '<')
      out += "&#" + std::to_string(b) + ";";
    else
      out += c;
  }
  return out;
}

/// A field inside a JSON string.
std::string json_string(const std::string& text, Format format) {
  std::string out;
  for (const char c : text) {
    const auto b = static_cast<unsigned char>(c);
    if (format == json_escapes || c == '"' || c == '\\') {
      char escape[7];
      std::snprintf(escape, sizeof escape, "\\u%04x", b);
      out += escape;
    } else {
      out += c;
    }
  }
  return out;
}

/// Two continuous joints in series, 1 kg links.
std::string urdf_text(const std::vector<std::string>& f, Format format) {
  const auto a = [&](std::size_t i) { return "\"" + xml_attribute(f[i], format) + "\""; };
  const std::string inertial =
      "<inertial><origin xyz=\"0 0 -0.5\" rpy=\"0 0 0\"/><mass value=\"1\"/>"
      "<inertia ixx=\"0.1\" ixy=\"0\" ixz=\"0\" iyy=\"0.1\" iyz=\"0\" izz=\"0.1\"/></inertial>";
  return "<?xml version=\"1.0\"?>\n<robot name=" + a(0) + ">\n  <link name=" + a(1) +
         "/>\n  <link name=" + a(2) + ">" + inertial + "</link>\n  <link name=" + a(3) + ">" + inertial +
         "</link>\n  <joint name=" + a(4) + " type=\"continuous\"><parent link=" + a(1) +
         "/><child link=" + a(2) + "/><axis xyz=\"0 1 0\"/></joint>\n  <joint name=" + a(5) +
         " type=\"continuous\"><parent link=" + a(2) + "/><child link=" + a(3) +
         "/><origin xyz=\"0 0 -1\" rpy=\"0 0 0\"/><axis xyz=\"0 1 0\"/></joint>\n</robot>\n";
}

/// A double pendulum with a joint output and a point output. The parameters
/// are declared but used by no expression: GiNaC orders a sum's terms by its
/// symbols, so a parameter in the kernels would order them by its name and
/// the placeholder model's code would differ in more than the names.
std::string json_text(const std::vector<std::string>& f, Format format) {
  const auto s = [&](std::size_t i) { return "\"" + json_string(f[i], format) + "\""; };
  const std::string inertial = "\"com\": [0.5, 0, 0], \"inertia\": {\"ixx\": 0, \"iyy\": 0.1, \"izz\": 0.1}}";
  return "{\"format\": \"kanegen-model\", \"version\": 1, \"name\": " + s(0) + ", \"description\": " + s(1) +
         ",\n \"parameters\": {" + s(6) + ": 1.0, " + s(7) + ": 0.1},\n \"gravity\": [0, 0, -9.81],\n" +
         " \"bodies\": [{\"name\": " + s(2) + ", \"mass\": 1, " + inertial + ",\n  {\"name\": " + s(3) +
         ", \"mass\": 1, " + inertial + "],\n" + " \"joints\": [{\"name\": " + s(4) +
         ", \"type\": \"revolute\", \"parent\": \"ground\", \"child\": " + s(2) +
         ", \"axis\": [0, 1, 0]},\n  {\"name\": " + s(5) + ", \"type\": \"revolute\", \"parent\": " + s(2) +
         ", \"child\": " + s(3) + ", \"origin\": {\"xyz\": [1, 0, 0]}, \"axis\": [0, 1, 0]}],\n" +
         " \"outputs\": [{\"name\": " + s(8) + ", \"type\": \"joint\", \"joint\": " + s(4) +
         "},\n  {\"name\": " + s(9) + ", \"type\": \"point\", \"body\": " + s(3) +
         ", \"point\": [1, 0, 0]}]}\n";
}

/// The fields of an input, each at most 1000 bytes (long names are the
/// regression test's; here they would only slow the compiler).
std::vector<std::string> split_fields(const std::uint8_t* data, std::size_t size, std::size_t count) {
  std::vector<std::string> fields(1);
  for (std::size_t i = 0; i < size; ++i) {
    if (data[i] == kSeparator) {
      if (fields.size() == count) break;
      fields.emplace_back();
    } else if (fields.back().size() < 1000) {
      fields.back() += static_cast<char>(data[i]);
    }
  }
  fields.resize(count);
  return fields;
}

/// A file name for the model: no '/' or NUL (the file system's), and the
/// extension that chooses the loader.
std::string file_name(const std::string& field, Format format) {
  std::string name = field.substr(0, 200);
  std::replace(name.begin(), name.end(), '/', '_');
  std::replace(name.begin(), name.end(), '\0', '_');
  if (name == "." || name == "..") name += "_";
  return name + (format <= urdf_raw ? ".urdf" : ".json");
}

/// The same fields with every name replaced by "znameNNNN", numbered in the
/// names' byte order (so whatever sorts names sorts both alike) and equal
/// where the names are equal; the model name (an identifier of its own,
/// after the URDF's sanitizing) becomes "zmodel", the file "zfile".
std::vector<std::string> placeholders(const std::vector<std::string>& fields) {
  const std::set<std::string> names(fields.begin() + 1, fields.end() - 1);
  std::vector<std::string> out{"zmodel"};
  for (std::size_t i = 1; i + 1 < fields.size(); ++i) {
    char text[16];
    std::snprintf(text, sizeof text, "zname%04d",
                  static_cast<int>(std::distance(names.begin(), names.find(fields[i]))));
    out.push_back(text);
  }
  out.push_back("zfile");
  return out;
}

// ---------------------------------------------------------------------------
// Files and the preprocessor.

/// A fresh directory of this process, removed at exit.
class ScratchDir {
 public:
  ScratchDir() : path_(fs::temp_directory_path() / ("kanegen-fuzz-names-" + std::to_string(::getpid()))) {
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;
  ~ScratchDir() {
    std::error_code ignored;
    fs::remove_all(path_, ignored);
  }
  /// An emptied subdirectory.
  fs::path fresh(const std::string& name) const {
    const fs::path dir = path_ / name;
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
  }

 private:
  fs::path path_;
};

void write(const fs::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
  if (!out.flush()) failure("cannot write " + path.string());
}

/// The names of the two loaded models, matched by place: the placeholder
/// model's name of each body, joint, parameter and output -> the fuzzed one's.
NameMap match_names(const model::Model& placeheld, const model::Model& fuzzed) {
  NameMap names;
  const auto add = [&](const std::string& from, const std::string& to) {
    const auto [at, inserted] = names.emplace(from, to);
    if (!inserted && at->second != to)
      failure("placeholder " + from + " stands for both " + shown(at->second) + " and " + shown(to));
  };
  const auto add_all = [&](const auto& a, const auto& b, const char* what) {
    if (a.size() != b.size()) failure(std::string("the placeholder model has another number of ") + what);
    for (std::size_t i = 0; i < a.size(); ++i) add(a[i].name, b[i].name);
  };
  add(placeheld.name, fuzzed.name);
  add(placeheld.ground, fuzzed.ground);
  add_all(placeheld.bodies, fuzzed.bodies, "bodies");
  add_all(placeheld.joints, fuzzed.joints, "joints");
  add_all(placeheld.parameters, fuzzed.parameters, "parameters");
  add_all(placeheld.outputs, fuzzed.outputs, "outputs");
  return names;
}

/// The generated files by role (the model's name is in their file names).
std::string role(const std::string& file, const std::string& model_name) {
  if (file.rfind(model_name, 0) != 0) failure("generated file " + file + " not named after " + model_name);
  return file.substr(model_name.size());
}

/// The token streams of the generated .cpp files (by role): the files are
/// written to `dir` and preprocessed there.
std::map<std::string, std::vector<Token>> preprocessed_tokens(const pipeline::GeneratedModel& g,
                                                              const fs::path& dir, const fs::path& scratch) {
  for (const auto& [file, text] : g.files) write(dir / file, text);
  std::map<std::string, std::vector<Token>> tokens;
  for (const auto& [file, text] : g.files)
    if (fs::path(file).extension() == ".cpp")
      tokens[role(file, g.name)] =
          tokenize(preprocess(dir / file, KANEGEN_SOURCE_DIR "/runtime/include", scratch));
  return tokens;
}

/// The placeholder model's streams, kept by its generated text: few
/// placeholder models exist (one per order of the names), so most inputs
/// need g++ only for their own files.
const std::map<std::string, std::vector<Token>>& placeholder_tokens(const pipeline::GeneratedModel& g,
                                                                    const ScratchDir& scratch) {
  static std::map<std::string, std::map<std::string, std::vector<Token>>> cache;
  std::string key;
  for (const auto& [file, text] : g.files) key += file + '\0' + text + '\0';
  const auto hit = cache.find(key);
  if (hit != cache.end()) return hit->second;
  if (cache.size() > 64) cache.clear();
  return cache[key] = preprocessed_tokens(g, scratch.fresh("placeholder"), scratch.fresh("placeholder-g++"));
}

/// Loads and generates; false (after checking the message) for a ModelError.
bool generate(const std::string& path, model::Model& m, pipeline::GeneratedModel& g) {
  try {
    m = model::load_model(path);
    g = pipeline::generate(path);
    return true;
  } catch (const model::ModelError& e) {
    check_error(e, path);
    return false;
  } catch (const std::exception& e) {
    failure(std::string("generating threw something other than a ModelError: ") + e.what());
  }
}

void names(const std::uint8_t* data, std::size_t size) {
  static const ScratchDir scratch;
  if (size == 0) return;
  const auto format = static_cast<Format>(data[0] % 4);
  const bool urdf = format <= urdf_raw;
  const std::vector<std::string> fields = split_fields(data + 1, size - 1, urdf ? kUrdfFields : kJsonFields);
  const std::vector<std::string> placed = placeholders(fields);
  const auto text = [&](const std::vector<std::string>& f) {
    return urdf ? urdf_text(f, format) : json_text(f, format);
  };

  const fs::path fuzzed_path = scratch.fresh("model") / file_name(fields.back(), format);
  write(fuzzed_path, text(fields));
  model::Model fuzzed_model;
  pipeline::GeneratedModel fuzzed;
  if (!generate(fuzzed_path.string(), fuzzed_model, fuzzed)) return;

  // Accepted: the same model with placeholders must be too.
  const fs::path placed_path = scratch.fresh("placeholder-model") / file_name(placed.back(), format);
  write(placed_path, text(placed));
  model::Model placed_model;
  pipeline::GeneratedModel placeholder;
  try {
    placed_model = model::load_model(placed_path.string());
    placeholder = pipeline::generate(placed_path.string());
  } catch (const std::exception& e) {
    failure(std::string("the model is accepted, but not with placeholder names: ") + e.what());
  }
  const NameMap names = match_names(placed_model, fuzzed_model);
  const auto& expected = placeholder_tokens(placeholder, scratch);
  const auto actual = preprocessed_tokens(fuzzed, scratch.fresh("generated"), scratch.fresh("generated-g++"));
  if (expected.size() != actual.size()) failure("not the placeholder model's generated files");
  for (const auto& [file, tokens] : expected) {
    const auto other = actual.find(file);
    if (other == actual.end()) failure("no generated " + file);
    compare_tokens(fuzzed.name + file, tokens, other->second, names);
  }
}

}  // namespace
}  // namespace kanegen::fuzz

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return kanegen::fuzz::run_or_abort(kanegen::fuzz::names, data, size);
}
