// SPDX-License-Identifier: GPL-2.0-or-later
// The expression graph's derivatives (codegen/graph_derivative.*) against
// GiNaC's own differentiation: every operation the graph has, through a
// Program intermediate, evaluated at a point; and a node that does not
// depend on the variable has the derivative 0 (no code).
#include <catch2/catch.hpp>
#include <cmath>
#include <map>
#include <string>

#include "codegen/expression_graph.hpp"
#include "codegen/graph_derivative.hpp"
#include "codegen/graph_substitution.hpp"
#include "model/load.hpp"
#include "symbolic/program.hpp"
#include "symbolic/variables.hpp"

namespace {

using kanegen::codegen::ExpressionGraph;
using kanegen::codegen::GraphDerivative;
using kanegen::codegen::Op;

/// The value of a node, its inputs taken from `inputs` by C++ name.
double value(const ExpressionGraph& g, int id, const std::map<std::string, double>& inputs) {
  const kanegen::codegen::Node& n = g.node(id);
  const auto arg = [&](std::size_t i) { return value(g, n.args[i], inputs); };
  switch (n.op) {
    case Op::number:
      return n.value;
    case Op::input:
      return inputs.at(n.name);
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
  }
  return std::nan("");
}

}  // namespace

TEST_CASE("graph derivatives agree with GiNaC's, through intermediates", "[codegen][jacobians]") {
  const kanegen::model::Model model =
      kanegen::model::load_model(KANEGEN_SOURCE_DIR "/models/double_pendulum.json");
  const kanegen::symbolic::Variables vars(model);
  kanegen::symbolic::Program program;
  const GiNaC::ex q0 = vars.q[0], q1 = vars.q[1], u0 = vars.u[0];
  // An intermediate used twice, as the Program names kinematic quantities.
  const GiNaC::ex w = program.define(GiNaC::sin(q0) * q1 + GiNaC::cos(q1) * u0);
  const GiNaC::ex e = w * w + GiNaC::pow(q1, 3) / (1 + q0 * q0) + GiNaC::sqrt(2 + GiNaC::sin(w)) +
                      GiNaC::tan(q0) * GiNaC::exp(-q1) + GiNaC::log(3 + q0 * q1) + GiNaC::abs(q0 - 2 * q1) -
                      GiNaC::pow(w, -2);
  // The same expression with the intermediate substituted, for GiNaC's diff.
  const GiNaC::ex expanded = e.subs(w == *program.definition(GiNaC::ex_to<GiNaC::symbol>(w)));

  ExpressionGraph graph(vars, program);
  const int node = graph.add(e);
  const std::map<std::string, double> inputs{{"q[0]", 0.37}, {"q[1]", -0.81}, {"u[0]", 1.3}, {"u[1]", 0.4}};
  const GiNaC::exmap at{{q0, 0.37}, {q1, -0.81}, {u0, 1.3}, {vars.u[1], 0.4}};
  for (const GiNaC::symbol& variable : {vars.q[0], vars.q[1], vars.u[0]}) {
    GraphDerivative derivative(graph, graph.add(variable));
    const double graph_value = value(graph, derivative.of(node), inputs);
    const double ginac_value =
        GiNaC::ex_to<GiNaC::numeric>(GiNaC::evalf(expanded.diff(variable).subs(at))).to_double();
    INFO(variable);
    CHECK(graph_value == Approx(ginac_value).epsilon(1e-13));
  }
  // u[1] does not occur: its derivative is the number 0.
  GraphDerivative by_u1(graph, graph.add(vars.u[1]));
  CHECK(kanegen::codegen::is_zero(graph, by_u1.of(node)));
}

TEST_CASE(
    "graph substitution replaces inputs inside intermediates, as GiNaC's subs of the inlined expression",
    "[codegen][jacobians]") {
  const kanegen::model::Model model =
      kanegen::model::load_model(KANEGEN_SOURCE_DIR "/models/double_pendulum.json");
  const kanegen::symbolic::Variables vars(model);
  kanegen::symbolic::Program program;
  const GiNaC::ex q0 = vars.q[0], q1 = vars.q[1], u0 = vars.u[0], u1 = vars.u[1];
  const GiNaC::ex w = program.define(GiNaC::sin(q0) * u0 + GiNaC::cos(q1) * u1 * u1);
  const GiNaC::ex e =
      w * w * q1 + GiNaC::sqrt(2 + GiNaC::cos(w)) + u0 * GiNaC::exp(q1) - GiNaC::pow(1 + w, -2);
  const GiNaC::ex expanded = e.subs(w == *program.definition(GiNaC::ex_to<GiNaC::symbol>(w)));

  ExpressionGraph graph(vars, program);
  const int node = graph.add(e);
  // u0 -> 0 and u1 -> the kernel argument a[1]: w's product with u0 must vanish inside w.
  kanegen::codegen::GraphSubstitution substituted(
      graph, {{graph.add(u0), graph.constant(0.0)}, {graph.add(u1), graph.input("a[1]")}});
  const int image = substituted.of(node);
  const std::map<std::string, double> inputs{
      {"q[0]", 0.37}, {"q[1]", -0.81}, {"u[0]", 1.3}, {"u[1]", 0.4}, {"a[1]", -1.7}};
  const GiNaC::exmap at{{q0, 0.37}, {q1, -0.81}, {u0, 0}, {u1, -1.7}};
  const double ginac_value = GiNaC::ex_to<GiNaC::numeric>(GiNaC::evalf(expanded.subs(at))).to_double();
  CHECK(value(graph, image, inputs) == Approx(ginac_value).epsilon(1e-14));
  // The original node is untouched, and a node without the inputs is its own image.
  const GiNaC::exmap original{{q0, 0.37}, {q1, -0.81}, {u0, 1.3}, {u1, 0.4}};
  CHECK(
      value(graph, node, inputs) ==
      Approx(GiNaC::ex_to<GiNaC::numeric>(GiNaC::evalf(expanded.subs(original))).to_double()).epsilon(1e-14));
  const int only_q = graph.add(GiNaC::sin(q0) * q1);
  CHECK(substituted.of(only_q) == only_q);
}
