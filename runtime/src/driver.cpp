// SPDX-License-Identifier: MIT
// The runner's command line: everything that does not depend on the model's
// type, so it is compiled once here rather than in every model executable.
#include "kanegen/runtime/driver.hpp"

#include <algorithm>
#include <csignal>
#include <memory>
#include <optional>
#include <set>
#include <stdexcept>
#include <utility>

#include "batch.hpp"
#include "kanegen/runtime/csv.hpp"
#include "kanegen/runtime/integrators.hpp"
#include "kanegen/runtime/loops.hpp"
#include "kanegen/runtime/text.hpp"

namespace kanegen::runtime {
namespace {

// A bad command line (exit code 2) or a failure while running (exit code 1).
struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};
struct RunError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

constexpr const char* kMainUsage = R"(usage: PROG <command> [options]

Runs the compiled model MODEL.

commands:
  simulate   integrate the equations of motion, write a CSV time series
  eval       mass matrix, forcing, accelerations and energies at one state (JSON)
  info       sizes, names, parameter defaults and initial state (JSON)
  batch      evaluate states read as JSON lines from stdin (for kanegen verify)

'PROG <command> --help' describes a command's options.
)";

constexpr const char* kSimulateUsage = R"(usage: PROG simulate --t-end T [options]

Integrates x = [q; u] from t = 0 with all inputs zero (qdot from the
kinematic equations, udot from the forward dynamics) and writes the CSV
columns t, coordinates, speeds, outputs at t = 0, dt, 2 dt, ..., T.

options:
  --t-end T            final time (required)
  --dt H               output interval, also the rk4 step (default 0.01)
  --integrator NAME    dopri5 (adaptive, default) or rk4 (fixed step dt)
  --rtol R             dopri5 relative tolerance (default 1e-8)
  --atol A             dopri5 absolute tolerance (default 1e-10)
  --h0 H               dopri5 initial step (default: estimated)
  --h-min H            dopri5: fail if the step must go below H (default: round-off limit)
  --h-max H            dopri5 largest step (default: T)
  --max-steps N        fail after N attempted steps (default 100000)
  --set NAME=VALUE     set a parameter (repeatable)
  --q0 NAME=VALUE      initial coordinate (repeatable; default: the model's q0)
  --u0 NAME=VALUE      initial speed (repeatable; default: the model's u0)
  -o, --output FILE    write the CSV to FILE instead of stdout
  --stats              print step statistics on stderr
  -h, --help           show this help
)";

constexpr const char* kEvalUsage =
    R"(usage: PROG eval [--q v1,v2,...] [--u v1,v2,...] [--t T] [--set NAME=VALUE]...

Evaluates the equations of motion at one state, inputs zero, and prints
{"coordinates": [names], "mass_matrix": [[...]], "forcing": [...], "udot": [...],
 "kinetic_energy": x, "potential_energy": y}

options:
  --q v1,v2,...        coordinates, one per coordinate (default: the model's q0)
  --u v1,v2,...        speeds, one per speed (default: the model's u0)
  --t T                time (default 0)
  --set NAME=VALUE     set a parameter (repeatable)
  -h, --help           show this help
)";

constexpr const char* kInfoUsage = R"(usage: PROG info

Prints the model's name, sizes, names, parameter defaults, q0 and u0 as JSON.
)";

std::string replace_all(std::string text, const std::string& from, const std::string& to) {
  for (size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size())) {
    text.replace(at, from.size(), to);
  }
  return text;
}

// Walks the arguments; "--name=value" is split into option and value.
class ArgScanner {
 public:
  ArgScanner(const std::vector<std::string>& args, size_t first, std::string command)
      : args_(args), next_(first), command_(std::move(command)) {}

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
    if (arg.empty() || arg[0] != '-') throw UsageError("unexpected argument '" + arg + "' for " + command_);
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

  // Single-valued options may be given once.
  void once(const std::string& option) {
    if (!seen_.insert(option).second) throw UsageError("option " + option + " given more than once");
  }

