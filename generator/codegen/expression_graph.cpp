#include "codegen/expression_graph.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>

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

std::uint64_t hash_text(const std::string& s) {
  std::uint64_t h = 0xcbf29ce484222325ULL;
  for (unsigned char c : s) h = (h ^ c) * 0x100000001b3ULL;
  return h;
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
    case Op::power: return std::pow(arg(0), n.value);
    case Op::sqrt: return std::sqrt(arg(0));
    case Op::sin: return std::sin(arg(0));
    case Op::cos: return std::cos(arg(0));
    case Op::tan: return std::tan(arg(0));
    case Op::exp: return std::exp(arg(0));
    case Op::log: return std::log(arg(0));
    default: return n.value;
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
  key = mix(key, hash_text(node.name));
  for (int a : node.args) key = mix(key, nodes_[a].key);
  node.key = key;
  auto index_key = std::make_tuple(static_cast<int>(node.op), bits(node.value), node.name, node.args);
  auto it = index_.find(index_key);
  if (it != index_.end()) return it->second;
  nodes_.push_back(std::move(node));
  const int id = static_cast<int>(nodes_.size()) - 1;
  index_.emplace(std::move(index_key), id);
  return id;
}

int ExpressionGraph::number(double v) {
  Node n;
  n.op = Op::number;
  n.value = v == 0.0 ? 0.0 : v;  // one zero, not two
  return intern(std::move(n));
}

int ExpressionGraph::add(const GiNaC::ex& e) { return convert(e); }

int ExpressionGraph::convert(const GiNaC::ex& e) {
  auto done = converted_.find(e);
  if (done != converted_.end()) return done->second;
  int id = -1;
  if (GiNaC::is_a<GiNaC::symbol>(e)) {
    const auto& s = GiNaC::ex_to<GiNaC::symbol>(e);
    if (const GiNaC::ex* definition = program_.definition(s)) {
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
    Node n;
    n.op = GiNaC::is_a<GiNaC::add>(e) ? Op::add : Op::mul;
    for (std::size_t i = 0; i < e.nops(); ++i) n.args.push_back(convert(e.op(i)));
    id = intern(std::move(n));
  } else if (GiNaC::is_a<GiNaC::power>(e)) {
    const GiNaC::ex exponent = e.op(1);
    if (!GiNaC::is_a<GiNaC::numeric>(exponent)) throw std::logic_error("expression graph: symbolic exponent");
    const double x = GiNaC::ex_to<GiNaC::numeric>(exponent).to_double();
    Node n;
    if (x == 0.5) {
      n.op = Op::sqrt;
    } else {
      n.op = Op::power;
      n.value = x;
    }
    n.args.push_back(convert(e.op(0)));
    id = intern(std::move(n));
  } else if (GiNaC::is_a<GiNaC::function>(e)) {
    const std::string name = GiNaC::ex_to<GiNaC::function>(e).get_name();
    static const std::map<std::string, Op> functions{{"sin", Op::sin}, {"cos", Op::cos}, {"tan", Op::tan},
                                                     {"exp", Op::exp}, {"log", Op::log}};
    auto f = functions.find(name);
    if (f == functions.end()) throw std::logic_error("expression graph: unsupported function " + name);
    Node n;
    n.op = f->second;
    n.args.push_back(convert(e.op(0)));
    id = intern(std::move(n));
  } else {
    throw std::logic_error("expression graph: unsupported expression");
  }
  // Constant subexpressions (e.g. sqrt(3)/2) fold to one number.
  const Node& made = nodes_[id];
  if (made.op != Op::number && made.op != Op::input) {
    bool constant = true;
    for (int a : made.args) constant = constant && nodes_[a].op == Op::number;
    if (constant) id = number(fold(made));
  }
  converted_.emplace(e, id);
  return id;
}

}  // namespace kanegen::codegen
