// SPDX-License-Identifier: GPL-2.0-or-later
#include "codegen/cpp_printer.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <map>
#include <numeric>
#include <set>

#include "codegen/statement_order.hpp"

namespace kanegen::codegen {

namespace {

/// The number of significant digits of the shortest decimal that reads back
/// as v (std::to_chars's shortest scientific form), so that the search for
/// the %g precision below starts where it ends: the same text as a search
/// from 1, in one or two tries instead of up to 17 (literals are a large
/// part of a big model's generation time).
int shortest_digits(double v) {
  char buffer[40];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, v, std::chars_format::scientific);
  if (result.ec != std::errc()) return 1;
  int digits = 0;
  for (const char* c = buffer; c != result.ptr && *c != 'e'; ++c)
    digits += std::isdigit(static_cast<unsigned char>(*c)) ? 1 : 0;
  return digits < 1 ? 1 : digits;
}

}  // namespace

std::string format_double(double v) {
  char buffer[40];
  for (int precision = std::isfinite(v) ? shortest_digits(v) : 1; precision <= 17; ++precision) {
    std::snprintf(buffer, sizeof buffer, "%.*g", precision, v);
    if (std::strtod(buffer, nullptr) == v) break;
  }
  std::string s = buffer;
  if (s.find_first_of(".einf") == std::string::npos) s += ".0";
  return s;
}

namespace {

bool is_leaf(const Node& n) { return n.op == Op::number || n.op == Op::input; }
bool is_integer(double x) { return std::floor(x) == x && std::abs(x) < 64; }

class Printer {
 public:
  Printer(const ExpressionGraph& graph, const std::string& indent, const std::string& prefix,
          const ScalarType& scalar)
      : graph_(graph),
        indent_(indent),
        prefix_(prefix),
        scalar_(scalar),
        uses_(graph.size(), 0),
        temps_(graph.size(), -1),
        planned_at_(graph.size(), -1) {}

  PrintedKernel run(const std::vector<Assignment>& assignments) {
    out_.temp_prefix = prefix_;
    for (const Assignment& a : assignments) count_uses(a.node);
    out_.operations -= shared_multiplications();
    // The printer's order: each temporary just before its first use. Then
    // the order that keeps fewer values live (statement_order.hpp), unless
    // the kernel reads what it assigns, where the order is the meaning.
    std::vector<Planned> plan;
    for (std::size_t i = 0; i < assignments.size(); ++i) {
      plan_temporaries(assignments[i].node, plan);
      plan.push_back({assignments[i].node, static_cast<int>(i)});
    }
    std::vector<int> order(plan.size());
    std::iota(order.begin(), order.end(), 0);
    if (!reads_own_targets(assignments)) order = shorten_live_ranges(dependencies(plan));
    for (int k : order) {
      const Planned& item = plan[k];
      if (item.assignment < 0) {
        Statement s = statement(item.node, true);
        s.temporary = temporaries_;
        temps_[item.node] = temporaries_++;
        out_.body +=
            indent_ + "const " + scalar_.name() + " " + temp_name(item.node) + " = " + s.expression + ";\n";
        out_.statements.push_back(std::move(s));
      } else {
        const Assignment& a = assignments[item.assignment];
        Statement s = statement(a.node, false);
        s.target = a.target;
        out_.body += indent_ + a.target + " = " + s.expression + ";\n";
        out_.statements.push_back(std::move(s));
      }
    }
    out_.temporaries = temporaries_;
    return out_;
  }

  long count(const std::vector<Assignment>& assignments) {
    for (const Assignment& a : assignments) count_uses(a.node);
    return out_.operations - shared_multiplications();
  }

 private:
  const Node& node(int id) const { return graph_.node(id); }

  // Counts references; a node first reached is costed once, as the emitted
  // code evaluates it once (temporary or inlined at its single use).
  void count_uses(int id) {
    if (uses_[id]++ > 0) return;
    const Node& n = node(id);
    out_.operations += cost(n);
    for (int a : n.args) count_uses(a);
    // A power's base is repeated in the printed product: give it a name.
    if (n.op == Op::power && !is_leaf(node(n.args[0]))) uses_[n.args[0]] += 1;
  }

  long cost(const Node& n) const {
    const long k = static_cast<long>(n.args.size());
    switch (n.op) {
      case Op::number:
      case Op::input: return 0;
      case Op::add: return k - 1;
      case Op::mul: {
        long c = k - 1;
        for (int a : n.args)
          if (node(a).op == Op::number && std::abs(node(a).value) == 1.0) --c;
        return c < 0 ? 0 : c;
      }
      case Op::power: {
        if (!is_integer(n.value)) return 1;
        const long e = std::labs(static_cast<long>(n.value));
        return (e - 1) + (n.value < 0 ? 1 : 0);
      }
      default: return 1;
    }
  }

