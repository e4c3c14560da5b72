// SPDX-License-Identifier: MIT
// The runner's command line: everything that does not depend on the model's
// type, so it is compiled once here rather than in every model executable.
#include "kanegen/runtime/driver.hpp"

#include <algorithm>
#include <csignal>
#include <memory>
#include <stdexcept>

#include "batch.hpp"
#include "kanegen/runtime/csv.hpp"
#include "kanegen/runtime/integrators.hpp"
#include "kanegen/runtime/loops.hpp"
#include "kanegen/runtime/methods.hpp"
#include "kanegen/runtime/options.hpp"
#include "kanegen/runtime/state_jacobian.hpp"
#include "kanegen/runtime/text.hpp"
#include "model_integrators.hpp"
#include "nonconservative_work.hpp"
#include "run_report.hpp"

namespace kanegen::runtime {
namespace {

// A failure while running (exit code 1); a bad command line is a UsageError (options.hpp, exit code 2).
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

// The heads of the commands' help; the "options:" block follows from the table.
constexpr const char* kSimulateUsage = R"(usage: PROG simulate --t-end T [options]

Integrates x = [q; u] from t = 0 with all inputs zero (qdot from the
kinematic equations, udot from the forward dynamics) and writes the CSV
columns t, coordinates, speeds, outputs at t = 0, dt, 2 dt, ..., T.

)";

constexpr const char* kEvalUsage =
    R"(usage: PROG eval [--q v1,v2,...] [--u v1,v2,...] [--t T] [--set NAME=VALUE]...

Evaluates the equations of motion at one state, inputs zero, and prints
{"coordinates": [names], "mass_matrix": [[...]], "forcing": [...], "udot": [...],
 "kinetic_energy": x, "potential_energy": y}

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
  // Name the coordinate whose pivot failed and the bodies it moves: the
  // user's fix is a mass or inertia of one of them.
  const int i = pivot - 1;
  const std::string coordinate = pivot <= info.nq ? info.coordinate_names[i] : "?";
  std::string what = "mass matrix is not positive definite at coordinate '" + coordinate + "' (pivot " +
                     std::to_string(pivot) + " of its LDL^T factorisation is not positive): ";
  if (pivot > info.nq || !info.coordinate_joints || !info.moved_bodies_first || !info.moved_bodies)
    return what +
           "a body it moves has a zero or negative mass or an invalid inertia at these parameters; check the "
           "bodies carried by joint '" +
           coordinate + "' and the --set values";
  const std::string joint = info.coordinate_joints[i];
  std::string bodies;
  const int first = info.moved_bodies_first[i], end = info.moved_bodies_first[i + 1];
  for (int k = first; k < end; ++k)
    bodies += std::string(k > first ? ", '" : "'") + info.moved_bodies[k] + "'";
  what += joint.empty() ? "this elastic coordinate" : "joint '" + joint + "'";
  const bool one = end - first == 1;
  what += (one ? " moves body " : " moves bodies ") + bodies + (one ? ", which has" : ", one of which has");
  return what +
         " a zero or negative mass or an invalid inertia at these parameters (or no mass moves along this "
         "coordinate); check " +
         (one ? "its mass and inertia" : "their masses and inertias") + " and the --set values";
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
    case SIGINT:
      return "SIGINT";
    case SIGTERM:
      return "SIGTERM";
    case SIGHUP:
      return "SIGHUP";
    default:
      return "a signal";
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
  Method method = kDefaultMethod;
  std::vector<Assignment> sets, q0, u0;
  std::string output;
  bool stats = false;
  double rho_inf = 0.8;  ///< genalpha
  bool energies = false;
};

// The simulate options, values checked one by one by the parser (defaults
// from the table), and the one rule that ties two of them.
SimulateArgs simulate_args(const ParsedOptions& p) {
  SimulateArgs a;
  IntegrationOptions& o = a.opt;
  o.t_end = p.number("--t-end");
  o.dt = p.number("--dt");
  o.rtol = p.number("--rtol");
  o.atol = p.number("--atol");
  o.h0 = p.number("--h0");
  o.h_min = p.number("--h-min");
  o.h_max = p.number("--h-max");
  o.max_steps = p.integer("--max-steps");
  o.max_order = static_cast<int>(std::min(p.integer("--max-order"), 6L));
  parse_method(p.text("--integrator"), &a.method);  // one of the table's choices
  a.sets = p.assignments("--set");
  a.q0 = p.assignments("--q0");
  a.u0 = p.assignments("--u0");
  a.output = p.text("--output");
  a.stats = p.flag("--stats");
  a.rho_inf = p.number("--rho-inf");
  a.energies = p.flag("--energies");
  if (o.rtol == 0 && o.atol == 0) throw UsageError("--rtol and --atol cannot both be zero");
  if (a.rho_inf > 1) throw UsageError("--rho-inf must be in [0, 1]");
  if (o.max_order > 5) throw UsageError("--max-order must be 1 to 5");
  if (const detail::OptionsCheck check = resolved_spec(a.method).check)
    if (const std::string why = check(o); !why.empty()) throw UsageError(why);
  return a;
}

