// SPDX-License-Identifier: GPL-2.0-or-later
#include "codegen/batch_kernels.hpp"

#include <cctype>
#include <regex>
#include <set>
#include <stdexcept>

#include "kanegen/runtime/kernel_spec.hpp"

namespace kanegen::codegen {
namespace {

using Values = std::map<std::string, std::string>;

bool identifier_char(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }

const std::set<std::string>& math_functions() {
  // What cpp_printer calls (Op::sin ... Op::abs, pow for a non-integer power).
  static const std::set<std::string> names = {"sin", "cos", "tan", "exp", "log", "sqrt", "fabs", "pow"};
  return names;
}

/// Whether an expression holds a value of the lanes: any name but a Params
/// member (`p.x`), a called function or a number's exponent.
bool names_a_lane_value(const std::string& expr) {
  std::size_t at = 0;
  while (at < expr.size()) {
    if (std::isdigit(static_cast<unsigned char>(expr[at]))) {  // a number, exponent included
      while (at < expr.size() && (identifier_char(expr[at]) || expr[at] == '.' ||
                                  ((expr[at] == '-' || expr[at] == '+') && (expr[at - 1] == 'e'))))
        ++at;
    } else if (identifier_char(expr[at])) {
      std::size_t end = at;
      while (end < expr.size() && identifier_char(expr[end])) ++end;
      const bool member = at > 0 && expr[at - 1] == '.';
      const bool params = expr.compare(at, end - at, "p") == 0 && end < expr.size() && expr[end] == '.';
      const bool call = end < expr.size() && expr[end] == '(';
      if (!member && !params && !call) return true;
      at = end;
    } else {
      ++at;
    }
  }
  return false;
}

/// `double` as `Lanes` and each <math.h> call as its lane-wise helper.
std::string in_lanes(const std::string& code) {
  std::string out;
  std::size_t at = 0;
  while (at < code.size()) {
    if (!identifier_char(code[at])) {
      out += code[at++];
      continue;
    }
    std::size_t end = at;
    while (end < code.size() && identifier_char(code[end])) ++end;
    const std::string word = code.substr(at, end - at);
    const bool number = std::isdigit(static_cast<unsigned char>(word[0]));
    if (!number && word == "double")
      out += "Lanes";
    else if (!number && math_functions().count(word) && end < code.size() && code[end] == '(')
      out += "lanes_" + word;
    else
      out += word;
    at = end;
  }
  return out;
}

std::string batch_statement(const std::string& line) {
  static const std::regex check(R"(^(\s*)if \(!\(([A-Za-z_]\w*) > 0\.0\)\) return (\d+);$)");
  static const std::regex assignment(R"(^(\s*)(const double )?([A-Za-z_]\w*(\[\d+\])?) = (.+);$)");
  static const std::regex refused(R"(\b(if|else|for|while|do|switch|goto|return|case)\b|\?)");
  std::smatch m;
  if (std::regex_match(line, m, check))
    return m[1].str() + "lanes_check(status, " + m[2].str() + ", " + m[3].str() + ");";
  if (std::regex_search(line, refused))
    throw std::logic_error("batch_body: a statement the batched kernels cannot evaluate lane by lane: " +
                           line);
  if (std::regex_match(line, m, assignment)) {
    const std::string value = in_lanes(m[5].str());
    // A value made of numbers and parameters alone is one number: make it a
    // vector (adding -0.0 is exact, also for -0.0 itself).
    return m[1].str() + (m[2].matched ? "const Lanes " : "") + m[3].str() + " = " +
           (names_a_lane_value(m[5].str()) ? value : "lanes_zero + (" + value + ")") + ";";
  }
  return in_lanes(line);
}

/// `const double s = sin(a);` and `const double c = cos(a);` of one
/// argument in one scope become one lane loop at the first of them,
/// `Lanes s, c; lanes_sincos(a, s, c);` (lines that batch_statement keeps),
/// so that the compiler makes one sincos call per lane of them, as it does
/// in the scalar kernel.
void pair_sines_and_cosines(std::vector<std::string>& lines) {
  static const std::regex call(R"(^(\s*)const double ([A-Za-z_]\w*) = (sin|cos)\((.+)\);$)");
  std::map<std::string, std::size_t> first;  // argument -> line of its first sin or cos
  std::smatch m;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    if (lines[i].find_first_of("{}") != std::string::npos) first.clear();  // a scope opens or closes
    if (!std::regex_match(lines[i], m, call)) continue;
    const std::string indent = m[1], name = m[2], function = m[3], argument = m[4];
    const auto at = first.find(argument);
    std::smatch other;
    if (at == first.end() || !std::regex_match(lines[at->second], other, call) || other[3] == function) {
      first[argument] = i;
      continue;
    }
    const std::string sine = function == "sin" ? name : other[2].str();
    const std::string cosine = function == "cos" ? name : other[2].str();
    lines[at->second] = indent + "Lanes " + sine + ", " + cosine + ";\n" + indent + "lanes_sincos(" +
                        in_lanes(argument) + ", " + sine + ", " + cosine + ");";
    lines[i].clear();
    first.erase(at);
  }
}

/// The lanes type, its operators where it is the portable struct, and the
/// lane-wise helpers of the batched kernels, for W lanes.
std::string lanes_helpers(int lanes) {
  const std::string w = std::to_string(lanes);
  const std::string each = "for (int l = 0; l < " + w + "; ++l) ";
  std::string zeros, operators;
  for (int l = 0; l < lanes; ++l) zeros += (l ? ", " : "") + std::string("-0.0");
  for (const char* op : {"+", "-", "*", "/"}) {
    const std::string o = op;
    operators += "[[maybe_unused]] inline Lanes operator" + o + "(Lanes a, const Lanes& b) {\n  " + each +
                 "a.lane[l] " + o + "= b.lane[l];\n  return a;\n}\n";
    operators += "[[maybe_unused]] inline Lanes operator" + o + "(Lanes a, double b) {\n  " + each +
                 "a.lane[l] " + o + "= b;\n  return a;\n}\n";
    operators += "[[maybe_unused]] inline Lanes operator" + o + "(double a, Lanes b) {\n  " + each +
                 "b.lane[l] = a " + o + " b.lane[l];\n  return b;\n}\n";
    operators += "[[maybe_unused]] inline Lanes& operator" + o + "=(Lanes& a, const Lanes& b) {\n  " + each +
                 "a.lane[l] " + o + "= b.lane[l];\n  return a;\n}\n";
    operators += "[[maybe_unused]] inline Lanes& operator" + o + "=(Lanes& a, double b) {\n  " + each +
                 "a.lane[l] " + o + "= b;\n  return a;\n}\n";
  }
  operators += "[[maybe_unused]] inline Lanes operator-(Lanes a) {\n  " + each +
               "a.lane[l] = -a.lane[l];\n  return a;\n}\n";
  std::string math;
  for (const std::string& f : math_functions()) {
    const bool two = f == "pow";
    math += "[[maybe_unused]] KANEGEN_LANES_INLINE Lanes lanes_" + f + "(const Lanes& a" +
            (two ? ", double b" : "") + ") {\n  Lanes r = a;\n  " + each + "r[l] = " + f + "(a[l]" +
            (two ? ", b" : "") + ");\n  return r;\n}\n";
    math += "[[maybe_unused]] inline double lanes_" + f + "(double a" + (two ? ", double b" : "") +
            ") { return " + f + "(a" + (two ? ", b" : "") + "); }\n";
  }
  return "namespace {\n\n"
         "#if (defined(__GNUC__) || defined(__clang__)) && !defined(KANEGEN_BATCH_PORTABLE)\n"
         "// The lanes as a GCC/Clang vector extension: +, -, *, / lane by lane (IEEE,\n"
         "// as the scalar kernels compute them), in SIMD registers where the target has them.\n"
         "__extension__ typedef double Lanes __attribute__((vector_size(" +
         w + " * sizeof(double))));\n" + "[[maybe_unused]] const Lanes lanes_zero = {" + zeros +
         "};\n"
         "#define KANEGEN_LANES_INLINE __attribute__((always_inline)) inline\n"
         "#else\n"
         "// The lanes as a plain struct (KANEGEN_BATCH_PORTABLE defined, or a compiler\n"
         "// without vector extensions): each operator applied lane by lane.\n"
         "struct Lanes {\n  double lane[" +
         w +
         "];\n"
         "  double& operator[](int l) { return lane[l]; }\n"
         "  const double& operator[](int l) const { return lane[l]; }\n"
         "};\n" +
         "[[maybe_unused]] const Lanes lanes_zero = {{" + zeros + "}};\n" + operators +
         "#define KANEGEN_LANES_INLINE inline\n"
         "#endif\n\n"
         "// <math.h> lane by lane; a number (of parameters alone) stays a number.\n" +
         math +
         "// Both of one argument in one lane loop: the compiler makes it one sincos call per lane.\n"
         "[[maybe_unused]] KANEGEN_LANES_INLINE void lanes_sincos(const Lanes& a, Lanes& s, Lanes& c) {\n"
         "  s = a;\n  c = a;\n  " +
         each +
         "{\n    s[l] = sin(a[l]);\n    c[l] = cos(a[l]);\n  }\n}\n"
         "// Structure of arrays: entry i of lane l at from[i * " +
         w +
         " + l].\n"
         "[[maybe_unused]] KANEGEN_LANES_INLINE void lanes_load(Lanes* to, const double* from, int n) {\n"
         "  for (int i = 0; i < n; ++i)\n    " +
         each + "to[i][l] = from[i * " + w +
         " + l];\n}\n"
         "[[maybe_unused]] KANEGEN_LANES_INLINE void lanes_store(double* to, const Lanes* from, int n) {\n"
         "  for (int i = 0; i < n; ++i)\n    " +
         each + "to[i * " + w +
         " + l] = from[i][l];\n}\n"
         "// A lane's first pivot that is not positive is its status, as the scalar kernel returns it.\n"
         "[[maybe_unused]] KANEGEN_LANES_INLINE void lanes_check(int* status, const Lanes& pivot, int k) {\n "
         " " +
         each +
         "\n    if (status[l] == 0 && !(pivot[l] > 0.0)) status[l] = k;\n}\n"
         "[[maybe_unused]] inline int lanes_failed(const int* status) {\n  int n = 0;\n  " +
         each + "n += status[l] != 0;\n  return n;\n}\n\n}  // namespace\n\n";
}

std::string batch_name(const KernelSignature& s, int lanes) {
  return std::string(s.name) + "_batch" + std::to_string(lanes);
}

/// The batched kernel's arguments: Params as the scalar kernel's, every
/// array and scalar as W lanes (`<name>_lanes`), and the lanes' status for
/// a kernel that returns one.
std::vector<std::string> batch_arguments(const KernelSignature& s, const std::string& body,
                                         bool mark_unused) {
  std::vector<std::string> out;
  const runtime::KernelSpec& spec = runtime::kernel_spec(s.kernel);
  const auto unused = [&](const std::string& name) {
    return mark_unused && !names_identifier(body, name) ? "[[maybe_unused]] " : "";
  };
  if (spec.params == runtime::ParamsAccess::read) out.push_back(std::string(unused("p")) + "const Params& p");
  for (std::size_t i = 0; i < spec.argument_count; ++i) {
    const runtime::KernelArgumentSpec& a = spec.arguments[i];
    const std::string name = a.name;
    const bool out_array = a.role == runtime::ArgumentRole::out;
    out.push_back(std::string(out_array ? "" : unused(name)) + (out_array ? "double* " : "const double* ") +
                  name + "_lanes");
  }
  if (std::string(s.returns) == "int") out.push_back("int* status");
  return out;
}

std::string batch_doc(const KernelSignature& s, int lanes) {
  const std::string w = std::to_string(lanes);
  const runtime::KernelSpec& spec = runtime::kernel_spec(s.kernel);
  std::string arrays;
  for (std::size_t i = 0; i < spec.argument_count; ++i) {
    const runtime::KernelArgumentSpec& a = spec.arguments[i];
    arrays += std::string(arrays.empty() ? "" : ", ") + a.name +
              "_lanes: " + (std::string(a.size) == "1" ? w : std::string(a.size) + "*" + w);
  }
  std::string doc = "/// " + std::string(s.name) + " for " + w +
                    " states at once, each lane as the scalar kernel computes it;\n"
                    "/// p is shared by the lanes. Structure of arrays: entry i of lane l at [i*" +
                    w + " + l] (" + arrays + ").\n";
  if (std::string(s.returns) == "int")
    doc += "/// status: " + w +
           " entries, each the scalar kernel's return for its lane (not 0: that lane's\n" +
           "/// outputs are invalid). Returns the number of lanes whose status is not 0.\n";
  return doc;
}

std::string batch_definition(const KernelCode& code, int lanes) {
  const KernelSignature& s = signature(code.kernel);
  const runtime::KernelSpec& spec = runtime::kernel_spec(s.kernel);
  const std::string body = batch_body(code.body);
  const bool returns_status = std::string(s.returns) == "int";
  std::string head, tail;
  for (std::size_t i = 0; i < spec.argument_count; ++i) {
    const runtime::KernelArgumentSpec& a = spec.arguments[i];
    const std::string name = a.name, size = a.size;
    if (a.role == runtime::ArgumentRole::out) {
      head += "  Lanes " + name + "[" + size + "] = {};\n";
      tail += "  lanes_store(" + name + "_lanes, " + name + ", " + size + ");\n";
    } else if (names_identifier(body, name) && a.role == runtime::ArgumentRole::scalar) {
      head += "  Lanes " + name + ";\n  lanes_load(&" + name + ", " + name + "_lanes, 1);\n";
    } else if (names_identifier(body, name)) {
      head += "  Lanes " + name + "[" + size + "];\n  lanes_load(" + name + ", " + name + "_lanes, " + size +
              ");\n";
    }
  }
  if (returns_status) {
    head += "  for (int l = 0; l < " + std::to_string(lanes) + "; ++l) status[l] = 0;\n";
    tail += "  return lanes_failed(status);\n";
  }
  return prototype((returns_status ? "int " : "void ") + batch_name(s, lanes), batch_arguments(s, body, true),
                   " {") +
         "\n" + head + body + tail + "}\n";
}

}  // namespace