  bool wants_temp(int id) const {
    const Node& n = node(id);
    return !is_leaf(n) && uses_[id] > 1;
  }

  /// A statement to print: a temporary's definition (assignment -1) or an assignment.
  struct Planned {
    int node;
    int assignment;
  };

  void plan_temporaries(int id, std::vector<Planned>& plan) {
    if (planned_at_[id] >= 0 || is_leaf(node(id))) return;
    for (int a : node(id).args) plan_temporaries(a, plan);
    if (wants_temp(id)) {
      planned_at_[id] = static_cast<int>(plan.size());
      plan.push_back({id, -1});
    }
  }

  /// The temporaries (as plan indices) that the text of node `id` reads where it is used.
  void collect_reads(int id, std::vector<int>& reads) const {
    if (is_leaf(node(id))) return;
    if (wants_temp(id)) {
      reads.push_back(planned_at_[id]);
      return;
    }
    for (int a : node(id).args) collect_reads(a, reads);
  }

  std::vector<OrderedStatement> dependencies(const std::vector<Planned>& plan) const {
    std::vector<OrderedStatement> statements(plan.size());
    for (std::size_t k = 0; k < plan.size(); ++k) {
      std::vector<int>& reads = statements[k].reads;
      if (plan[k].assignment < 0) {
        for (int a : node(plan[k].node).args) collect_reads(a, reads);
        statements[k].defines = true;
      } else {
        collect_reads(plan[k].node, reads);
      }
      std::sort(reads.begin(), reads.end());
      reads.erase(std::unique(reads.begin(), reads.end()), reads.end());
    }
    return statements;
  }

  /// An assignment's target that another statement reads, or a target
  /// assigned twice ("udot" of "udot[3]", "m0_0" of "const double m0_0").
  bool reads_own_targets(const std::vector<Assignment>& assignments) const {
    auto root = [](const std::string& s) {
      const std::size_t begin = s.find_last_of(' ') == std::string::npos ? 0 : s.find_last_of(' ') + 1;
      return s.substr(begin, s.find_first_of("[.", begin) - begin);
    };
    std::set<std::string> targets, whole;
    for (const Assignment& a : assignments) {
      targets.insert(root(a.target));
      if (!whole.insert(a.target).second) return true;
    }
    for (std::size_t id = 0; id < uses_.size(); ++id)
      if (uses_[id] > 0 && node(static_cast<int>(id)).op == Op::input &&
          targets.count(root(node(static_cast<int>(id)).name)))
        return true;
    return false;
  }

  // The statement of node `id`, with the temporaries and inputs its text reads
  // (a temporary's own defining text is its expression, not its name).
  Statement statement(int id, bool defining) {
    read_temps_.clear();
    read_inputs_.clear();
    read_operations_ = 0;
    Statement s;
    s.expression = defining ? expression(id) : text(id);
    s.operations = read_operations_;
    s.temporaries.assign(read_temps_.begin(), read_temps_.end());
    s.inputs.assign(read_inputs_.begin(), read_inputs_.end());
    return s;
  }

  // The text of a node where it is used: its temporary's name if it has one.
  std::string text(int id) const {
    if (!has_temp(id)) return expression(id);
    read_temps_.insert(temps_[id]);
    return temp_name(id);
  }
  bool has_temp(int id) const { return temps_[id] >= 0; }
  std::string temp_name(int id) const { return prefix_ + std::to_string(temps_[id]); }

  // Text safe to use as a factor of a product.
  std::string factor(int id) const {
    const Node& n = node(id);
    const std::string s = text(id);
    if (has_temp(id)) return s;
    if (n.op == Op::add || n.op == Op::mul || (n.op == Op::number && n.value < 0) ||
        (n.op == Op::power && n.value < 0))
      return "(" + s + ")";
    return s;
  }

  // A product split into sign, magnitude of the coefficient, and factors.
  std::string product(const Node& n, bool& negative) const {
    double coefficient = 1.0;
    std::vector<std::string> numerator, denominator;
    for (int a : n.args) {
      const Node& f = node(a);
      if (f.op == Op::number) {
        coefficient *= f.value;
      } else if (f.op == Op::power && is_integer(f.value) && f.value < 0 && !has_temp(a)) {
        denominator.push_back(repeated(f.args[0], static_cast<long>(-f.value)));
      } else {
        numerator.push_back(factor(a));
      }
    }
    negative = coefficient < 0;
    const double magnitude = std::abs(coefficient);
    std::string s;
    if (magnitude != 1.0 || numerator.empty()) s = scalar_.literal(magnitude);
    for (const std::string& f : numerator) s += (s.empty() ? "" : "*") + f;
    if (!denominator.empty()) {
      std::string d;
      for (const std::string& f : denominator) d += (d.empty() ? "" : "*") + f;
      s += "/" + (denominator.size() > 1 || d.find('*') != std::string::npos ? "(" + d + ")" : d);
    }
    return s;
  }