std::vector<std::string> state_names(const ModelInfo& info) {
  std::vector<std::string> names(info.coordinate_names, info.coordinate_names + info.nq);
  names.insert(names.end(), info.speed_names, info.speed_names + info.nu);
  return names;
}

// --stats: the counters of every method, and the Newton counters of the implicit ones.
void print_stats(std::FILE* err, Method method, const IntegrationResult& r) {
  const StepStats& s = r.stats;
  // An alias ("implicit") is reported as the method it selected.
  const MethodSpec& spec = resolved_spec(method);
  std::string line = std::string("stats: integrator=") + spec.name +
                     " accepted=" + std::to_string(s.accepted) + " rejected=" + std::to_string(s.rejected);
  // A method that steps the Model (genalpha) evaluates residuals, not the right-hand side.
  if (spec.ode != nullptr) line += " rhs_evals=" + std::to_string(s.rhs_evals);
  if (is_implicit(spec.kind))
    line += " newton_iterations=" + std::to_string(s.newton_iterations) +
            " newton_failures=" + std::to_string(s.newton_failures) +
            " jacobian_evals=" + std::to_string(s.jacobian_evaluations) +
            " lu_factorizations=" + std::to_string(s.factorizations) +
            (s.projections > 0 ? " projections=" + std::to_string(s.projections) : "");
  print(err, line + " t=" + format_double(r.t) + "\n");
}

