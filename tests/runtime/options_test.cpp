// SPDX-License-Identifier: GPL-2.0-or-later
// The runner's option tables (options.hpp): well formed, defaults that pass
// their own checks and agree with IntegrationOptions, and the parser's rules.
#include "kanegen/runtime/options.hpp"

#include <catch2/catch.hpp>
#include <set>
#include <string>
#include <vector>

#include "kanegen/runtime/genalpha.hpp"
#include "kanegen/runtime/integrators.hpp"
#include "kanegen/runtime/methods.hpp"

namespace {

using kanegen::runtime::command_options;
using kanegen::runtime::OptionSpec;
using kanegen::runtime::ParsedOptions;
using kanegen::runtime::UsageError;
using kanegen::runtime::ValueKind;

// The registry's names (methods.hpp) as the unknown-integrator message lists
// them: a new method changes the message, not this test.
std::string known_integrators() {
  std::string known;
  for (const std::string& name : kanegen::runtime::method_names())
    known += (known.empty() ? "" : ", ") + name;
  return known;
}

ParsedOptions parse(const std::string& command, std::vector<std::string> args) {
  args.insert(args.begin(), {"runner", command});
  return kanegen::runtime::parse_options(*command_options(command), args, 2, "runner " + command);
}

std::string parse_error(const std::string& command, const std::vector<std::string>& args) {
  try {
    parse(command, args);
  } catch (const UsageError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("each runner command's option table is well formed", "[options]") {
  for (const char* command : {"simulate", "eval", "info", "batch"}) {
    INFO(command);
    const std::vector<OptionSpec>* table = command_options(command);
    REQUIRE(table != nullptr);
    std::set<std::string> names;
    for (const OptionSpec& o : *table) {
      INFO(o.name);
      CHECK(std::string(o.name).rfind("--", 0) == 0);
      CHECK(names.insert(o.name).second);
      if (*o.short_name != '\0') CHECK(names.insert(o.short_name).second);
      CHECK(*o.help != '\0');
      CHECK((*o.value == '\0') == (o.kind == ValueKind::kFlag));
      // A default, or the reason there is none.
      const bool explained = o.default_note != nullptr && *o.default_note != '\0';
      CHECK((o.kind == ValueKind::kFlag || o.required || o.repeatable || *o.default_value != '\0' ||
             explained));
      if (*o.default_value != '\0') CHECK(kanegen::runtime::value_error(o, o.default_value).empty());
      if (o.kind == ValueKind::kChoice) CHECK(*o.choices != '\0');
      // The help shows the default: the runner's --help and kanegen's come from option_help.
      CHECK(kanegen::runtime::options_usage(*table).find(kanegen::runtime::option_help(o)) !=
            std::string::npos);
    }
    CHECK(names.count("--help") == 0);
    CHECK(names.count("-h") == 0);
  }
  CHECK(command_options("fly") == nullptr);
}

TEST_CASE("simulate's defaults are IntegrationOptions' defaults", "[options]") {
  const ParsedOptions p = parse("simulate", {"--t-end", "1"});
  const kanegen::runtime::IntegrationOptions defaults;
  CHECK(p.number("--dt") == defaults.dt);
  CHECK(p.number("--rtol") == defaults.rtol);
  CHECK(p.number("--atol") == defaults.atol);
  CHECK(p.number("--h0") == defaults.h0);
  CHECK(p.number("--h-min") == defaults.h_min);
  CHECK(p.number("--h-max") == defaults.h_max);
  CHECK(p.integer("--max-steps") == defaults.max_steps);
  CHECK(p.integer("--max-order") == defaults.max_order);
  CHECK(p.number("--rho-inf") == kanegen::runtime::GenAlphaOptions().rho_inf);
  kanegen::runtime::Method method = kanegen::runtime::Method::kRk4;
  CHECK(kanegen::runtime::parse_method(p.text("--integrator"), &method));
  CHECK(method == kanegen::runtime::Method::kDopri5);
  CHECK(p.text("--output") == "-");
  CHECK(!p.flag("--stats"));
  CHECK(p.assignments("--set").empty());
}

TEST_CASE("the parser: given values, repeats, inline values and help", "[options]") {
  const ParsedOptions p = parse(
      "simulate", {"--t-end=2", "--set", "m=1", "--set=l=0.5", "-o", "x.csv", "--stats", "--max-steps", "7"});
  CHECK(p.number("--t-end") == 2.0);
  REQUIRE(p.assignments("--set").size() == 2);
  CHECK(p.assignments("--set")[1].name == "l");
  CHECK(p.assignments("--set")[1].value == 0.5);
  CHECK(p.text("--output") == "x.csv");
  CHECK(p.flag("--stats"));
  CHECK(p.integer("--max-steps") == 7);
  CHECK(!p.given("--dt"));
  // Help stops the scan: nothing after it is checked, not even a required option.
  CHECK(parse("simulate", {"--help", "--bogus"}).help);
  CHECK(parse("eval", {"--q", "1,2", "-h"}).numbers("--q") == std::vector<double>{1, 2});
}

TEST_CASE("the parser's messages name the option and the rule", "[options]") {
  CHECK(parse_error("simulate", {}) == "simulate needs --t-end");
  CHECK(parse_error("simulate", {"--t-end", "-1"}) == "--t-end must be >= 0");
  CHECK(parse_error("simulate", {"--t-end", "1", "--rtol", "-1e-9"}) == "--rtol must be >= 0");
  CHECK(parse_error("simulate", {"--t-end", "1", "--h-max", "-1"}) == "--h-max must be >= 0");
  CHECK(parse_error("simulate", {"--t-end", "1", "--dt", "0"}) == "--dt must be positive");
  CHECK(parse_error("simulate", {"--t-end", "1", "--max-steps", "0"}) ==
        "--max-steps needs a positive integer, got '0'");
  CHECK(parse_error("simulate", {"--t-end", "1", "--integrator", "euler"}) ==
        "unknown integrator 'euler'; known: " + known_integrators());
  CHECK(parse_error("simulate", {"--t-end", "1", "--stats=1"}) == "option --stats takes no value");
  CHECK(parse_error("simulate", {"--t-end", "1", "-o", "a", "--output", "b"}) ==
        "option --output given more than once");
  CHECK(parse_error("simulate", {"--t-end", "1", "--q0", "=1"}) == "--q0 expects NAME=VALUE, got '=1'");
  CHECK(parse_error("eval", {"--t", "x"}) == "invalid number 'x' for --t");
  CHECK(parse_error("eval", {"--q", "1,,2"}) ==
        "invalid list '1,,2' for --q (expected comma-separated numbers)");
  CHECK(parse_error("info", {"-v"}) == "unknown option '-v' for runner info (see 'runner info --help')");
  CHECK(parse_error("batch", {"x"}) == "unexpected argument 'x' for runner batch");
}
