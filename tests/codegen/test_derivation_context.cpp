// SPDX-License-Identifier: GPL-2.0-or-later
// The lazy derivation context (kane::DerivationContext): a product is
// derived on its first request, from the products it needs only, and once;
// the mass matrix it gives against the double pendulum's closed form; the
// kernels of a model asking it for what they need, each product once.
#include <catch2/catch.hpp>
#include <cmath>
#include <functional>
#include <map>
#include <string>

#include "codegen/expression_graph.hpp"
#include "codegen/model_kernels.hpp"
#include "kane/equations.hpp"
#include "model/load.hpp"
#include "symbolic/program.hpp"
#include "symbolic/shape_function.hpp"
#include "symbolic/variables.hpp"

namespace {

using kanegen::kane::DerivationContext;
using kanegen::kane::Product;

constexpr Product kAll[] = {Product::kinematics,       Product::bodies,
                            Product::mass_matrix,      Product::coordinates,
                            Product::joint_forces,     Product::forcing,
                            Product::energies,         Product::loops,
                            Product::inverse_dynamics, Product::generalized_momentum,
                            Product::recursion,        Product::outputs};

/// The value of `e`, its intermediates inlined from `program`, at the inputs
/// given by their C++ names ("q[1]", "p.m1").
double value(const GiNaC::ex& e, const kanegen::symbolic::Program& program,
             const kanegen::symbolic::Variables& vars, const std::map<std::string, double>& inputs) {
  if (GiNaC::is_a<GiNaC::symbol>(e)) {
    if (const GiNaC::ex* definition = program.definition(e)) return value(*definition, program, vars, inputs);
    const std::string name = vars.cpp_name(GiNaC::ex_to<GiNaC::symbol>(e));
    const auto found = inputs.find(name);
    if (found == inputs.end()) FAIL("no value for " << name);
    return found->second;
  }
  if (GiNaC::is_a<GiNaC::numeric>(e)) return GiNaC::ex_to<GiNaC::numeric>(e).to_double();
  if (GiNaC::is_a<GiNaC::add>(e) || GiNaC::is_a<GiNaC::mul>(e)) {
    const bool sum = GiNaC::is_a<GiNaC::add>(e);
    double v = sum ? 0.0 : 1.0;
    for (std::size_t i = 0; i < e.nops(); ++i) {
      const double x = value(e.op(i), program, vars, inputs);
      v = sum ? v + x : v * x;
    }
    return v;
  }
  if (GiNaC::is_a<GiNaC::power>(e))
    return std::pow(value(e.op(0), program, vars, inputs), value(e.op(1), program, vars, inputs));
  const std::string f = GiNaC::ex_to<GiNaC::function>(e).get_name();
  const double x = value(e.op(0), program, vars, inputs);
  if (f == "sin") return std::sin(x);
  if (f == "cos") return std::cos(x);
  FAIL("unexpected function " << f);
  return 0.0;
}

struct Loaded {
  kanegen::model::Model model;
  kanegen::symbolic::Variables vars;
  explicit Loaded(const std::string& name)
      : model(kanegen::model::load_model(KANEGEN_SOURCE_DIR "/models/" + name)), vars(model) {}
};

}  // namespace

TEST_CASE("the derivation context derives a product on request, from what it needs, once",
          "[codegen][context]") {
  const Loaded m("double_pendulum.json");
  kanegen::symbolic::Program program;
  DerivationContext products(m.model, m.vars, program);
  for (Product p : kAll) CHECK(products.derivations(p) == 0);
  CHECK(program.size() == 0);

  const auto& mass = products.mass_matrix();
  CHECK(products.derivations(Product::kinematics) == 1);
  CHECK(products.derivations(Product::bodies) == 1);
  CHECK(products.derivations(Product::mass_matrix) == 1);
  // M needs neither the recursions nor the joints' forces, energies, loops or outputs.
  for (Product p :
       {Product::recursion, Product::inverse_dynamics, Product::generalized_momentum, Product::joint_forces,
        Product::forcing, Product::energies, Product::loops, Product::outputs, Product::coordinates})
    CHECK(products.derivations(p) == 0);

  // Asked again: the same product, not derived again, no new intermediates.
  const std::size_t intermediates = program.size();
  CHECK(&products.mass_matrix() == &mass);
  CHECK(products.derivations(Product::mass_matrix) == 1);
  CHECK(program.size() == intermediates);

  // The recursion asks for f (and so the joints' forces) and the coordinates' names.
  CHECK(products.recursion().unavailable.empty());
  CHECK(products.derivations(Product::recursion) == 1);
  CHECK(products.derivations(Product::forcing) == 1);
  CHECK(products.derivations(Product::joint_forces) == 1);
  CHECK(products.derivations(Product::mass_matrix) == 1);
  CHECK(products.derivations(Product::inverse_dynamics) == 0);
  CHECK(products.derivations(Product::energies) == 0);
  CHECK(program.size() > intermediates);
}

TEST_CASE("the context's mass matrix is the double pendulum's closed form", "[codegen][context]") {
  // Two uniform rods of mass 1 and length 1 hinged at their ends about
  // parallel axes: M = [5/3 + cos q2, 1/3 + cos(q2)/2; ., 1/3].
  const Loaded m("double_pendulum.json");
  kanegen::symbolic::Program program;
  DerivationContext products(m.model, m.vars, program);
  for (double q2 : {0.0, 0.7, -2.1}) {
    std::map<std::string, double> inputs{{"q[0]", 0.4}, {"q[1]", q2}};
    for (const auto& p : m.model.parameters) inputs["p." + p.name] = p.value;
    const auto& mass = products.mass_matrix();
    const double expected[4] = {5.0 / 3 + std::cos(q2), 1.0 / 3 + std::cos(q2) / 2,
                                1.0 / 3 + std::cos(q2) / 2, 1.0 / 3};
    for (int k = 0; k < 4; ++k) CHECK(value(mass[k], program, m.vars, inputs) == Approx(expected[k]));
  }
}

TEST_CASE("the kernels ask the context for each product once, and not for the unneeded",
          "[codegen][context]") {
  const Loaded m("four_bar.json");
  kanegen::symbolic::Program program;
  DerivationContext products(m.model, m.vars, program);
  kanegen::codegen::ExpressionGraph graph(m.vars, program);
  const auto kernels = kanegen::codegen::derive_kernels(products, graph);
  CHECK(!kernels.empty());
  for (Product p : kAll) {
    INFO(static_cast<int>(p));
    CHECK(products.derivations(p) <= 1);
  }
  CHECK(products.derivations(Product::loops) == 1);
  // A closed loop's forward_dynamics is the saddle-point solve: no recursion.
  CHECK(products.derivations(Product::recursion) == 0);
}