// Integrates with the chosen method: the explicit ones on rhs, the implicit
// ones with the model's Jacobian kernels (model_integrators.hpp).
// n_state: the components of x, nq + nu and W_nc when simulate carries it.
IntegrationResult run_method(const Model& model, const SimulateArgs& a, const Rhs& rhs, double* x,
                             int n_state, const IntegrationOptions& opt, const Observer& observer,
                             const double* tau) {
  try {
    return detail::integrate_model(a.method, {model, rhs, tau, x, n_state, opt, observer, a.rho_inf});
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
}

// The start: the model's initial state with the parameters, --q0 and --u0
// applied (nq + nu components).
std::vector<double> start_state(Model& model, const SimulateArgs& a) {
  const ModelInfo& info = model.info();
  apply_parameters(model, a.sets);
  std::vector<double> x(static_cast<size_t>(std::max(info.nq + info.nu, 1)), 0.0);
  model.initial_state(x.data(), x.data() + info.nq);
  apply_state(a.q0, "--q0", "coordinates", info.coordinate_names, info.nq, x.data());
  apply_state(a.u0, "--u0", "speeds", info.speed_names, info.nu, x.data() + info.nq);
  return x;
}

// Closed loops: the start made consistent, and the line that says how.
void assemble_loops(const LoopSolver& loops, double* x, int nq, std::FILE* err) {
  const Assembly assembly = loops.assemble(x, x + nq);
  const std::string held =
      assembly.independent.empty()
          ? std::string("no independent coordinate (the prescribed motion drives the mechanism)")
          : "independent coordinates " + loops.describe(assembly.independent) +
                (assembly.picked ? " (picked by the solver; mark joints \"independent\": true to choose)"
                                 : "");
  print(err, "assembly: " + held + "; loops closed to |phi| = " + format_double(assembly.residual) + " in " +
                 std::to_string(assembly.iterations) + " Newton steps\n");
}

// What a run has written, for its last messages.
struct RunRecord {
  long rows = 0;
  double t_last_row = 0.0;
  double largest_loop_residual = 0.0;
  std::string why;  // the reason the right-hand side failed
};

// After the integration: the summary lines, the CSV closed, and the outcome
// (exit status after a signal, else an exception for a failed run).
int finish_run(const SimulateArgs& a, const IntegrationResult& r, const EnergyColumns& energy, bool loops,
               CsvWriter& csv, bool to_stdout, const RunRecord& record, std::FILE* err) {
  if (a.stats) print_stats(err, a.method, r);
  if (a.stats) print(err, run_summary(r.stats.accepted, r.t, energy, loops, record.largest_loop_residual));
  const bool closed = csv.close();
  if (g_stop_signal != 0) {
    const int signal_number = g_stop_signal;
    print(err, std::string("error: interrupted by ") + signal_name(signal_number) + "; " +
                   std::to_string(record.rows) + " rows written" + (to_stdout ? "" : " to " + a.output) +
                   ", up to t=" + format_double(record.t_last_row) +
                   " of t_end=" + format_double(a.opt.t_end) + "\n");
    return 128 + signal_number;
  }
  if (r.status == Status::kInvalidArgument) throw UsageError(r.message);
  if (!r.ok())
    throw RunError(r.status == Status::kRhsFailed && !record.why.empty() ? record.why + "; " + r.message
                                                                         : r.message);
  if (r.status == Status::kStoppedByObserver || !closed) throw RunError(csv.error());
  return 0;
}

int simulate(Model& model, const SimulateArgs& a, std::FILE* out, std::FILE* err) {
  const ModelInfo& info = model.info();
  // Before anything is written: a model without Jacobians cannot run implicitly.
  const bool jacobians = resolved_spec(a.method).needs_jacobians;
  if (jacobians && !model.has_jacobians()) throw UsageError(missing_jacobians_message(info));
  const int nq = info.nq, n = info.nq + info.nu;
  std::vector<double> x = start_state(model, a);
  // Closed loops: a consistent start, then every accepted step projected.
  const LoopSolver loops(model);
  if (loops.active()) assemble_loops(loops, x.data(), nq, err);
  // W_nc (--energies, a model with forces not from V) rides along as state
  // component n, integrated to the method's tolerance; the implicit methods
  // own their state layout and take the trapezoid rule over the rows instead.
  const bool work = a.energies && info.nonconservative;
  // (needs_jacobians, not names: radau and bdf write nq + nu components, no more.)
  const bool work_in_state = work && !jacobians;
  const int n_state = work_in_state ? n + 1 : n;
  x.resize(static_cast<size_t>(std::max(n_state, 1)));
  if (work_in_state) x[n] = 0.0;
  std::vector<double> projected(static_cast<size_t>(std::max(n_state, 1)));
  NonconservativePower power(model);

  const bool to_stdout = a.output.empty() || a.output == "-";
  auto csv = to_stdout ? std::make_unique<CsvWriter>(out) : std::make_unique<CsvWriter>(a.output);
  if (!csv->ok()) throw RunError(csv->error());
  std::vector<std::string> header = {"t"};
  const std::vector<std::string> names = state_names(info);
  header.insert(header.end(), names.begin(), names.end());
  header.insert(header.end(), info.output_names, info.output_names + info.ny);
  EnergyColumns energy(model, a.energies);
  energy.add_header(header);
  if (!csv->write_header(header)) throw RunError(csv->error());
  Progress progress(err, a.opt.t_end);
  RunRecord record;

  std::vector<double> tau(static_cast<size_t>(std::max(info.ntau, 1)), 0.0);
  std::vector<double> lambda(static_cast<size_t>(std::max(info.nc, 1)));
  std::vector<double> row(1 + n + std::max(info.ny, 1) + energy.count());
  const StopOnSignal stop_on_signal;
  const Rhs rhs = [&](double t, const double* xs, double* xdot) {
    if (g_stop_signal != 0) return false;
    progress.on_rhs(t);
    model.coordinate_rates(xs, xs + nq, xdot);
    const int pivot = loops.active() ? loops.dynamics(t, xs, xs + nq, tau.data(), xdot + nq, lambda.data())
                                     : model.forward_dynamics(t, xs, xs + nq, tau.data(), xdot + nq);
    if (pivot != 0) record.why = pivot_message(info, pivot);
    if (pivot == 0 && work_in_state) xdot[n] = power(t, xs, xs + nq, tau.data(), xdot + nq, lambda.data());
    return pivot == 0;
  };
  // The trapezoid rule's last row (implicit methods): t, dW/dt and W there.
  double work_t = 0.0, work_rate = 0.0, work_sum = 0.0;
  bool work_started = false;
  std::vector<double> row_udot(static_cast<size_t>(std::max(info.nu, 1)));
  const auto work_at_row = [&](double t, const double* xs) {
    if (!work) return 0.0;
    if (work_in_state) return xs[n];
    const int pivot = loops.active()
                          ? loops.dynamics(t, xs, xs + nq, tau.data(), row_udot.data(), lambda.data())
                          : model.forward_dynamics(t, xs, xs + nq, tau.data(), row_udot.data());
    const double rate = pivot == 0 ? power(t, xs, xs + nq, tau.data(), row_udot.data(), lambda.data()) : 0.0;
    if (work_started) work_sum += (t - work_t) * (rate + work_rate) / 2;
    work_started = true;
    work_t = t;
    work_rate = rate;
    return work_sum;
  };
  const Observer observer = [&](double t, const double* xs) {
    if (g_stop_signal != 0) return false;
    row[0] = t;
    if (loops.active()) {  // rows between steps come from the dense output: project them too
      std::copy(xs, xs + n_state, projected.begin());
      std::string ignored;
      if (loops.project(projected.data(), projected.data() + nq, &ignored)) xs = projected.data();
    }
    std::copy(xs, xs + n, row.begin() + 1);
    model.outputs(t, xs, xs + nq, row.data() + 1 + n);
    energy.fill(xs, xs + nq, work_at_row(t, xs), row.data() + 1 + n + info.ny);
    if (loops.active())
      record.largest_loop_residual = std::max(record.largest_loop_residual, loops.residual(xs));
    record.t_last_row = t;
    ++record.rows;
    return csv->write_row(row.data(), 1 + n + info.ny + energy.count());
  };
  IntegrationOptions opt = a.opt;
  opt.state_names = names;
  if (work_in_state) {
    opt.state_names.push_back("nonconservative_work");
    if (!opt.atol_per_component.empty()) opt.atol_per_component.push_back(opt.atol);
  }
  opt.on_step = [&](double t, long steps) { progress.on_step(t, steps); };
  if (loops.active())
    opt.project = [&](double, double* xs, std::string* why) { return loops.project(xs, xs + nq, why); };
  const IntegrationResult r = run_method(model, a, rhs, x.data(), n_state, opt, observer, tau.data());
  progress.finish();
  return finish_run(a, r, energy, loops.active(), *csv, to_stdout, record, err);
}

int simulate_command(Model& model, const ParsedOptions& options, std::FILE* out, std::FILE* err) {
  return simulate(model, simulate_args(options), out, err);
}

// ---------------------------------------------------------------- eval

// The values of --q or --u (the model's q0 or u0 if not given), checked
// against the model's count.
std::vector<double> state_list(const ParsedOptions& options, const std::string& option, const double* initial,
                               const char* what, const char* const* names, int n) {
  if (!options.given(option)) return std::vector<double>(initial, initial + n);
  std::vector<double> v = options.numbers(option);
  if (static_cast<int>(v.size()) != n) {
    throw UsageError(option + " expects " + std::to_string(n) + " value(s), got " + std::to_string(v.size()) +
                     "; " + known(what, names, n));
  }
  return v;
}

int eval_command(Model& model, const ParsedOptions& options, std::FILE* out) {
  const ModelInfo& info = model.info();
  std::vector<double> q = state_list(options, "--q", info.q0, "coordinates", info.coordinate_names, info.nq);
  std::vector<double> u = state_list(options, "--u", info.u0, "speeds", info.speed_names, info.nu);
  const double t = options.number("--t");
  const std::vector<Assignment> sets = options.assignments("--set");
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

int info_command(const Model& model, std::FILE* out) {
  const ModelInfo& i = model.info();
  std::vector<double> defaults(static_cast<size_t>(std::max(i.np, 1)));
  for (int k = 0; k < i.np; ++k) defaults[k] = model.parameter(k);
  std::vector<const char*> held;  // the kernels of the spec the table holds
  for (const KernelSpec& spec : kernel_specs)
    if (model.has(spec.kernel)) held.push_back(spec.name);
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
                 size("nc", i.nc) + ", \"constraints\": " + json_names(i.constraint_names, i.nc) +
                 ", \"jacobians\": " + (model.has_jacobians() ? "true" : "false") +
                 ", \"inverse_dynamics\": " + (model.has_inverse_dynamics() ? "true" : "false") +
                 ", \"controller\": " + (model.has_controller() ? "true" : "false") +
                 ", \"kernels\": " + json_names(held.data(), static_cast<int>(held.size())) + "}\n");
  return 0;
}

// ---------------------------------------------------------------- batch

// ---------------------------------------------------------------- dispatch

// Runs the command, its options parsed.
int dispatch(Model& model, const std::string& command, const ParsedOptions& options, std::FILE* in,
             std::FILE* out, std::FILE* err) {
  if (command == "simulate") return simulate_command(model, options, out, err);
  if (command == "eval") return eval_command(model, options, out);
  if (command == "info") return info_command(model, out);
  return run_batch(model, in, out);
}

// A command's --help: its head, then the "options:" block of its table.
std::string usage_for(const std::string& command) {
  if (command == "simulate") return kSimulateUsage + options_usage(*command_options(command));
  if (command == "eval") return kEvalUsage + options_usage(*command_options(command));
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
    const std::vector<OptionSpec>* table = command_options(command);
    if (table == nullptr)
      throw UsageError("unknown command '" + command +
                       "'; commands: simulate, eval, info, batch (see --help)");
    const ParsedOptions options = parse_options(*table, args, 2, prog + " " + command);
    if (options.help) {
      print(out, usage(command));
      return 0;
    }
    return dispatch(model, command, options, in, out, err);
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