  [[noreturn]] void unknown(const std::string& option) const {
    throw UsageError("unknown option '" + option + "' for " + command_ + " (see '" + command_ + " --help')");
  }

 private:
  const std::vector<std::string>& args_;
  size_t next_;
  std::string command_;
  std::optional<std::string> inline_value_;
  std::set<std::string> seen_;
};

double number_arg(const std::string& option, const std::string& text) {
  double v = 0;
  if (!parse_number(text, &v)) throw UsageError("invalid number '" + text + "' for " + option);
  return v;
}

struct Assignment {
  std::string name;
  double value;
};

Assignment assignment_arg(const std::string& option, const std::string& text) {
  const size_t eq = text.find('=');
  if (eq == std::string::npos || eq == 0)
    throw UsageError(option + " expects NAME=VALUE, got '" + text + "'");
  return {text.substr(0, eq), number_arg(option, text.substr(eq + 1))};
}

std::string known(const char* what, const char* const* names, int n) {
  return n == 0 ? std::string("the model has no ") + what
                : std::string("known ") + what + ": " + join_names(names, n);
}

void apply_parameters(Model& model, const std::vector<Assignment>& sets) {
  const ModelInfo& info = model.info();
  for (const Assignment& a : sets) {
    if (!model.set_parameter(a.name.c_str(), a.value)) {
      throw UsageError("unknown parameter '" + a.name + "' in --set; " +
                       known("parameters", info.parameter_names, info.np));
    }
  }
}

// Sets x[i] for each NAME=VALUE, NAME one of names[0..n).
void apply_state(const std::vector<Assignment>& sets, const char* option, const char* what,
                 const char* const* names, int n, double* x) {
  for (const Assignment& a : sets) {
    const auto end = names + n;
    const auto it = std::find_if(names, end, [&](const char* s) { return a.name == s; });
    if (it == end) {
      throw UsageError("unknown name '" + a.name + "' in " + option + "; " + known(what, names, n));
    }
    x[it - names] = a.value;
  }
}

std::string pivot_message(const ModelInfo& info, int pivot) {
  if (pivot < 0)
    return std::string("singular configuration: loop equation ") + info.constraint_names[-pivot - 1] +
           " is (nearly) dependent on the ones before it, so the loop forces grow without bound and the "
           "motion may change branch; the mechanism is at or near a dead point or a bifurcation (links in "
           "line)";
  return "mass matrix is not positive definite (pivot " + std::to_string(pivot) +
         " of its LDL^T factorisation is not positive)";
}

std::string json_numbers(const double* v, int n) {
  std::string s = "[";
  for (int i = 0; i < n; ++i) s += (i ? ", " : "") + json_number(v[i]);
  return s + "]";
}

std::string json_names(const char* const* names, int n) {
  std::string s = "[";
  for (int i = 0; i < n; ++i) s += (i ? ", " : "") + json_string(names[i]);
  return s + "]";
}

void print(std::FILE* stream, const std::string& text) {
  std::fputs(text.c_str(), stream);
  std::fflush(stream);
}

// ---------------------------------------------------------------- simulate

// The signal that asked a simulation to stop (SIGINT, SIGTERM or SIGHUP), or 0.
// The integration checks it at every right-hand side and every output row, so
// a stopped run still closes its CSV with every row computed and says where.
volatile std::sig_atomic_t g_stop_signal = 0;

extern "C" void request_stop(int signal_number) { g_stop_signal = signal_number; }

const char* signal_name(int signal_number) {
  switch (signal_number) {
    case SIGINT: return "SIGINT";
    case SIGTERM: return "SIGTERM";
    case SIGHUP: return "SIGHUP";
    default: return "a signal";
  }
}

// Installs request_stop for the lifetime of a simulation, then restores the
// previous handlers.
class StopOnSignal {
 public:
  StopOnSignal() {
    g_stop_signal = 0;
    for (int i = 0; i < kCount; ++i) previous_[i] = std::signal(kSignals[i], request_stop);
  }
  ~StopOnSignal() {
    for (int i = 0; i < kCount; ++i) std::signal(kSignals[i], previous_[i]);
  }
  StopOnSignal(const StopOnSignal&) = delete;
  StopOnSignal& operator=(const StopOnSignal&) = delete;