bool has_batch_form(Kernel kernel) {
  return kernel == Kernel::forward_dynamics || kernel == Kernel::inverse_dynamics;
}

std::string batch_body(const std::string& scalar_body) {
  std::vector<std::string> lines;
  std::size_t from = 0;
  while (from < scalar_body.size()) {
    const std::size_t end = std::min(scalar_body.find('\n', from), scalar_body.size());
    lines.push_back(scalar_body.substr(from, end - from));
    from = end + 1;
  }
  while (!lines.empty() && lines.back().find_first_not_of(' ') == std::string::npos) lines.pop_back();
  if (!lines.empty() && lines.back() == "  return 0;") lines.pop_back();
  pair_sines_and_cosines(lines);
  std::string out;
  for (const std::string& line : lines) {
    const std::size_t first = line.find_first_not_of(' ');
    if (line.empty()) continue;  // the second of a sine and cosine pair
    if (first == std::string::npos || line.compare(first, 2, "//") == 0 ||
        line.compare(first, 6, "Lanes ") == 0) {
      out += line + "\n";
      continue;
    }
    const std::size_t comment = line.find("  //");
    const std::string statement = comment == std::string::npos ? line : line.substr(0, comment);
    out += batch_statement(statement) + (comment == std::string::npos ? "" : line.substr(comment)) + "\n";
  }
  return out;
}

