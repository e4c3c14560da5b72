// SPDX-License-Identifier: GPL-2.0-or-later
#include "codegen/kernel_printer.hpp"

#include <cctype>

namespace kanegen::codegen {
namespace {

constexpr std::size_t kColumnLimit = 110;  // as .clang-format

bool identifier_char(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }

std::vector<std::string> typed_arguments(const KernelSignature& signature, bool mark_unused,
                                         const std::string& body, const ScalarType& scalar) {
  std::vector<std::string> out;
  for (const KernelArgument& a : arguments(signature)) {
    const bool unused = mark_unused && !names_identifier(body, a.name);
    out.push_back((unused ? "[[maybe_unused]] " : "") + scalar.in_type(a.type) + " " + a.name);
  }
  return out;
}

/// `p` as the kernel takes it, from the table's untyped pointer.
std::string call_argument(const KernelArgument& a) {
  if (a.type == "const Params&") return "*static_cast<const Params*>(" + a.name + ")";
  if (a.type == "Params&") return "*static_cast<Params*>(" + a.name + ")";
  return a.name;
}

std::string untyped(const KernelArgument& a) {
  if (a.type == "const Params&") return "const void* " + a.name;
  if (a.type == "Params&") return "void* " + a.name;
  return a.type + " " + a.name;
}

std::string call(const KernelSignature& signature, const std::string& prefix, bool from_table) {
  std::string s = prefix + signature.name + "(";
  bool first = true;
  for (const KernelArgument& a : arguments(signature)) {
    s += (first ? "" : ", ") + (from_table ? call_argument(a) : a.name);
    first = false;
  }
  return s + ")";
}

std::string returning(const KernelSignature& signature) {
  return std::string(signature.returns) == "void" ? "" : "return ";
}

}  // namespace

bool names_identifier(const std::string& code, const std::string& name) {
  for (std::size_t at = code.find(name); at != std::string::npos; at = code.find(name, at + 1)) {
    const bool starts = at == 0 || !identifier_char(code[at - 1]);
    const std::size_t end = at + name.size();
    const bool ends = end >= code.size() || !identifier_char(code[end]);
    if (starts && ends) return true;
  }
  return false;
}

std::string prototype(const std::string& head, const std::vector<std::string>& arguments,
                      const std::string& tail, const std::string& indent) {
  const std::string opening = indent + head + "(";
  const std::string continuation(opening.size(), ' ');
  std::string text = opening, line = opening;
  for (std::size_t i = 0; i < arguments.size(); ++i) {
    const bool last = i + 1 == arguments.size();
    const std::string piece = arguments[i] + (last ? ")" + tail : ",");
    const bool first_on_line = line.size() == opening.size() || line == continuation;
    if (!first_on_line && line.size() + 1 + piece.size() > kColumnLimit) {
      text += "\n" + continuation;
      line = continuation;
    } else if (!first_on_line) {
      text += " ";
      line += " ";
    }
    text += piece;
    line += piece;
  }
  if (arguments.empty()) text += ")" + tail;
  return text;
}

std::string declaration(const KernelSignature& signature, const ScalarType& scalar) {
  return std::string(signature.doc) + "\n" +
         prototype(scalar.in_type(signature.returns) + " " + signature.name,
                   typed_arguments(signature, false, "", scalar), ";") +
         "\n";
}

std::string definition(const KernelSignature& signature, const std::string& body, const ScalarType& scalar) {
  return prototype(scalar.in_type(signature.returns) + " " + signature.name,
                   typed_arguments(signature, true, body, scalar), " {") +
         "\n" + body + "}\n";
}

std::string system_forwarder(const KernelSignature& signature, const std::string& model_name) {
  return prototype(std::string("static ") + signature.returns + " " + signature.name,
                   typed_arguments(signature, false, "", ScalarType()), " {", "  ") +
         "\n    " + returning(signature) + call(signature, "::kanegen_models::" + model_name + "::", false) +
         ";\n  }\n";
}

std::string table_entry(const KernelSignature& signature) {
  std::vector<std::string> untyped_arguments;
  for (const KernelArgument& a : arguments(signature)) untyped_arguments.push_back(untyped(a));
  return prototype("table." + std::string(signature.name) + " = []", untyped_arguments, " {", "  ") +
         "\n    " + returning(signature) + call(signature, "", true) + ";\n  };\n";
}

}  // namespace kanegen::codegen