 private:
  static constexpr int kCount = 3;
  static constexpr int kSignals[kCount] = {SIGINT, SIGTERM, SIGHUP};
  void (*previous_[kCount])(int) = {};
};

struct SimulateArgs {
  IntegrationOptions opt;
  Method method = Method::kDopri5;
  bool t_end_given = false;
  std::vector<Assignment> sets, q0, u0;
  std::string output;
  bool stats = false;
};

// Parses one simulate option; false if it is not one.
bool parse_simulate_option(ArgScanner& args, const std::string& o, SimulateArgs& a) {
  IntegrationOptions& opt = a.opt;
  const auto num = [&]() {
    args.once(o);
    return number_arg(o, args.value(o));
  };
  if (o == "--t-end") {
    opt.t_end = num();
    a.t_end_given = true;
  } else if (o == "--dt") {
    opt.dt = num();
  } else if (o == "--rtol") {
    opt.rtol = num();
  } else if (o == "--atol") {
    opt.atol = num();
  } else if (o == "--h0") {
    opt.h0 = num();
  } else if (o == "--h-min") {
    opt.h_min = num();
  } else if (o == "--h-max") {
    opt.h_max = num();
  } else if (o == "--max-steps") {
    args.once(o);
    const std::string v = args.value(o);
    if (!parse_integer(v, &opt.max_steps) || opt.max_steps <= 0)
      throw UsageError("--max-steps needs a positive integer, got '" + v + "'");
  } else if (o == "--integrator") {
    args.once(o);
    const std::string v = args.value(o);
    if (!parse_method(v, &a.method)) throw UsageError("unknown integrator '" + v + "'; known: rk4, dopri5");
  } else if (o == "--set" || o == "--q0" || o == "--u0") {
    auto& list = o == "--set" ? a.sets : o == "--q0" ? a.q0 : a.u0;
    list.push_back(assignment_arg(o, args.value(o)));
  } else if (o == "-o" || o == "--output") {
    args.once("--output");
    a.output = args.value(o);
  } else if (o == "--stats") {
    args.no_value(o);
    a.stats = true;
  } else {
    return false;
  }
  return true;
}

void check_simulate_args(const SimulateArgs& a) {
  const IntegrationOptions& o = a.opt;
  if (!a.t_end_given) throw UsageError("simulate needs --t-end");
  if (o.t_end < 0) throw UsageError("--t-end must be >= 0");
  if (o.dt <= 0) throw UsageError("--dt must be positive");
  if (o.rtol < 0 || o.atol < 0) throw UsageError("--rtol and --atol must be >= 0");
  if (o.rtol == 0 && o.atol == 0) throw UsageError("--rtol and --atol cannot both be zero");
  if (o.h0 < 0 || o.h_min < 0 || o.h_max < 0) throw UsageError("--h0, --h-min and --h-max must be >= 0");
}

std::vector<std::string> state_names(const ModelInfo& info) {
  std::vector<std::string> names(info.coordinate_names, info.coordinate_names + info.nq);
  names.insert(names.end(), info.speed_names, info.speed_names + info.nu);
  return names;
}