  std::string repeated(int base, long times) const {
    std::string b = factor(base), s = b;
    for (long i = 1; i < times; ++i) s += "*" + b;
    return s;
  }

  // When a node's value is ready, in cycles of a machine that runs every
  // operation as soon as its operands are (additions and multiplications 3,
  // a division 13, a library call 40): the longest path of latencies to it.
  double readiness(int id) const {
    if (ready_.empty()) ready_.assign(graph_.size(), -1.0);
    double& r = ready_[id];
    if (r >= 0) return r;
    const Node& n = node(id);
    switch (n.op) {
      case Op::number:
      case Op::input:
        r = 0;
        break;
      case Op::add:
      case Op::mul: {
        std::vector<double> operands;
        for (int a : n.args)
          if (node(a).op != Op::number) operands.push_back(readiness(a));
        std::sort(operands.begin(), operands.end());
        r = operands.empty() ? 0 : operands[0];
        for (std::size_t k = 1; k < operands.size(); ++k) r = std::max(r, operands[k]) + 3;
        if (n.op == Op::mul && operands.size() < n.args.size()) r += 3;  // the coefficient
        break;
      }
      case Op::power: {
        const long e = is_integer(n.value) ? std::labs(static_cast<long>(n.value)) : 1;
        r = readiness(n.args[0]) + 3 * static_cast<double>(e - 1) + (n.value < 0 ? 13 : 0);
        break;
      }
      default:
        r = readiness(n.args[0]) + 40;
        break;
    }
    return r;
  }

  // A sum's terms, the earliest ready first: C++ adds from the left, so the
  // term ready last waits for one addition, not for the whole sum.
  std::vector<int> by_readiness(const std::vector<int>& args) const {
    std::vector<int> order = args;
    std::stable_sort(order.begin(), order.end(),
                     [this](int a, int b) { return readiness(a) < readiness(b); });
    return order;
  }

  // The numeric coefficient of a product, or 0 when its text would not be
  // the coefficient times its factors (no factor, or a divisor).
  double plain_coefficient(const Node& n) const {
    double coefficient = 1.0;
    bool factors = false;
    for (int a : n.args) {
      const Node& f = node(a);
      if (f.op == Op::number)
        coefficient *= f.value;
      else if (f.op == Op::power && is_integer(f.value) && f.value < 0 && !wants_temp(a))
        return 0;
      else
        factors = true;
    }
    return factors ? coefficient : 0;
  }

  // A sum's terms printed in place by their coefficient: |coefficient| ->
  // how many of its terms have it (products other than +-1 times factors).
  std::map<double, int> coefficients(const Node& sum) const {
    std::map<double, int> terms;
    for (int a : sum.args)
      if (node(a).op == Op::mul && !wants_temp(a))
        if (const double c = std::abs(plain_coefficient(node(a))); c != 0 && c != 1) ++terms[c];
    return terms;
  }

  // The multiplications that sums save by sharing a coefficient (sum()):
  // the count is of the code as printed.
  long shared_multiplications() const {
    long shared = 0;
    for (std::size_t id = 0; id < graph_.size(); ++id)
      if (uses_[id] > 0 && node(static_cast<int>(id)).op == Op::add)
        for (const auto& entry : coefficients(node(static_cast<int>(id)))) shared += entry.second - 1;
    return shared;
  }

  // The factors of such a product, without its coefficient.
  std::string factors_text(const Node& n) const {
    std::string s;
    for (int a : n.args)
      if (node(a).op != Op::number) s += (s.empty() ? "" : "*") + factor(a);
    return s;
  }

