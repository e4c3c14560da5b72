// SPDX-License-Identifier: MIT
// The runner's option tables and the one parser over them (options.hpp).
#include "kanegen/runtime/options.hpp"

#include <algorithm>
#include <optional>
#include <set>
#include <utility>

#include "kanegen/runtime/methods.hpp"
#include "kanegen/runtime/text.hpp"

namespace kanegen::runtime {
namespace {

using K = ValueKind;

// ---------------------------------------------------------------- the methods' help, from the registry

// The names of the methods with `property`, in table order: "a/b/c" with
// sep = last = "/", or "a, b and c".
std::string method_list(bool (*property)(const MethodSpec&), const char* sep, const char* last) {
  std::vector<std::string> names;
  for (const MethodSpec& m : kMethods)
    if (property(m)) names.emplace_back(m.name);
  std::string text;
  for (size_t i = 0; i < names.size(); ++i)
    text += (i == 0 ? "" : i + 1 == names.size() ? last : sep) + names[i];
  return text;
}

// --integrator's help: every method with its description, the default and what an alias selects.
std::string integrator_help() {
  std::string text;
  for (size_t i = 0; i < kMethodCount; ++i) {
    const MethodSpec& m = kMethods[i];
    text += std::string(i == 0 ? "" : i + 1 == kMethodCount ? " or " : ", ") + m.name + " (" + m.description;
    if (m.method == kDefaultMethod) text += ", default";
    if (m.alias_of != m.method) text += std::string("; it is ") + method_name(m.alias_of);
    text += ")";
  }
  return text;
}

const std::string kIntegratorChoices = method_list([](const MethodSpec&) { return true; }, ",", ",");
const std::string kIntegratorHelp = integrator_help();
const std::string kDtHelp = "output interval, also the " +
                            method_list([](const MethodSpec& m) { return m.steps_by_dt; }, ", ", " and ") +
                            " step";
// The methods --rtol, --atol, --h0, --h-min and --h-max apply to: "dopri5/implicit/radau/bdf".
const std::string kAdaptive = method_list([](const MethodSpec& m) { return m.takes_tolerances; }, "/", "/");
const std::string kRtolHelp = kAdaptive + " relative tolerance";
const std::string kAtolHelp = kAdaptive + " absolute tolerance";
const std::string kH0Help = kAdaptive + " initial step";
const std::string kHMinHelp = kAdaptive + ": fail if the step must go below H";
const std::string kHMaxHelp = kAdaptive + " largest step";
const std::string kStatsHelp =
    "after the run, print on stderr the step statistics (and Newton iterations, Jacobian evaluations and LU "
    "factorizations for " +
    method_list([](const MethodSpec& m) { return is_implicit(m.kind); }, ", ", " and ") +
    ") and a summary line: steps, final time, the largest change of T+V and, with loops, the largest loop "
    "residual";

// The defaults of simulate are IntegrationOptions' (integrators.hpp); a unit
// test holds the two together. --max-steps is 10 million, what `kanegen
// simulate` has always passed: explicit dopri5 on a flexible model takes
// more than 100000 steps for a few seconds of motion.
const std::vector<OptionSpec> kSimulate = {
    {"--t-end", "", "T", "", nullptr, "final time", K::kNonNegative, true},
    {"--dt", "", "H", "0.01", nullptr, kDtHelp.c_str(), K::kPositive},
    {"--integrator", "", "NAME", method_spec(kDefaultMethod).name, "", kIntegratorHelp.c_str(), K::kChoice,
     false, false, kIntegratorChoices.c_str()},
    {"--rho-inf", "", "R", "0.8", nullptr, "genalpha: spectral radius at infinity in [0, 1] (1: no damping)",
     K::kNonNegative},
    {"--max-order", "", "K", "2", nullptr,
     "bdf: highest BDF order, 1 to 5 (orders above 2 are not A-stable: elastic links crawl)",
     K::kPositiveInteger},
    {"--rtol", "", "R", "1e-8", nullptr, kRtolHelp.c_str(), K::kNonNegative},
    {"--atol", "", "A", "1e-10", nullptr, kAtolHelp.c_str(), K::kNonNegative},
    {"--h0", "", "H", "0", "estimated", kH0Help.c_str(), K::kNonNegative},
    {"--h-min", "", "H", "0", "round-off limit", kHMinHelp.c_str(), K::kNonNegative},
    {"--h-max", "", "H", "0", "T", kHMaxHelp.c_str(), K::kNonNegative},
    {"--max-steps", "", "N", "10000000", nullptr, "fail after N attempted steps", K::kPositiveInteger},
    {"--set", "", "NAME=VALUE", "", nullptr, "set a parameter", K::kAssignment, false, true},
    {"--q0", "", "NAME=VALUE", "", "the model's q0", "initial coordinate", K::kAssignment, false, true},
    {"--u0", "", "NAME=VALUE", "", "the model's u0", "initial speed", K::kAssignment, false, true},
    {"--output", "-o", "FILE", "-", "", "write the CSV to FILE instead of stdout", K::kText},
    {"--stats", "", "", "", nullptr, kStatsHelp.c_str(), K::kFlag},
    {"--energies", "", "", "", nullptr,
     "add kinetic_energy, potential_energy and total_energy columns, and nonconservative_work (the work "
     "W_nc of dampers, joint efforts, body-fixed forces and prescribed motions since t = 0; "
     "total_energy - nonconservative_work stays constant) for a model that has any",
     K::kFlag},
};

const std::vector<OptionSpec> kEval = {
    {"--q", "", "v1,v2,...", "", "the model's q0", "coordinates, one per coordinate", K::kNumberList},
    {"--u", "", "v1,v2,...", "", "the model's u0", "speeds, one per speed", K::kNumberList},
    {"--t", "", "T", "0", nullptr, "time", K::kNumber},
    {"--set", "", "NAME=VALUE", "", nullptr, "set a parameter", K::kAssignment, false, true},
};

const std::vector<OptionSpec> kNone;

std::string quoted(const std::string& text) { return "'" + text + "'"; }

// The number check shared by the numeric kinds: "" or the message.
std::string number_error(const std::string& option, const std::string& text, double* value) {
  return parse_number(text, value) ? "" : "invalid number " + quoted(text) + " for " + option;
}

std::string choice_error(const OptionSpec& o, const std::string& text) {
  std::vector<std::string> choices;
  for (std::string_view rest = o.choices;;) {
    const size_t comma = rest.find(',');
    choices.emplace_back(rest.substr(0, comma));
    if (comma == std::string_view::npos) break;
    rest.remove_prefix(comma + 1);
  }
  if (std::find(choices.begin(), choices.end(), text) != choices.end()) return "";
  std::string known;
  for (const std::string& c : choices) known += (known.empty() ? "" : ", ") + c;
  return "unknown " + std::string(o.name + 2) + " " + quoted(text) + "; known: " + known;
}

// Walks the arguments; "--name=value" is split into option and value.
class Scanner {
 public:
  Scanner(const std::vector<std::string>& args, size_t first, const std::string& command)
      : args_(args), next_(first), command_(command) {}

