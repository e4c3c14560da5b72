// SPDX-License-Identifier: GPL-2.0-or-later
#include "codegen/expression_graph.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>

#include "model/fnv1a.hpp"

namespace kanegen::codegen {
namespace {

std::uint64_t mix(std::uint64_t h, std::uint64_t v) {
  h ^= v + 0x9e3779b97f4a7c15ULL + (h << 6) + (h >> 2);
  return h * 0x100000001b3ULL;
}

std::uint64_t bits(double v) {
  std::uint64_t b;
  std::memcpy(&b, &v, sizeof b);
  return b;
}

}  // namespace

double ExpressionGraph::fold(const Node& n) const {
  auto arg = [&](std::size_t i) { return nodes_[n.args[i]].value; };
  switch (n.op) {
    case Op::add: {
      double s = 0;
      for (std::size_t i = 0; i < n.args.size(); ++i) s += arg(i);
      return s;
    }
    case Op::mul: {
      double p = 1;
      for (std::size_t i = 0; i < n.args.size(); ++i) p *= arg(i);
      return p;
    }
    case Op::power:
      return std::pow(arg(0), n.value);
    case Op::sqrt:
      return std::sqrt(arg(0));
    case Op::sin:
      return std::sin(arg(0));
    case Op::cos:
      return std::cos(arg(0));
    case Op::tan:
      return std::tan(arg(0));
    case Op::exp:
      return std::exp(arg(0));
    case Op::log:
      return std::log(arg(0));
    case Op::abs:
      return std::abs(arg(0));
    default:
      return n.value;
  }
}

namespace {

bool commutative(Op op) { return op == Op::add || op == Op::mul; }

}  // namespace

int ExpressionGraph::intern(Node node) {
  if (commutative(node.op)) {
    std::sort(node.args.begin(), node.args.end(), [this](int a, int b) {
      return nodes_[a].key != nodes_[b].key ? nodes_[a].key < nodes_[b].key : a < b;
    });
  }
  std::uint64_t key = mix(static_cast<std::uint64_t>(node.op) + 1, bits(node.value));
  key = mix(key, model::fnv1a(node.name));
  for (int a : node.args) key = mix(key, nodes_[a].key);
  node.key = key;
  auto [first, inserted] = first_with_key_.try_emplace(key, -1);
  if (!inserted)
    for (int id = first->second; id >= 0; id = next_with_key_[id])
      if (same(nodes_[id], node)) return id;
  nodes_.push_back(std::move(node));
  const int id = static_cast<int>(nodes_.size()) - 1;
  next_with_key_.push_back(first->second);
  first->second = id;
  return id;
}

bool ExpressionGraph::same(const Node& a, const Node& b) const {
  return a.op == b.op && bits(a.value) == bits(b.value) && a.name == b.name && a.args == b.args;
}

int ExpressionGraph::number(double v) {
  Node n;
  n.op = Op::number;
  n.value = v == 0.0 ? 0.0 : v;  // one zero, not two
  return intern(std::move(n));
}

ExpressionGraph::Term ExpressionGraph::split_coefficient(int id) {
  const Node& n = nodes_[id];
  if (n.op == Op::number) return {n.value, -1};
  if (n.op != Op::mul) return {1.0, id};
  double coefficient = 1.0;
  for (int a : n.args)
    if (nodes_[a].op == Op::number) coefficient *= nodes_[a].value;
  if (coefficient == 1.0) return {1.0, id};  // the common case: no copy of the factors
  std::vector<int> rest;
  for (int a : n.args)
    if (nodes_[a].op != Op::number) rest.push_back(a);
  if (rest.size() == 1) return {coefficient, rest[0]};
  Node base;
  base.op = Op::mul;
  base.args = std::move(rest);
  return {coefficient, intern(std::move(base))};
}

// A product in canonical form: at most one numeric coefficient, the product of
// all coefficients of the factors multiplied in sorted order (so that the
// rounding does not depend on GiNaC's operand order), and the other factors.
// A factor that is a product keeps its coefficient-free part whole (c w with
// w = -a b is -c (a b), not -c a b): the part is one node, computed once
// wherever it recurs (chain20's forward_dynamics: 8653 -> 8404 operations;
// the shipped models' sources: 0 to 4 % fewer).
int ExpressionGraph::make_mul(std::vector<int> factors) {
  std::vector<double> coefficients;
  Node n;
  n.op = Op::mul;
  for (int f : factors) {
    const Term t = split_coefficient(f);
    coefficients.push_back(t.coefficient);
    if (t.base < 0) continue;
    n.args.push_back(t.base);
  }
  std::sort(coefficients.begin(), coefficients.end());
  double c = 1.0;
  for (double x : coefficients) c *= x;
  if (c == 0.0 || n.args.empty()) return number(c);
  if (c == 1.0 && n.args.size() == 1) return n.args[0];
  if (c != 1.0) n.args.push_back(number(c));
  return intern(std::move(n));
}

// A sum in canonical form: terms ordered by their coefficient-free part, equal
// parts merged, and the sign chosen so that the first term is positive. GiNaC
// may write the same sum as a - b or as -(b - a) depending on its run-to-run
// term order; both become one node here.
int ExpressionGraph::make_add(std::vector<int> terms) {
  std::vector<Term> split;
  for (int t : terms) split.push_back(split_coefficient(t));
  auto key = [this](int base) { return base < 0 ? std::uint64_t{0} : nodes_[base].key; };
  std::sort(split.begin(), split.end(), [&](const Term& a, const Term& b) {
    if (key(a.base) != key(b.base)) return key(a.base) < key(b.base);
    if (a.base != b.base) return a.base < b.base;
    return a.coefficient < b.coefficient;
  });
  std::vector<Term> merged;
  for (const Term& t : split) {
    if (!merged.empty() && merged.back().base == t.base)
      merged.back().coefficient += t.coefficient;
    else
      merged.push_back(t);
  }
  merged.erase(
      std::remove_if(merged.begin(), merged.end(), [](const Term& t) { return t.coefficient == 0.0; }),
      merged.end());
  if (merged.empty()) return number(0.0);
  auto term_node = [this](double c, int base) {
    if (base < 0) return number(c);
    return make_mul({number(c), base});
  };
  if (merged.size() == 1) return term_node(merged[0].coefficient, merged[0].base);
  const double sign = merged[0].coefficient < 0 ? -1.0 : 1.0;
  Node n;
  n.op = Op::add;
  for (const Term& t : merged) n.args.push_back(term_node(sign * t.coefficient, t.base));
  const int sum = intern(std::move(n));
  return sign > 0 ? sum : make_mul({number(-1.0), sum});
}

int ExpressionGraph::add(const GiNaC::ex& e) { return convert(e); }

int ExpressionGraph::convert(const GiNaC::ex& e) {
  auto done = converted_.find(e);
  if (done != converted_.end()) return done->second;
  int id = -1;
  if (GiNaC::is_a<GiNaC::symbol>(e)) {
    const auto& s = GiNaC::ex_to<GiNaC::symbol>(e);
    if (const GiNaC::ex* definition = program_.definition(e)) {
      id = convert(*definition);
    } else {
      Node n;
      n.op = Op::input;
      n.name = vars_.cpp_name(s);
      if (n.name.empty()) throw std::logic_error("expression graph: unknown symbol " + s.get_name());
      id = intern(std::move(n));
    }
  } else if (GiNaC::is_a<GiNaC::numeric>(e) || GiNaC::is_a<GiNaC::constant>(e)) {
    id = number(GiNaC::ex_to<GiNaC::numeric>(GiNaC::evalf(e)).to_double());
  } else if (GiNaC::is_a<GiNaC::add>(e) || GiNaC::is_a<GiNaC::mul>(e)) {
    std::vector<int> args;
    for (std::size_t i = 0; i < e.nops(); ++i) args.push_back(convert(e.op(i)));
    id = GiNaC::is_a<GiNaC::add>(e) ? make_add(std::move(args)) : make_mul(std::move(args));
  } else if (GiNaC::is_a<GiNaC::power>(e)) {
    const GiNaC::ex exponent = e.op(1);
    if (!GiNaC::is_a<GiNaC::numeric>(exponent)) throw std::logic_error("expression graph: symbolic exponent");
    const double x = GiNaC::ex_to<GiNaC::numeric>(exponent).to_double();
    const int base = convert(e.op(0));
    const Term split = split_coefficient(base);
    Node n;
    n.op = x == 0.5 ? Op::sqrt : Op::power;
    n.value = x == 0.5 ? 0.0 : x;
    if (n.op == Op::power && std::floor(x) == x && split.base >= 0 && split.coefficient != 1.0) {
      // (c b)^k = c^k b^k: the sign GiNaC happened to give b does not show.
      n.args.push_back(split.base);
      id = make_mul({number(std::pow(split.coefficient, x)), intern(std::move(n))});
    } else {
      n.args.push_back(base);
      id = intern(std::move(n));
    }
  } else if (GiNaC::is_a<GiNaC::function>(e)) {
    const std::string name = GiNaC::ex_to<GiNaC::function>(e).get_name();
    static const std::map<std::string, Op> functions{{"sin", Op::sin}, {"cos", Op::cos}, {"tan", Op::tan},
                                                     {"exp", Op::exp}, {"log", Op::log}, {"abs", Op::abs}};
    auto f = functions.find(name);
    if (f == functions.end()) throw std::logic_error("expression graph: unsupported function " + name);
    Node n;
    n.op = f->second;
    n.args.push_back(convert(e.op(0)));
    id = intern(std::move(n));
  } else {
    throw std::logic_error("expression graph: unsupported expression");
  }
  id = folded(id);
  converted_.emplace(e, id);
  return id;
}

// Constant subexpressions (e.g. sqrt(3)/2) fold to one number.
int ExpressionGraph::folded(int id) {
  const Node& made = nodes_[id];
  if (made.op == Op::number || made.op == Op::input) return id;
  for (int a : made.args)
    if (nodes_[a].op != Op::number) return id;
  return number(fold(made));
}

int ExpressionGraph::input(const std::string& cpp_name) {
  Node n;
  n.op = Op::input;
  n.name = cpp_name;
  return intern(std::move(n));
}

int ExpressionGraph::apply(Op op, int arg, double value) {
  if (op == Op::power && value == 0.0) return number(1.0);
  if (op == Op::power && value == 1.0) return arg;
  if (op == Op::power && value == 0.5) return apply(Op::sqrt, arg);
  Node n;
  n.op = op;
  n.value = op == Op::power ? value : 0.0;
  n.args.push_back(arg);
  return folded(intern(std::move(n)));
}

}  // namespace kanegen::codegen
