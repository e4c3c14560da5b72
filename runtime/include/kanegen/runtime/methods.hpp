// SPDX-License-Identifier: MIT
// The registry of integration methods: one row per `--integrator` name with
// its properties and its entry point. Everything that needs to know the
// methods reads this table: integrate()'s dispatch, the runner's option
// parsing and help, simulate's stats and state layout, and `kanegen
// simulate`'s choice of generating the Jacobian kernels. Adding a method is
// its source file, its row here (and its Method value), and its test
// (docs/runtime.md, "Adding an integrator").
//
// Layering: the methods (runtime/src/rk4.cpp, dopri5.cpp, radau.cpp,
// cvode.cpp, genalpha_run.cpp) include this header for their entry's
// declaration only and call nothing above them; the callers (integrators.cpp,
// model_integrators.cpp, driver.cpp, options.cpp) reach the methods through
// the table.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "kanegen/runtime/integration_types.hpp"

namespace kanegen::runtime {

class Model;

/// One value per row of kMethods, in the same order (checked below).
/// kImplicit is the adaptive implicit method of choice, an alias: its row
/// names the method it selects (implicit_method()).
enum class Method { kRk4, kDopri5, kImplicit, kRadau, kBdf, kGenAlpha };

enum class MethodKind {
  kExplicitFixedStep,  ///< steps by --dt, f only
  kExplicitAdaptive,   ///< steps by --rtol/--atol, f only
  kImplicitAdaptive,   ///< steps by --rtol/--atol, Newton with the Jacobian
  kImplicitFixedStep,  ///< steps by --dt, Newton with the Jacobian kernels
};

/// What the runner's simulate hands a method: the model, its right-hand
/// side on x = (q, u) (and W_nc as component nq + nu if n says so), the
/// inputs tau, and the method options that are not IntegrationOptions'.
struct ModelRun {
  const Model& model;
  const Rhs& rhs;
  const double* tau;
  double* x;
  int n;  ///< components of x an explicit method integrates
  const IntegrationOptions& opt;
  const Observer& observer;
  double rho_inf;  ///< genalpha: spectral radius at infinity
};

namespace detail {

class Run;  // integration_run.hpp: the counting, checking state of one integrate() call

/// Integrates run's x' = f from t0 to opt.t_end, x the state (checked
/// finite, the options checked); returns run.finish(time of the state in x).
using OdeEntry = IntegrationResult (*)(Run& run, const Jacobian& jacobian, double t0, double* x);
/// Steps the model itself from t = 0; throws std::invalid_argument for
/// options or a model it cannot take.
using ModelEntry = IntegrationResult (*)(const ModelRun& run);
/// Why the options do not suit the method (checked before anything is
/// written), or "".
using OptionsCheck = std::string (*)(const IntegrationOptions& opt);

// The entries of the rows below, each defined in its method's source file.
IntegrationResult integrate_rk4(Run& run, const Jacobian& jacobian, double t0, double* x);
IntegrationResult integrate_dopri5(Run& run, const Jacobian& jacobian, double t0, double* x);
IntegrationResult integrate_radau(Run& run, const Jacobian& jacobian, double t0, double* x);
IntegrationResult integrate_cvode(Run& run, const Jacobian& jacobian, double t0, double* x);
IntegrationResult integrate_genalpha(const ModelRun& run);
std::string genalpha_check(const IntegrationOptions& opt);

}  // namespace detail

struct MethodSpec {
  Method method;
  const char* name;  ///< as typed after --integrator
  MethodKind kind;
  /// The method an alias selects (its properties are the target's); the row's own method if not an alias.
  Method alias_of;
  bool needs_jacobians;        ///< the runner must be generated with the Jacobian kernels
  bool steps_by_dt;            ///< --dt is the step, not only the output interval
  bool takes_tolerances;       ///< --rtol, --atol, --h0, --h-min, --h-max apply
  const char* description;     ///< for --help, after the name; an alias's help adds "; it is <target>"
  detail::OdeEntry ode;        ///< steps x' = f(t, x); nullptr for an alias or a method that steps the Model
  detail::ModelEntry model;    ///< steps the Model itself; nullptr: `ode` on the model's right-hand side
  detail::OptionsCheck check;  ///< an extra rule on the options, or nullptr
  /// Why an FMU (kanegen fmu) does not carry the method, or nullptr if it does: an FMU compiles every
  /// source of runtime/src/ but the runner's own and those of the methods with a reason here
  /// (generator/CMakeLists.txt), whose entries templates/fmu/absent_methods.cpp stands in for.
  const char* not_in_fmu;
};

// clang-format off
inline constexpr MethodSpec kMethods[] = {
    {Method::kRk4, "rk4", MethodKind::kExplicitFixedStep, Method::kRk4, false, true, false,
     "fixed step dt", detail::integrate_rk4, nullptr, nullptr, nullptr},
    {Method::kDopri5, "dopri5", MethodKind::kExplicitAdaptive, Method::kDopri5, false, false, true,
     "adaptive explicit", detail::integrate_dopri5, nullptr, nullptr, nullptr},
    {Method::kImplicit, "implicit", MethodKind::kImplicitAdaptive, Method::kRadau, true, false, true,
     "adaptive implicit for stiff models: use it for elastic links, with --rtol 1e-2 to 1e-4 and --atol 100 "
     "times smaller", nullptr, nullptr, nullptr, nullptr},
    {Method::kRadau, "radau", MethodKind::kImplicitAdaptive, Method::kRadau, true, false, true,
     "Radau IIA of order 5", detail::integrate_radau, nullptr, nullptr, nullptr},
    {Method::kBdf, "bdf", MethodKind::kImplicitAdaptive, Method::kBdf, true, false, true,
     "SUNDIALS CVODE's BDF", detail::integrate_cvode, nullptr, nullptr,
     "it needs SUNDIALS, which an FMU does not carry"},
    {Method::kGenAlpha, "genalpha", MethodKind::kImplicitFixedStep, Method::kGenAlpha, true, true, false,
     "fixed step dt, real time", nullptr, detail::integrate_genalpha, detail::genalpha_check,
     "it steps whole runs from t = 0, not communication steps"},
};
// clang-format on

/// The runner's --integrator when none is given.
inline constexpr Method kDefaultMethod = Method::kDopri5;

inline constexpr std::size_t kMethodCount = sizeof kMethods / sizeof kMethods[0];

namespace detail {
// Rows in enum order (so that a Method indexes its row), aliases naming a method that is not one.
constexpr bool methods_well_formed() {
  for (std::size_t i = 0; i < kMethodCount; ++i) {
    const MethodSpec& m = kMethods[i];
    if (static_cast<std::size_t>(m.method) != i) return false;
    const MethodSpec& target = kMethods[static_cast<std::size_t>(m.alias_of)];
    if (target.alias_of != target.method) return false;
  }
  return true;
}
static_assert(methods_well_formed(), "kMethods: one row per Method, in order; an alias names a non-alias");
}  // namespace detail

/// The row of `method` (as given: an alias's own row).
constexpr const MethodSpec& method_spec(Method method) { return kMethods[static_cast<std::size_t>(method)]; }
/// The row that runs `method`: the target of an alias, else its own.
constexpr const MethodSpec& resolved_spec(Method method) { return method_spec(method_spec(method).alias_of); }
constexpr bool is_implicit(MethodKind kind) {
  return kind == MethodKind::kImplicitAdaptive || kind == MethodKind::kImplicitFixedStep;
}

/// The row's name: "rk4", "dopri5", "implicit", "radau", "bdf" or "genalpha".
const char* method_name(Method method);
/// The method that kImplicit selects (kRadau or kBdf; bench/implicit.py).
Method implicit_method();
/// Parses the names of method_name; false if unknown.
bool parse_method(std::string_view text, Method* method);
/// The row called `name`, or nullptr.
const MethodSpec* find_method(std::string_view name);
/// Every row's name, in table order.
std::vector<std::string> method_names();

}  // namespace kanegen::runtime