  bool done() const { return next_ >= args_.size(); }

  std::string next_option() {
    std::string arg = args_[next_++];
    inline_value_.reset();
    if (arg.rfind("--", 0) == 0) {
      if (const size_t eq = arg.find('='); eq != std::string::npos) {
        inline_value_ = arg.substr(eq + 1);
        arg.resize(eq);
      }
    }
    if (arg.empty() || arg[0] != '-')
      throw UsageError("unexpected argument " + quoted(arg) + " for " + command_);
    return arg;
  }

  std::string value(const std::string& option) {
    if (inline_value_) return *std::exchange(inline_value_, std::nullopt);
    if (done()) throw UsageError("option " + option + " needs a value");
    return args_[next_++];
  }

  // For flags: "--stats=1" is an error, not silently ignored.
  void no_value(const std::string& option) const {
    if (inline_value_) throw UsageError("option " + option + " takes no value");
  }

  [[noreturn]] void unknown(const std::string& option) const {
    throw UsageError("unknown option " + quoted(option) + " for " + command_ + " (see '" + command_ +
                     " --help')");
  }

 private:
  const std::vector<std::string>& args_;
  size_t next_;
  const std::string& command_;
  std::optional<std::string> inline_value_;
};

}  // namespace

const std::vector<OptionSpec>* command_options(std::string_view command) {
  if (command == "simulate") return &kSimulate;
  if (command == "eval") return &kEval;
  if (command == "info" || command == "batch") return &kNone;
  return nullptr;
}

const OptionSpec* find_option(const std::vector<OptionSpec>& table, std::string_view name) {
  for (const OptionSpec& o : table) {
    if (name == o.name || (*o.short_name != '\0' && name == o.short_name)) return &o;
  }
  return nullptr;
}

std::string value_error(const OptionSpec& o, const std::string& text) {
  const std::string name = o.name;
  double v = 0;
  switch (o.kind) {
    case K::kFlag:
    case K::kText:
      return "";
    case K::kNumber:
      return number_error(name, text, &v);
    case K::kNonNegative:
      if (std::string e = number_error(name, text, &v); !e.empty()) return e;
      return v >= 0 ? "" : name + " must be >= 0";
    case K::kPositive:
      if (std::string e = number_error(name, text, &v); !e.empty()) return e;
      return v > 0 ? "" : name + " must be positive";
    case K::kPositiveInteger: {
      long n = 0;
      return parse_integer(text, &n) && n > 0 ? "" : name + " needs a positive integer, got " + quoted(text);
    }
    case K::kChoice:
      return choice_error(o, text);
    case K::kAssignment: {
      const size_t eq = text.find('=');
      if (eq == std::string::npos || eq == 0) return name + " expects NAME=VALUE, got " + quoted(text);
      return number_error(name, text.substr(eq + 1), &v);
    }
    case K::kNumberList: {
      std::vector<double> values;
      return parse_number_list(text, &values)
                 ? ""
                 : "invalid list " + quoted(text) + " for " + name + " (expected comma-separated numbers)";
    }
  }
  return "";
}

std::string option_help(const OptionSpec& o) {
  std::vector<std::string> notes;
  if (o.required) notes.emplace_back("required");
  if (o.repeatable) notes.emplace_back("repeatable");
  if (o.default_note == nullptr) {
    if (*o.default_value != '\0') notes.push_back(std::string("default ") + o.default_value);
  } else if (*o.default_note != '\0') {
    notes.push_back(std::string("default: ") + o.default_note);
  }
  std::string help = o.help;
  for (size_t i = 0; i < notes.size(); ++i) help += (i == 0 ? " (" : "; ") + notes[i];
  return notes.empty() ? help : help + ")";
}

std::string options_usage(const std::vector<OptionSpec>& table) {
  const auto line = [](std::string left, const std::string& help) {
    left.resize(std::max<size_t>(left.size() + 1, 21), ' ');
    return "  " + left + help + "\n";
  };
  std::string text = "options:\n";
  for (const OptionSpec& o : table) {
    std::string left = *o.short_name != '\0' ? std::string(o.short_name) + ", " + o.name : o.name;
    if (*o.value != '\0') left += std::string(" ") + o.value;
    text += line(left, option_help(o));
  }
  return text + line("-h, --help", "show this help");
}

std::string ParsedOptions::text(const std::string& name) const {
  if (const auto it = values_.find(name); it != values_.end()) return it->second.back();
  const OptionSpec* o = table_ ? find_option(*table_, name) : nullptr;
  return o ? o->default_value : "";
}

double ParsedOptions::number(const std::string& name) const {
  double v = 0;
  if (!parse_number(text(name), &v)) throw UsageError("invalid number '" + text(name) + "' for " + name);
  return v;
}

long ParsedOptions::integer(const std::string& name) const {
  long v = 0;
  if (!parse_integer(text(name), &v)) throw UsageError(name + " needs an integer, got '" + text(name) + "'");
  return v;
}

std::vector<double> ParsedOptions::numbers(const std::string& name) const {
  std::vector<double> v;
  if (!parse_number_list(text(name), &v)) throw UsageError("invalid list '" + text(name) + "' for " + name);
  return v;
}

std::vector<Assignment> ParsedOptions::assignments(const std::string& name) const {
  std::vector<Assignment> list;
  const auto it = values_.find(name);
  if (it == values_.end()) return list;
  for (const std::string& text : it->second) {
    const size_t eq = text.find('=');
    double v = 0;
    if (eq == std::string::npos || !parse_number(std::string_view(text).substr(eq + 1), &v))
      throw UsageError(name + " expects NAME=VALUE, got '" + text + "'");
    list.push_back({text.substr(0, eq), v});
  }
  return list;
}

ParsedOptions parse_options(const std::vector<OptionSpec>& table, const std::vector<std::string>& args,
                            size_t first, const std::string& command) {
  ParsedOptions parsed;
  parsed.table_ = &table;
  Scanner scan(args, first, command);
  while (!scan.done()) {
    const std::string arg = scan.next_option();
    if (arg == "-h" || arg == "--help") {
      parsed.help = true;
      return parsed;
    }
    const OptionSpec* o = find_option(table, arg);
    if (o == nullptr) scan.unknown(arg);
    std::vector<std::string>& values = parsed.values_[o->name];
    if (o->kind == K::kFlag) {
      scan.no_value(arg);
      values.assign(1, "");
      continue;
    }
    if (!o->repeatable && !values.empty())
      throw UsageError(std::string("option ") + o->name + " given more than once");
    values.push_back(scan.value(arg));
    if (std::string e = value_error(*o, values.back()); !e.empty()) throw UsageError(e);
  }
  // "PROG simulate" -> "simulate needs --t-end"
  const std::string verb = command.substr(command.rfind(' ') + 1);
  for (const OptionSpec& o : table) {
    if (o.required && !parsed.given(o.name)) throw UsageError(verb + " needs " + o.name);
  }
  return parsed;
}

}  // namespace kanegen::runtime