int simulate(Model& model, const SimulateArgs& a, std::FILE* out, std::FILE* err) {
  const ModelInfo& info = model.info();
  const int nq = info.nq, n = info.nq + info.nu;
  apply_parameters(model, a.sets);
  std::vector<double> x(static_cast<size_t>(std::max(n, 1)), 0.0);
  model.initial_state(x.data(), x.data() + nq);
  apply_state(a.q0, "--q0", "coordinates", info.coordinate_names, nq, x.data());
  apply_state(a.u0, "--u0", "speeds", info.speed_names, info.nu, x.data() + nq);

  // Closed loops: a consistent start, then every accepted step projected.
  const LoopSolver loops(model);
  if (loops.active()) {
    const Assembly assembly = loops.assemble(x.data(), x.data() + nq);
    const std::string held =
        assembly.independent.empty()
            ? std::string("no independent coordinate (the prescribed motion drives the mechanism)")
            : "independent coordinates " + loops.describe(assembly.independent) +
                  (assembly.picked ? " (picked by the solver; mark joints \"independent\": true to choose)"
                                   : "");
    print(err, "assembly: " + held + "; loops closed to |phi| = " + format_double(assembly.residual) +
                   " in " + std::to_string(assembly.iterations) + " Newton steps\n");
  }
  std::vector<double> projected(static_cast<size_t>(std::max(n, 1)));

  const bool to_stdout = a.output.empty() || a.output == "-";
  auto csv = to_stdout ? std::make_unique<CsvWriter>(out) : std::make_unique<CsvWriter>(a.output);
  if (!csv->ok()) throw RunError(csv->error());
  std::vector<std::string> header = {"t"};
  const std::vector<std::string> names = state_names(info);
  header.insert(header.end(), names.begin(), names.end());
  header.insert(header.end(), info.output_names, info.output_names + info.ny);
  if (!csv->write_header(header)) throw RunError(csv->error());

  std::vector<double> tau(static_cast<size_t>(std::max(info.ntau, 1)), 0.0);
  std::vector<double> row(1 + n + std::max(info.ny, 1));
  std::string why;  // the reason the right-hand side failed, for the message
  const StopOnSignal stop_on_signal;
  double t_last_row = 0.0;
  long rows = 0;
  const Rhs rhs = [&](double t, const double* xs, double* xdot) {
    if (g_stop_signal != 0) return false;
    model.coordinate_rates(xs, xs + nq, xdot);
    const int pivot = model.forward_dynamics(t, xs, xs + nq, tau.data(), xdot + nq);
    if (pivot != 0) why = pivot_message(info, pivot);
    return pivot == 0;
  };
  const Observer observer = [&](double t, const double* xs) {
    if (g_stop_signal != 0) return false;
    row[0] = t;
    if (loops.active()) {  // rows between steps come from the dense output: project them too
      std::copy(xs, xs + n, projected.begin());
      std::string ignored;
      if (loops.project(projected.data(), projected.data() + nq, &ignored)) xs = projected.data();
    }
    std::copy(xs, xs + n, row.begin() + 1);
    model.outputs(t, xs, xs + nq, row.data() + 1 + n);
    t_last_row = t;
    ++rows;
    return csv->write_row(row.data(), 1 + n + info.ny);
  };
  IntegrationOptions opt = a.opt;
  opt.state_names = names;
  if (loops.active())
    opt.project = [&](double, double* xs, std::string* why) { return loops.project(xs, xs + nq, why); };
  const IntegrationResult r = integrate(a.method, rhs, 0.0, x.data(), n, opt, observer);
  if (a.stats) {
    std::fprintf(err, "stats: integrator=%s accepted=%ld rejected=%ld rhs_evals=%ld t=%s\n",
                 method_name(a.method), r.stats.accepted, r.stats.rejected, r.stats.rhs_evals,
                 format_double(r.t).c_str());
  }
  const bool closed = csv->close();
  if (g_stop_signal != 0) {
    const int signal_number = g_stop_signal;
    print(err, std::string("error: interrupted by ") + signal_name(signal_number) + "; " + std::to_string(rows) +
                   " rows written" + (to_stdout ? "" : " to " + a.output) + ", up to t=" + format_double(t_last_row) +
                   " of t_end=" + format_double(a.opt.t_end) + "\n");
    return 128 + signal_number;
  }
  if (r.status == Status::kInvalidArgument) throw UsageError(r.message);
  if (!r.ok())
    throw RunError(r.status == Status::kRhsFailed && !why.empty() ? why + "; " + r.message : r.message);
  if (r.status == Status::kStoppedByObserver || !closed) throw RunError(csv->error());
  return 0;
}

