// SPDX-License-Identifier: GPL-2.0-or-later
#include "verify/verify_power.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "kanegen/runtime/integrators.hpp"
#include "numeric/spherical.hpp"

namespace kanegen::verify {
namespace {

/// Tight enough that the integration error (about this size, relative to the
/// energy) stays far below the power-balance tolerance (100 rtol, 1e-7 by
/// default).
constexpr double kIntegrationTolerance = 1e-10;
constexpr int kOutputs = 20;
/// A trajectory ends after its duration or this many steps, whichever comes
/// first, so that fast models (many short links) still verify in seconds.
constexpr long kMaxSteps = 400;

}  // namespace

Worst power_balance(runner::RunnerProcess& runner, const TrajectoryStart& start, double duration, int index,
                    long* points) {
  // x = (q, u, W): the kernels' q (nq: a ball's quaternion, numeric/spherical.hpp), u (n).
  numeric::Instance model = *start.instance;
  const int n = model.coordinates(), nq = n + static_cast<int>(model.ball_joints.size()), size = nq + n;
  const auto request = [&](double t, const double* x, const std::vector<std::string>& kernels) {
    const nlohmann::json r{{"t", t},
                           {"q", std::vector<double>(x, x + nq)},
                           {"u", std::vector<double>(x + nq, x + size)},
                           {"tau", start.runner_tau},
                           {"p", start.runner_p}};
    return runner::call_kernels(runner, r, kernels);
  };

  std::string why;
  bool singular = false;  // the trajectory reached a singular configuration of the loops
  numeric::State s = start.state;
  const runtime::Rhs rhs = [&](double t, const double* x, double* xdot) {
    singular = false;  // set by the call that fails, not by an earlier probe
    const nlohmann::json a = request(t, x, {"forward_dynamics"})["forward_dynamics"];
    if (const int pivot = static_cast<int>(a["returns"].get<double>()); pivot != 0) {
      singular = pivot < 0;
      why = singular ? "loop equation " + std::to_string(-pivot) + " (nearly) dependent on the ones before it"
                     : "M not positive definite (pivot " + std::to_string(pivot) + ")";
      return false;
    }
    numeric::kernel_coordinate_rates(model, x, x + nq, xdot);  // u = q_dot, and the quaternions'
    for (int i = 0; i < n; ++i) xdot[nq + i] = a["udot"][i].get<double>();
    s.t = t;
    s.q = model.ball_joints.empty() ? std::vector<double>(x, x + n)
                                    : numeric::take_kernel_coordinates(model, x);
    s.u.assign(x + nq, x + size);
    // With the generated udot for the work of the prescribed speeds' constraint forces.
    const std::vector<double> udot(xdot + nq, xdot + size);
    xdot[size] = numeric::nonconservative_power(model, s, &udot);
    return true;
  };

  Worst worst;
  worst.where = index;
  double e0 = 0, scale = 0;
  std::vector<double> times, energy, work;
  const auto record = [&](double t, const double* x) {
    const nlohmann::json a = request(t, x, {"kinetic_energy", "potential_energy"});
    const double kinetic = a["kinetic_energy"]["returns"].get<double>(),
                 potential = a["potential_energy"]["returns"].get<double>();
    if (times.empty()) e0 = kinetic + potential;
    scale = std::max(scale, kinetic + std::abs(potential) + std::abs(x[size]));
    times.push_back(t);
    energy.push_back(kinetic + potential - e0);
    work.push_back(x[size]);
    return true;
  };
  const runtime::Observer observer = record;

  std::vector<double> x(size + 1, 0.0);
  const std::vector<double> q0 = numeric::kernel_coordinates(*start.instance, start.state.q);
  std::copy(q0.begin(), q0.end(), x.begin());
  std::copy(start.state.u.begin(), start.state.u.end(), x.begin() + nq);
  runtime::IntegrationOptions opt;
  opt.t_end = start.state.t + duration;
  opt.dt = duration / kOutputs;
  opt.rtol = opt.atol = kIntegrationTolerance;
  opt.max_steps = kMaxSteps;
  const runtime::IntegrationResult result =
      runtime::integrate(runtime::Method::kDopri5, rhs, start.state.t, x.data(), size + 1, opt, observer);
  // A random start is not on the loops, and its trajectory can reach a state
  // where the loop equations are dependent (the generated solve stops
  // there): the balance is checked up to it, as up to kMaxSteps.
  const bool ended = result.status == runtime::Status::kMaxSteps ||
                     (result.status == runtime::Status::kRhsFailed && singular);
  if (ended && !times.empty() && result.t > times.back()) record(result.t, x.data());
  if (!result.ok() && !ended) {
    worst.abs = worst.rel = std::numeric_limits<double>::infinity();
    worst.entry =
        "(integration failed: " + (why.empty() ? result.message : why + "; " + result.message) + ")";
    return worst;
  }
  if (scale == 0) scale = 1;  // nothing moves and nothing acts: every residual is 0
  for (std::size_t k = 0; k < times.size(); ++k) {
    const double d = std::abs(energy[k] - work[k]);
    if (k == 0 || d > worst.abs || std::isnan(d)) {
      worst.abs = d;
      worst.entry = "t=" + std::to_string(times[k]);
      worst.generated = energy[k];
      worst.numeric = work[k];
    }
  }
  worst.rel = worst.abs / scale;
  *points += static_cast<long>(times.size());
  return worst;
}

}  // namespace kanegen::verify
