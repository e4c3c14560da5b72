// SPDX-License-Identifier: MIT
// The runner's command-line options as data: one table per command (name,
// value placeholder, default, help, how the value is checked) and one parser
// over it. The runner parses with it and `kanegen simulate/eval` registers its
// forwarded options from it, so the two cannot disagree on a default, a help
// line or a rule. Standard library only.
#pragma once

#include <map>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace kanegen::runtime {

/// A bad command line: the runner exits with status 2.
struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// How an option's value is checked.
enum class ValueKind {
  kFlag,             ///< no value
  kText,             ///< any text
  kNumber,           ///< a finite number (parse_number)
  kNonNegative,      ///< a number >= 0
  kPositive,         ///< a number > 0
  kPositiveInteger,  ///< an integer > 0
  kChoice,           ///< one of OptionSpec::choices
  kAssignment,       ///< NAME=VALUE, VALUE a number
  kNumberList,       ///< v1,v2,... (parse_number_list)
};

struct OptionSpec {
  const char* name;        ///< "--dt"
  const char* short_name;  ///< "-o", or "" if none
  const char* value;       ///< placeholder in the help ("H"); "" for a flag
  /// The value used when the option is not given, as text; "" if there is
  /// none (a flag, a required or repeatable option, or a model-dependent one).
  const char* default_value;
  /// How the help shows the default: nullptr "(default <default_value>)",
  /// "" nothing (the help says it), else "(default: <note>)".
  const char* default_note;
  const char* help;  ///< one line, without the default
  ValueKind kind;
  bool required = false;
  bool repeatable = false;   ///< may be given more than once; the values are kept in order
  const char* choices = "";  ///< kChoice: the allowed values, "a,b"
};

/// The options of a runner command ("simulate", "eval", "info", "batch");
/// nullptr for another name. -h/--help is implied and not in the table.
const std::vector<OptionSpec>* command_options(std::string_view command);

/// The option of `table` called `name` (long or short); nullptr if none.
const OptionSpec* find_option(const std::vector<OptionSpec>& table, std::string_view name);

/// Why `text` is not a valid value of `option` ("--dt must be positive"), or
/// "" if it is.
std::string value_error(const OptionSpec& option, const std::string& text);

/// The help of one option with its notes: "output interval (default 0.01)".
std::string option_help(const OptionSpec& option);

/// The "options:" block of a command's --help, -h/--help last.
std::string options_usage(const std::vector<OptionSpec>& table);

/// A NAME=VALUE pair of a kAssignment option.
struct Assignment {
  std::string name;
  double value;
};

/// A command line checked against a table. Getters take the long name and
/// fall back to the option's default_value when it was not given.
class ParsedOptions {
 public:
  bool help = false;  ///< -h or --help was given (parsing stopped there)

  bool given(const std::string& name) const { return values_.count(name) != 0; }
  bool flag(const std::string& name) const { return given(name); }
  /// The value given, else the default ("" if neither).
  std::string text(const std::string& name) const;
  double number(const std::string& name) const;
  long integer(const std::string& name) const;
  std::vector<double> numbers(const std::string& name) const;
  /// Every NAME=VALUE given, in order.
  std::vector<Assignment> assignments(const std::string& name) const;

 private:
  friend ParsedOptions parse_options(const std::vector<OptionSpec>&, const std::vector<std::string>&, size_t,
                                     const std::string&);
  const std::vector<OptionSpec>* table_ = nullptr;
  std::map<std::string, std::vector<std::string>> values_;  ///< by long name; flags have one ""
};

/// Parses args[first..] against `table` for `command` (as named in messages,
/// "PROG simulate"). "--name=value" is split; a single-valued option may be
/// given once; required options must be given unless help was asked.
/// Throws UsageError with the runner's messages.
ParsedOptions parse_options(const std::vector<OptionSpec>& table, const std::vector<std::string>& args,
                            size_t first, const std::string& command);

}  // namespace kanegen::runtime