  // A sum's text, its terms the earliest ready first; `negated`: of minus the
  // sum, each term's sign flipped (the same value: negating is exact). Terms
  // with the same coefficient (other than +-1) share one multiplication,
  // c*(a + b) for c*a + c*b, placed where the last of them is ready.
  std::string sum(const Node& n, bool negated) const {
    const std::map<double, int> sharing = coefficients(n);
    struct Item {
      double ready;
      std::string text;
      bool negative;
    };
    std::vector<Item> items;
    std::map<double, std::size_t> group;  // |coefficient| -> its item
    for (int a : by_readiness(n.args)) {
      const Node& term = node(a);
      if (term.op == Op::mul && !has_temp(a)) {
        read_operations_ += cost(term);
        const double c = plain_coefficient(term);
        if (const auto shared = sharing.find(std::abs(c)); shared != sharing.end() && shared->second > 1) {
          const bool negative = (c < 0) != negated;
          const std::string t = factors_text(term);
          auto [it, first] = group.emplace(std::abs(c), items.size());
          if (first) {
            items.push_back({readiness(a), t, negative});
          } else {
            read_operations_ -= 1;  // the coefficient's multiplication, shared
            Item& g = items[it->second];
            g.ready = std::max(g.ready, readiness(a));
            g.text += (negative != g.negative ? " - " : " + ") + t;
          }
          continue;
        }
        bool negative = false;
        const std::string t = product(term, negative);
        items.push_back({readiness(a), t, negative != negated});
      } else if (term.op == Op::number) {
        items.push_back({0, scalar_.literal(std::abs(term.value)), (term.value < 0) != negated});
      } else if (term.op == Op::add && !has_temp(a)) {
        // A sum in the sum is spliced in as it is (its terms continue the
        // outer sum's order of additions), its signs flipped with the outer's.
        // Its leading sign becomes the item's: a + -b is printed a - b.
        read_operations_ += cost(term);
        const std::string t = sum(term, negated);
        if (t[0] == '-')
          items.push_back({readiness(a), t.substr(1), true});
        else
          items.push_back({readiness(a), t, false});
      } else {
        items.push_back({readiness(a), text(a), negated});
      }
    }
    for (const auto& [c, k] : group) items[k].text = scalar_.literal(c) + "*(" + items[k].text + ")";
    std::stable_sort(items.begin(), items.end(),
                     [](const Item& a, const Item& b) { return a.ready < b.ready; });
    std::string s;
    for (const Item& item : items) {
      if (s.empty())
        s = item.negative ? "-" + item.text : item.text;
      else
        s += (item.negative ? " - " : " + ") + item.text;
    }
    return s;
  }

  // For a product -1 * s with s a sum printed in place: s, else -1.
  // Printed as -(c - q), g++ folds cos(-x) to cos(x) but not sin's, and the
  // two calls of one angle no longer share an argument to become one sincos.
  int negated_sum(const Node& n) const {
    if (n.args.size() != 2) return -1;
    for (int k = 0; k < 2; ++k) {
      const int a = n.args[k], b = n.args[1 - k];
      if (node(a).op == Op::number && node(a).value == -1.0 && node(b).op == Op::add && !has_temp(b))
        return b;
    }
    return -1;
  }

  // The <math.h> function (not <cmath>'s std::): the kernels compile freestanding.
  std::string call(const char* f, const Node& n) const {
    return scalar_.function(f) + "(" + text(n.args[0]) + ")";
  }

  std::string expression(int id) const {
    const Node& n = node(id);
    read_operations_ += cost(n);
    switch (n.op) {
      case Op::number: return scalar_.literal(n.value);
      case Op::input:
        read_inputs_.insert(n.name);
        return n.name;
      case Op::add: return sum(n, false);
      case Op::mul: {
        if (const int s = negated_sum(n); s >= 0) {
          read_operations_ += cost(node(s));
          return sum(node(s), true);
        }
        bool negative = false;
        const std::string s = product(n, negative);
        return negative ? "-" + s : s;
      }
      case Op::power: {
        if (is_integer(n.value) && n.value > 0) return repeated(n.args[0], static_cast<long>(n.value));
        if (is_integer(n.value))
          return scalar_.literal(1.0) + "/(" + repeated(n.args[0], static_cast<long>(-n.value)) + ")";
        return scalar_.function("pow") + "(" + text(n.args[0]) + ", " + scalar_.literal(n.value) + ")";
      }
      case Op::sqrt: return call("sqrt", n);
      case Op::sin: return call("sin", n);
      case Op::cos: return call("cos", n);
      case Op::tan: return call("tan", n);
      case Op::exp: return call("exp", n);
      case Op::log: return call("log", n);
      case Op::abs: return call("fabs", n);
    }
    return "";
  }

  const ExpressionGraph& graph_;
  std::string indent_, prefix_;
  ScalarType scalar_;
  // Indexed by node: a kernel's uses and temporaries' numbers (-1 for none),
  // where ordered maps cost a logarithm on every lookup of a large graph.
  std::vector<int> uses_;
  std::vector<int> temps_;
  std::vector<int> planned_at_;  ///< a temporary's index in the plan
  int temporaries_ = 0;
  // What the statement being printed reads (filled by the const text functions).
  mutable std::set<int> read_temps_;
  mutable std::set<std::string> read_inputs_;
  mutable long read_operations_ = 0;
  mutable std::vector<double> ready_;  ///< readiness() by node, -1 until computed
  PrintedKernel out_;
};

}  // namespace

PrintedKernel print_kernel(const ExpressionGraph& graph, const std::vector<Assignment>& assignments,
                           const ScalarType& scalar, const std::string& indent,
                           const std::string& temp_prefix) {
  return Printer(graph, indent, temp_prefix, scalar).run(assignments);
}

long count_operations(const ExpressionGraph& graph, const std::vector<Assignment>& assignments) {
  return Printer(graph, "", "", ScalarType()).count(assignments);
}

}  // namespace kanegen::codegen
