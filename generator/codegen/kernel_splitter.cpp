// SPDX-License-Identifier: GPL-2.0-or-later
#include "codegen/kernel_splitter.hpp"

#include <algorithm>
#include <map>
#include <regex>
#include <set>
#include <vector>

#include "codegen/kernel_printer.hpp"

namespace kanegen::codegen {
namespace {

const char* const kWorkspace = "w";

/// "q" of "q[3]", "p" of "p.m1", "t" of "t".
std::string root(const std::string& name) { return name.substr(0, name.find_first_of("[.")); }

/// Where each statement goes and where each value that crosses parts lives.
struct Layout {
  int parts = 0;
  std::vector<std::size_t> first;         ///< of each part, then the number of statements
  std::vector<int> part;                  ///< of each statement
  std::map<int, int> defined_in;          ///< temporary -> its part
  std::map<int, int> slot;                ///< crossing temporary -> workspace index
  std::map<std::size_t, int> local_slot;  ///< statement assigning a local -> workspace index
  int slots = 0;
};

long total_operations(const std::vector<Statement>& statements) {
  long total = 0;
  for (const Statement& s : statements) total += s.operations;
  return total;
}

Layout lay_out(const std::vector<Statement>& statements, long threshold,
               const std::set<std::string>& argument_names) {
  Layout layout;
  const int n = static_cast<int>(statements.size());
  const long total = total_operations(statements);
  const long parts = (total + threshold - 1) / threshold;
  const long target = (total + parts - 1) / parts;  // parts of even operation counts
  long in_part = 0;
  for (int i = 0; i < n; ++i) {
    if (i == 0 || (in_part >= target && layout.parts < parts)) {
      layout.first.push_back(static_cast<std::size_t>(i));
      ++layout.parts;
      in_part = 0;
    }
    in_part += statements[i].operations;
    layout.part.push_back(layout.parts - 1);
  }
  layout.first.push_back(statements.size());
  std::map<int, int> last_read_in;
  for (int i = 0; i < n; ++i) {
    if (statements[i].temporary >= 0) layout.defined_in[statements[i].temporary] = layout.part[i];
    for (int k : statements[i].temporaries) last_read_in[k] = layout.part[i];
  }
  // Slots in statement order, the smallest free one first; a slot is free
  // again after the last part that reads its value (a local's never is).
  std::set<int> free;
  std::map<int, std::vector<int>> released_after;
  for (int i = 0; i < n; ++i) {
    const int part = layout.part[i];
    if (i > 0 && part != layout.part[i - 1])
      for (int s : released_after[part - 1]) free.insert(s);
    const Statement& s = statements[i];
    const auto read = last_read_in.find(s.temporary);
    const bool crossing = s.temporary >= 0 && read != last_read_in.end() && read->second > part;
    const bool local = s.temporary < 0 && !argument_names.count(root(s.target));
    if (!crossing && !local) continue;
    int slot = layout.slots;
    if (free.empty()) {
      ++layout.slots;
    } else {
      slot = *free.begin();
      free.erase(free.begin());
    }
    if (crossing) {
      layout.slot[s.temporary] = slot;
      released_after[read->second].push_back(slot);
    } else {
      layout.local_slot[static_cast<std::size_t>(i)] = slot;
    }
  }
  return layout;
}

std::string slot_text(int slot) { return std::string(kWorkspace) + "[" + std::to_string(slot) + "]"; }

struct Part {
  std::string function;                ///< its definition, a static member of the local struct Part
  std::vector<std::string> arguments;  ///< the names it is called with
};

/// The order of part `p`'s statements: its library calls (sin, cos) that
/// read only earlier parts' values or the arguments, each after the one
/// statement of inputs that gives its argument (q[k] + c), first; then the
/// rest in the printed order. A call may overwrite every floating-point
/// register (the caller saves them), so it is made where few values are
/// live: chain20's forward_dynamics, 15329 -> 15053 instructions.
std::vector<std::size_t> calls_first(const PrintedKernel& printed, const Layout& layout, int p) {
  static const std::regex call(R"(^(sin|cos|sinf|cosf)\([^()]*\)$)");
  const std::size_t begin = layout.first[p], end = layout.first[p + 1];
  std::map<int, std::size_t> local;  // temporary -> its statement in this part
  for (std::size_t i = begin; i < end; ++i)
    if (printed.statements[i].temporary >= 0) local[printed.statements[i].temporary] = i;
  const auto reads_local = [&](std::size_t i) {
    for (int k : printed.statements[i].temporaries)
      if (local.count(k)) return true;
    return false;
  };
  std::vector<bool> taken(end - begin, false);
  std::vector<std::size_t> order;
  for (std::size_t i = begin; i < end; ++i) {
    const Statement& s = printed.statements[i];
    if (!std::regex_match(s.expression, call)) continue;
    std::vector<std::size_t> arguments;
    bool movable = true;
    for (int k : s.temporaries) {
      const auto at = local.find(k);
      if (at == local.end()) continue;
      if (reads_local(at->second)) movable = false;
      arguments.push_back(at->second);
    }
    if (!movable) continue;
    for (std::size_t a : arguments)
      if (!taken[a - begin]) taken[a - begin] = true, order.push_back(a);
    taken[i - begin] = true;
    order.push_back(i);
  }
  for (std::size_t i = begin; i < end; ++i)
    if (!taken[i - begin]) order.push_back(i);
  return order;
}

/// The function of part `p`: its parameters are the kernel's arguments that
/// it reads or writes, in the kernel's order, and the workspace if it uses it.
Part part_function(const PrintedKernel& printed, const Layout& layout, int p,
                   const std::vector<KernelArgument>& parameters, const ScalarType& scalar) {
  const std::string real = scalar.name();
  const std::string indent = "      ";
  std::set<std::string> names;
  std::set<int> imports;  // temporaries of earlier parts that it reads
  std::string body;
  bool workspace = false;
  for (const std::size_t i : calls_first(printed, layout, p)) {
    const Statement& s = printed.statements[i];
    for (const std::string& input : s.inputs) names.insert(root(input));
    // A value of an earlier part is loaded where it is first read, not at
    // the top: fewer values live at once, less work for the register allocator.
    for (int k : s.temporaries)
      if (layout.defined_in.at(k) != p && imports.insert(k).second)
        body += indent + "const " + real + " " + printed.temp_prefix + std::to_string(k) + " = " +
                slot_text(layout.slot.at(k)) + ";\n";
    if (s.temporary >= 0) {
      const std::string name = printed.temp_prefix + std::to_string(s.temporary);
      body += indent + "const " + real + " " + name + " = " + s.expression + ";\n";
      const auto slot = layout.slot.find(s.temporary);
      if (slot != layout.slot.end()) {
        body += indent + slot_text(slot->second) + " = " + name + ";\n";
        workspace = true;
      }
    } else if (layout.local_slot.count(i)) {
      body += indent + slot_text(layout.local_slot.at(i)) + " = " + s.expression + ";\n";
      workspace = true;
    } else {
      names.insert(root(s.target));
      body += indent + s.target + " = " + s.expression + ";\n";
    }
  }
  workspace = workspace || !imports.empty();
  Part part;
  std::vector<std::string> typed;
  for (const KernelArgument& a : parameters)
    if (names.count(a.name)) {
      typed.push_back(scalar.in_type(a.type) + " " + a.name);
      part.arguments.push_back(a.name);
    }
  if (workspace) {
    typed.push_back(real + "* " + kWorkspace);
    part.arguments.push_back(kWorkspace);
  }
  part.function = prototype("[[gnu::noinline]] static void part" + std::to_string(p), typed, " {", "    ") +
                  "\n" + body + "    }\n";
  return part;
}

/// The call of part `p`: "  Part::part<p>(p, q, w);".
std::string part_call(const Part& part, int p) {
  std::string call;
  for (const std::string& a : part.arguments) call += (call.empty() ? "" : ", ") + a;
  return "  Part::part" + std::to_string(p) + "(" + call + ");\n";
}

std::string with_separators(long v) {
  std::string digits = std::to_string(v), out;
  for (std::size_t i = 0; i < digits.size(); ++i) {
    if (i > 0 && (digits.size() - i) % 3 == 0) out += ',';
    out += digits[i];
  }
  return out;
}

}  // namespace

std::string SplitBody::note() const {
  if (parts <= 1) return "";
  return " [split in " + std::to_string(parts) + " functions, " + with_separators(stack_bytes) +
         " bytes of stack between them]";
}

SplitBody split_kernel(const PrintedKernel& printed, const KernelSignature& signature,
                       const ScalarType& scalar, int threshold, const std::vector<KernelArgument>& arrays) {
  SplitBody unchanged{printed.body, 1, 0};
  const long total = total_operations(printed.statements);
  if (threshold <= 0 || total <= threshold) return unchanged;
  std::vector<KernelArgument> parameters = arguments(signature);
  parameters.insert(parameters.end(), arrays.begin(), arrays.end());
  std::set<std::string> argument_names;
  for (const KernelArgument& a : parameters) argument_names.insert(a.name);
  if (argument_names.count(kWorkspace)) return unchanged;
  for (const Statement& s : printed.statements)
    for (const std::string& input : s.inputs)
      if (!argument_names.count(root(input))) return unchanged;  // a local of the caller
  const long part_operations = std::min<long>(threshold, kPartOperations);
  const Layout layout = lay_out(printed.statements, part_operations, argument_names);
  std::string parts, calls, after;
  for (int p = 0; p < layout.parts; ++p) {
    const Part part = part_function(printed, layout, p, parameters, scalar);
    parts += part.function;
    calls += part_call(part, p);
  }
  for (const auto& [i, slot] : layout.local_slot)
    after += "  " + printed.statements[i].target + " = " + slot_text(slot) + ";\n";
  SplitBody split;
  split.parts = layout.parts;
  split.stack_bytes = static_cast<long>(layout.slots) * (scalar.is_double() ? 8 : 4);
  split.body = "  // " + std::to_string(total) + " operations in " + std::to_string(layout.parts) +
               " functions of about " + std::to_string(part_operations) +
               " at most (kanegen generate --split-threshold): the compile\n"
               "  // time grows linearly; w holds the " +
               std::to_string(layout.slots) + " values passed between them (" +
               with_separators(split.stack_bytes) + " bytes of stack).\n  struct Part {\n" + parts +
               "  };\n" +
               (layout.slots > 0 ? "  " + std::string(scalar.name()) + " " + kWorkspace + "[" +
                                       std::to_string(layout.slots) + "];\n"
                                 : "") +
               calls + after;
  return split;
}

}  // namespace kanegen::codegen