int simulate_command(Model& model, ArgScanner& args, std::FILE* out, std::FILE* err) {
  SimulateArgs a;
  while (!args.done()) {
    const std::string o = args.next_option();
    if (o == "-h" || o == "--help") return -1;
    if (!parse_simulate_option(args, o, a)) args.unknown(o);
  }
  check_simulate_args(a);
  return simulate(model, a, out, err);
}

// ---------------------------------------------------------------- eval

// The values of --q or --u, checked against the model's count.
std::vector<double> state_list(const std::string& option, const std::string& text, const char* what,
                               const char* const* names, int n) {
  std::vector<double> v;
  if (!parse_number_list(text, &v)) {
    throw UsageError("invalid list '" + text + "' for " + option + " (expected comma-separated numbers)");
  }
  if (static_cast<int>(v.size()) != n) {
    throw UsageError(option + " expects " + std::to_string(n) + " value(s), got " + std::to_string(v.size()) +
                     "; " + known(what, names, n));
  }
  return v;
}

int eval_command(Model& model, ArgScanner& args, std::FILE* out) {
  const ModelInfo& info = model.info();
  std::vector<double> q(info.q0, info.q0 + info.nq), u(info.u0, info.u0 + info.nu);
  double t = 0.0;
  std::vector<Assignment> sets;
  while (!args.done()) {
    const std::string o = args.next_option();
    if (o == "-h" || o == "--help") return -1;
    if (o == "--q") {
      args.once(o);
      q = state_list(o, args.value(o), "coordinates", info.coordinate_names, info.nq);
    } else if (o == "--u") {
      args.once(o);
      u = state_list(o, args.value(o), "speeds", info.speed_names, info.nu);
    } else if (o == "--t") {
      args.once(o);
      t = number_arg(o, args.value(o));
    } else if (o == "--set") {
      sets.push_back(assignment_arg(o, args.value(o)));
    } else {
      args.unknown(o);
    }
  }
  apply_parameters(model, sets);
  const int nu = info.nu;
  const size_t m = static_cast<size_t>(std::max(nu, 1));
  q.resize(std::max<size_t>(q.size(), 1));
  u.resize(m);
  std::vector<double> M(m * m), f(m), udot(m), tau(static_cast<size_t>(std::max(info.ntau, 1)), 0.0);
  model.mass_matrix(q.data(), M.data());
  model.forcing(t, q.data(), u.data(), tau.data(), f.data());
  if (const int pivot = model.forward_dynamics(t, q.data(), u.data(), tau.data(), udot.data()); pivot != 0) {
    throw RunError(pivot_message(info, pivot) + " at q=" + json_numbers(q.data(), info.nq));
  }
  std::string rows = "[";
  for (int i = 0; i < nu; ++i) rows += (i ? ", " : "") + json_numbers(M.data() + i * nu, nu);
  rows += "]";
  print(out, "{\"coordinates\": " + json_names(info.coordinate_names, info.nq) +
                 ", \"mass_matrix\": " + rows + ", \"forcing\": " + json_numbers(f.data(), nu) +
                 ", \"udot\": " + json_numbers(udot.data(), nu) +
                 ", \"kinetic_energy\": " + json_number(model.kinetic_energy(q.data(), u.data())) +
                 ", \"potential_energy\": " + json_number(model.potential_energy(q.data())) + "}\n");
  return 0;
}

// ---------------------------------------------------------------- info

