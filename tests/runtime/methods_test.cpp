// SPDX-License-Identifier: GPL-2.0-or-later
// The registry of methods (methods.hpp) is the one list of integrators:
// every row parses, the runner's --integrator help, choices and error list
// exactly its names, the option helps that name methods follow its
// properties, and the properties agree with the row's kind. (Every row
// running a simulation: implicit_test.cpp in-process, tests/cli on a
// shipped model.)
#include "kanegen/runtime/methods.hpp"

#include <catch2/catch.hpp>
#include <regex>
#include <string>
#include <vector>

#include "kanegen/runtime/integrators.hpp"
#include "kanegen/runtime/options.hpp"

namespace {

using namespace kanegen::runtime;

std::string join(const std::vector<std::string>& names, const std::string& sep) {
  std::string text;
  for (const std::string& n : names) text += (text.empty() ? "" : sep) + n;
  return text;
}

const OptionSpec& simulate_option(const char* name) {
  const OptionSpec* o = find_option(*command_options("simulate"), name);
  REQUIRE(o != nullptr);
  return *o;
}

// The names the --integrator help describes, "name (" each, in order.
std::vector<std::string> described_names() {
  const std::string help = option_help(simulate_option("--integrator"));
  static const std::regex entry("(?:^|, | or )([a-z0-9_]+) \\(");
  std::vector<std::string> names;
  for (auto it = std::sregex_iterator(help.begin(), help.end(), entry); it != std::sregex_iterator(); ++it)
    names.push_back((*it)[1]);
  return names;
}

std::string parse_error(const std::vector<std::string>& args) {
  std::vector<std::string> argv = {"runner", "simulate"};
  argv.insert(argv.end(), args.begin(), args.end());
  try {
    parse_options(*command_options("simulate"), argv, 2, "runner simulate");
  } catch (const UsageError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("methods: every row's name parses to its row and back", "[methods]") {
  REQUIRE(kMethodCount == method_names().size());
  for (const MethodSpec& m : kMethods) {
    INFO(m.name);
    Method parsed = m.method == Method::kRk4 ? Method::kDopri5 : Method::kRk4;
    CHECK(parse_method(m.name, &parsed));
    CHECK(parsed == m.method);
    CHECK(std::string(method_name(m.method)) == m.name);
    CHECK(find_method(m.name) == &m);
    CHECK(&method_spec(m.method) == &m);
  }
  Method untouched = Method::kBdf;
  CHECK(!parse_method("euler", &untouched));
  CHECK(untouched == Method::kBdf);
  CHECK(find_method("") == nullptr);
}

TEST_CASE("methods: the properties agree with the kind, an alias with its target", "[methods]") {
  for (const MethodSpec& m : kMethods) {
    INFO(m.name);
    const bool fixed_step =
        m.kind == MethodKind::kExplicitFixedStep || m.kind == MethodKind::kImplicitFixedStep;
    CHECK(m.needs_jacobians == is_implicit(m.kind));
    CHECK(m.steps_by_dt == fixed_step);
    CHECK(m.takes_tolerances == !fixed_step);
    CHECK(*m.description != '\0');
    if (m.alias_of != m.method) {  // an alias: no entry of its own, the properties of what it selects
      const MethodSpec& target = resolved_spec(m.method);
      CHECK(m.ode == nullptr);
      CHECK(m.model == nullptr);
      CHECK(m.kind == target.kind);
      CHECK(m.needs_jacobians == target.needs_jacobians);
      CHECK(m.steps_by_dt == target.steps_by_dt);
      CHECK(m.takes_tolerances == target.takes_tolerances);
      CHECK(m.not_in_fmu == nullptr);  // an FMU carries an alias if it carries its target
    } else {                           // exactly one entry: an ODE method or one that steps the Model
      CHECK((m.ode == nullptr) != (m.model == nullptr));
      // An FMU's DoStep integrates from any communication point: a method that steps a whole run cannot.
      if (m.model != nullptr) CHECK(m.not_in_fmu != nullptr);
    }
    if (m.not_in_fmu != nullptr) CHECK(*m.not_in_fmu != '\0');
  }
  CHECK(implicit_method() == method_spec(Method::kImplicit).alias_of);
  CHECK(method_spec(kDefaultMethod).alias_of == kDefaultMethod);
}

TEST_CASE("methods: the runner's --integrator help, choices and error list exactly the table", "[methods]") {
  const OptionSpec& integrator = simulate_option("--integrator");
  CHECK(described_names() == method_names());
  CHECK(std::string(integrator.choices) == join(method_names(), ","));
  CHECK(std::string(integrator.default_value) == method_name(kDefaultMethod));
  CHECK(parse_error({"--t-end", "1", "--integrator", "euler"}) ==
        "unknown integrator 'euler'; known: " + join(method_names(), ", "));
  for (const MethodSpec& m : kMethods) {
    INFO(m.name);
    CHECK(parse_error({"--t-end", "1", "--integrator", m.name}).empty());
    const std::string help = option_help(integrator);
    CHECK(help.find(std::string(m.name) + " (" + m.description) != std::string::npos);
    if (m.alias_of != m.method)
      CHECK(help.find(std::string("; it is ") + method_name(m.alias_of)) != std::string::npos);
  }
}

TEST_CASE("methods: the option helps that name methods follow the table", "[methods]") {
  std::vector<std::string> tolerances, fixed_step;
  for (const MethodSpec& m : kMethods) {
    if (m.takes_tolerances) tolerances.emplace_back(m.name);
    if (m.steps_by_dt) fixed_step.emplace_back(m.name);
  }
  const std::string adaptive = join(tolerances, "/");
  for (const char* option : {"--rtol", "--atol", "--h0", "--h-min", "--h-max"}) {
    INFO(option);
    CHECK(std::string(simulate_option(option).help).rfind(adaptive, 0) == 0);
  }
  for (const std::string& name : fixed_step)
    CHECK(std::string(simulate_option("--dt").help).find(name) != std::string::npos);
}

TEST_CASE("methods: integrate() refuses what the row cannot run", "[methods]") {
  const Rhs rhs = [](double, const double* x, double* xdot) {
    xdot[0] = -x[0];
    return true;
  };
  IntegrationOptions opt;
  for (const MethodSpec& m : kMethods) {
    INFO(m.name);
    std::vector<double> x = {1.0};
    const IntegrationResult r = integrate(m.method, rhs, 0.0, x.data(), 1, opt, nullptr);
    const MethodSpec& runs = resolved_spec(m.method);
    // Without a Jacobian only the explicit ODE methods run.
    CHECK(r.ok() == (runs.ode != nullptr && !runs.needs_jacobians));
    if (!r.ok()) CHECK(r.status == Status::kInvalidArgument);
  }
}