std::map<std::string, std::string> batch_files(const std::vector<KernelCode>& kernels, const Values& values,
                                               int lanes) {
  if (lanes != 4 && lanes != 8) throw std::logic_error("batched kernels of 4 or 8 lanes only");
  const std::string w = std::to_string(lanes), name = values.at("MODEL_NAME");
  const std::string head =
      "// SPDX-License-Identifier: MIT\n"
      "// This file is kanegen's output: you may use, copy, modify and distribute it under any terms you "
      "choose (docs/licensing.md).\n"
      "// " +
      name + ": batched kernels, " + w + " states per call (kanegen generate --batch " + w +
      "; docs/architecture.md#batched-kernels).\n"
      "// Generated by kanegen " +
      values.at("GENERATOR_VERSION") + " from " + values.at("MODEL_FILE") + " (model hash " +
      values.at("MODEL_HASH") + "). Do not edit.\n";
  std::string declarations, definitions;
  for (const KernelCode& code : kernels) {
    if (!has_batch_form(code.kernel)) continue;
    const KernelSignature& s = signature(code.kernel);
    declarations += "\n" + batch_doc(s, lanes) +
                    prototype(std::string(s.returns) == "int" ? "int " + batch_name(s, lanes)
                                                              : "void " + batch_name(s, lanes),
                              batch_arguments(s, "", false), ";") +
                    "\n";
    definitions += "\n" + batch_definition(code, lanes);
  }
  const std::string open = "namespace kanegen_models {\nnamespace " + name + " {\n";
  const std::string close = "}  // namespace " + name + "\n}  // namespace kanegen_models\n";
  const std::string header = name + "_batch" + w + ".hpp";
  return {
      {header, head + "//\n// Every array is W = " + w +
                   " states as a structure of arrays, entry i of lane l at [i*" + w +
                   " + l];\n// no function allocates, throws or keeps state.\n#pragma once\n\n#include \"" +
                   name + ".hpp\"\n\n" + open + declarations + "\n" + close},
      {name + "_batch" + w + ".cpp",
       head + "#include \"" + header +
           "\"\n\n#include <math.h>\n\n"
           "// Lane-wise helpers of internal linkage, always inlined: no vector crosses an ABI.\n"
           "#if defined(__GNUC__)\n#pragma GCC diagnostic push\n#pragma GCC diagnostic ignored \"-Wpsabi\"\n"
           "#endif\n\n" +
           open + "\n" + lanes_helpers(lanes) + definitions.substr(1) + "\n" + close +
           "\n#undef KANEGEN_LANES_INLINE\n#if defined(__GNUC__)\n#pragma GCC diagnostic pop\n#endif\n"},
  };
}

}  // namespace kanegen::codegen