int info_command(const Model& model, ArgScanner& args, std::FILE* out) {
  while (!args.done()) {
    const std::string o = args.next_option();
    if (o == "-h" || o == "--help") return -1;
    args.unknown(o);
  }
  const ModelInfo& i = model.info();
  std::vector<double> defaults(static_cast<size_t>(std::max(i.np, 1)));
  for (int k = 0; k < i.np; ++k) defaults[k] = model.parameter(k);
  const auto size = [](const char* key, int n) {
    return "\"" + std::string(key) + "\": " + std::to_string(n);
  };
  print(out, "{\"name\": " + json_string(i.name) + ", " + size("nq", i.nq) + ", " + size("nu", i.nu) + ", " +
                 size("ntau", i.ntau) + ", " + size("ny", i.ny) + ", " + size("np", i.np) +
                 ", \"coordinates\": " + json_names(i.coordinate_names, i.nq) + ", \"speeds\": " +
                 json_names(i.speed_names, i.nu) + ", \"inputs\": " + json_names(i.input_names, i.ntau) +
                 ", \"outputs\": " + json_names(i.output_names, i.ny) +
                 ", \"parameters\": " + json_names(i.parameter_names, i.np) +
                 ", \"parameter_defaults\": " + json_numbers(defaults.data(), i.np) +
                 ", \"q0\": " + json_numbers(i.q0, i.nq) + ", \"u0\": " + json_numbers(i.u0, i.nu) + ", " +
                 size("nc", i.nc) + ", \"constraints\": " + json_names(i.constraint_names, i.nc) + "}\n");
  return 0;
}

// ---------------------------------------------------------------- batch

int batch_command(Model& model, ArgScanner& args, std::FILE* in, std::FILE* out) {
  while (!args.done()) {
    const std::string o = args.next_option();
    if (o == "-h" || o == "--help") return -1;
    args.unknown(o);
  }
  return run_batch(model, in, out);
}

// ---------------------------------------------------------------- dispatch

// Runs the command; -1 means "print the command's help".
int dispatch(Model& model, const std::string& command, ArgScanner& args, std::FILE* in, std::FILE* out,
             std::FILE* err) {
  if (command == "simulate") return simulate_command(model, args, out, err);
  if (command == "eval") return eval_command(model, args, out);
  if (command == "info") return info_command(model, args, out);
  if (command == "batch") return batch_command(model, args, in, out);
  throw UsageError("unknown command '" + command + "'; commands: simulate, eval, info, batch (see --help)");
}

const char* usage_for(const std::string& command) {
  if (command == "simulate") return kSimulateUsage;
  if (command == "eval") return kEvalUsage;
  if (command == "info") return kInfoUsage;
  if (command == "batch") return kBatchUsage;
  return kMainUsage;
}

std::string program_name(const std::vector<std::string>& args) {
  if (args.empty() || args[0].empty()) return "runner";
  const size_t slash = args[0].find_last_of('/');
  return slash == std::string::npos ? args[0] : args[0].substr(slash + 1);
}

}  // namespace

int run_model(Model& model, const std::vector<std::string>& args, std::FILE* out, std::FILE* err) {
  return run_model(model, args, stdin, out, err);
}

int run_model(Model& model, const std::vector<std::string>& args, std::FILE* in, std::FILE* out,
              std::FILE* err) {
  const std::string prog = program_name(args);
  const auto usage = [&](const std::string& command) {
    return replace_all(replace_all(usage_for(command), "PROG", prog), "MODEL", model.info().name);
  };
  std::string command;
  try {
    if (args.size() < 2) {
      print(err, usage(""));
      return 2;
    }
    command = args[1];
    if (command == "-h" || command == "--help" || command == "help") {
      print(out, usage(""));
      return 0;
    }
    ArgScanner scanner(args, 2, prog + " " + command);
    const int code = dispatch(model, command, scanner, in, out, err);
    if (code == -1) print(out, usage(command));
    return code == -1 ? 0 : code;
  } catch (const UsageError& e) {
    print(err, std::string("error: ") + e.what() + "\n");
    return 2;
  } catch (const std::exception& e) {
    print(err, std::string("error: ") + e.what() + "\n");
    return 1;
  } catch (...) {
    print(err, "error: unknown exception\n");
    return 1;
  }
}

int run_model(Model& model, int argc, char** argv) {
  std::vector<std::string> args;
  try {
    args.assign(argv, argv + std::max(argc, 0));
  } catch (...) {
    std::fputs("error: out of memory\n", stderr);
    return 1;
  }
  return run_model(model, args, stdout, stderr);
}

}  // namespace kanegen::runtime
