// SPDX-License-Identifier: MIT
// This file is kanegen's output: you may use, copy, modify and distribute it under any terms you choose
// (docs/licensing.md).
#include "fmu_instance.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <memory>
#include <string>

#include "kanegen/runtime/integrators.hpp"
#include "kanegen/runtime/state_jacobian.hpp"

namespace kanegen_fmu {

namespace runtime = kanegen::runtime;

namespace {
// Largest |Phi| that model exchange lets pass before it asks for an event that projects the state back:
// far below what an importer's tolerance makes visible, far above the projection's 1e-12.
constexpr double kDriftTolerance = 1e-9;

std::size_t size(int n) { return static_cast<std::size_t>(std::max(n, 1)); }
}  // namespace

Instance::Instance(Logger logger)
    : logger_(std::move(logger)),
      settings_(settings()),
      table_(model_table()),
      model_(table_),
      loops_(model_),
      nq_(table_.nq),
      nu_(table_.nu),
      ntau_(table_.ntau),
      ny_(table_.ny),
      np_(table_.np) {
  reset();
}

void Instance::reset() {
  model_ = runtime::Model(table_);
  t_ = 0.0;
  x_.assign(size(nq_ + nu_), 0.0);
  std::copy(table_.q0, table_.q0 + nq_, x_.begin());
  std::copy(table_.u0, table_.u0 + nu_, x_.begin() + nq_);
  tau_.assign(size(ntau_), 0.0);
  y_.assign(size(ny_), 0.0);
  dx_.assign(size(nq_ + nu_), 0.0);
  lambda_.assign(size(table_.nc), 0.0);
  state_set_.assign(size(nq_ + nu_), 0);
  initialized_ = false;
}

Variable Instance::variable(unsigned value_reference) const {
  if (value_reference == 0) return {Role::time, 0};
  long at = static_cast<long>(value_reference) - 1;
  const std::pair<Role, int> blocks[] = {
      {Role::coordinate, nq_}, {Role::speed, nu_},  {Role::coordinate_rate, nq_}, {Role::acceleration, nu_},
      {Role::input, ntau_},    {Role::output, ny_}, {Role::parameter, np_}};
  for (const auto& [role, count] : blocks) {
    if (at < count) return {role, static_cast<int>(at)};
    at -= count;
  }
  return {};
}

void Instance::log_error(const std::string& message) const {
  if (logger_) logger_(true, message);
}

void Instance::enter_initialization(double start_time) { t_ = start_time; }

bool Instance::start_state(std::vector<double>& x, runtime::Assembly* assembly) const {
  std::vector<double> start(size(nq_ + nu_));
  model_.initial_state(start.data(), start.data() + nq_);
  for (std::size_t i = 0; i < static_cast<std::size_t>(nq_ + nu_); ++i)
    if (!state_set_[i]) x[i] = start[i];
  if (!loops_.active()) return true;
  try {
    *assembly = loops_.assemble(x.data(), x.data() + nq_);
  } catch (const std::exception& e) {
    log_error(e.what());
    return false;
  }
  return true;
}

bool Instance::exit_initialization() {
  runtime::Assembly assembly;
  if (!start_state(x_, &assembly)) return false;
  if (loops_.active() && logger_)
    logger_(false, "loops closed to |phi| = " + std::to_string(assembly.residual) + " in " +
                       std::to_string(assembly.iterations) + " Newton steps");
  initialized_ = true;
  return true;
}

int Instance::evaluate(double t, const double* x, double* dx) {
  model_.coordinate_rates(x, x + nq_, dx);
  return loops_.active() ? loops_.dynamics(t, x, x + nq_, tau_.data(), dx + nq_, lambda_.data())
                         : model_.forward_dynamics(t, x, x + nq_, tau_.data(), dx + nq_);
}

bool Instance::derivatives(double* dx) { return derivatives_at(x_.data(), dx); }

bool Instance::derivatives_at(const double* x, double* dx) {
  const int pivot = evaluate(t_, x, dx);
  if (pivot == 0) return true;
  log_error("the mass matrix (or the loops' equations) is singular at t = " + std::to_string(t_) +
            " (pivot " + std::to_string(pivot) + ")");
  return false;
}

bool Instance::get(unsigned value_reference, double* value) {
  const Variable v = variable(value_reference);
  const auto i = static_cast<std::size_t>(v.index);
  // In initialization mode the states, their derivatives and the outputs are those initialization will
  // end with (FMI lists them as initial unknowns): the start state, assembled on the loops.
  const double* x = x_.data();
  std::vector<double> provisional;
  runtime::Assembly ignored;
  if (!initialized_ && v.role != Role::time && v.role != Role::input && v.role != Role::parameter) {
    provisional = x_;
    if (!start_state(provisional, &ignored)) return false;
    x = provisional.data();
  }
  switch (v.role) {
    case Role::time:
      *value = t_;
      return true;
    case Role::coordinate:
      *value = x[i];
      return true;
    case Role::speed:
      *value = x[static_cast<std::size_t>(nq_) + i];
      return true;
    case Role::coordinate_rate:
    case Role::acceleration:
      if (!derivatives_at(x, dx_.data())) return false;
      *value = dx_[(v.role == Role::acceleration ? static_cast<std::size_t>(nq_) : 0) + i];
      return true;
    case Role::input:
      *value = tau_[i];
      return true;
    case Role::output:
      model_.outputs(t_, x, x + nq_, y_.data());
      *value = y_[i];
      return true;
    case Role::parameter:
      *value = model_.parameter(v.index);
      return true;
    case Role::none:
      break;
  }
  log_error("no variable has the value reference " + std::to_string(value_reference));
  return false;
}

bool Instance::set(unsigned value_reference, double value) {
  const Variable v = variable(value_reference);
  const auto i = static_cast<std::size_t>(v.index);
  switch (v.role) {
    case Role::coordinate:
    case Role::speed: {
      const std::size_t at = (v.role == Role::speed ? static_cast<std::size_t>(nq_) : 0) + i;
      x_[at] = value;
      if (!initialized_) state_set_[at] = 1;
      return true;
    }
    case Role::input:
      tau_[i] = value;
      return true;
    case Role::parameter:
      if (initialized_) break;  // variability "fixed": the loops were assembled with them
      model_.set_parameter(table_.parameter_names[i], value);
      return true;
    default:
      break;
  }
  log_error("the variable with value reference " + std::to_string(value_reference) + " cannot be set " +
            (initialized_ ? "after initialization" : "(it is computed)"));
  return false;
}

void Instance::set_states(const double* x) { std::copy(x, x + nq_ + nu_, x_.begin()); }

void Instance::get_states(double* x) const { std::copy(x_.begin(), x_.begin() + nq_ + nu_, x); }

bool Instance::drifted() const { return loops_.active() && loops_.residual(x_.data()) > kDriftTolerance; }

bool Instance::project(bool* changed) {
  *changed = false;
  if (!loops_.active() || loops_.residual(x_.data()) <= kDriftTolerance) return true;
  std::string why;
  if (!loops_.project(x_.data(), x_.data() + nq_, &why)) {
    log_error("the loops could not be closed again at t = " + std::to_string(t_) + ": " + why);
    return false;
  }
  *changed = true;
  return true;
}

bool Instance::do_step(double t, double h) {
  runtime::IntegrationOptions opt;
  opt.t_end = t + h;
  // rk4 steps by dt; the adaptive methods take it as the output interval only.
  const double steps = settings_.max_step > 0 ? std::ceil(h / settings_.max_step) : 1.0;
  opt.dt = h / std::max(steps, 1.0);
  opt.rtol = settings_.rtol;
  opt.atol = settings_.atol;
  if (loops_.active())
    opt.project = [&](double, double* xs, std::string* why) { return loops_.project(xs, xs + nq_, why); };
  const runtime::Rhs rhs = [&](double ts, const double* xs, double* dxs) {
    return evaluate(ts, xs, dxs) == 0;
  };
  std::unique_ptr<runtime::StateJacobian>
      state_jacobian;  // the implicit methods only: it needs the Jacobian kernels
  runtime::Jacobian jacobian;
  if (runtime::resolved_spec(settings_.method).needs_jacobians) {
    state_jacobian = std::make_unique<runtime::StateJacobian>(model_);
    jacobian = [&](double ts, const double* xs, double* J) {
      return state_jacobian->evaluate(ts, xs, tau_.data(), J);
    };
  }
  const runtime::IntegrationResult result =
      runtime::integrate(settings_.method, rhs, t, x_.data(), nq_ + nu_, opt, runtime::Observer(), jacobian);
  t_ = result.t;
  if (result.ok()) return true;
  log_error(result.message);
  return false;
}

}  // namespace kanegen_fmu
