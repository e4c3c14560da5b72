// SPDX-License-Identifier: GPL-2.0-or-later
// Helpers over a generated model's System: a right-hand side for the
// runtime integrators, total energy, and random states.
#pragma once

#include <algorithm>
#include <cmath>
#include <kanegen/runtime/integrators.hpp>
#include <random>
#include <vector>

namespace kanegen_test {

/// x = [q; u], x' = [q_dot(u); u_dot] with zero inputs.
template <class System>
kanegen::runtime::Rhs rhs(const typename System::Params& p) {
  return [&p](double t, const double* x, double* xdot) {
    double tau[System::ntau > 0 ? System::ntau : 1] = {};
    System::coordinate_rates(x, x + System::nq, xdot);
    return System::forward_dynamics(p, t, x, x + System::nq, tau, xdot + System::nq) == 0;
  };
}

template <class System>
double energy(const typename System::Params& p, const double* x) {
  return System::kinetic_energy(p, x, x + System::nq) + System::potential_energy(p, x);
}

/// Energy drift of a conservative model from state x0 with Dormand-Prince
/// at rtol 1e-10: max |E(t) - E(0)| over [0, t_end] relative to |E(0)|.
struct EnergyDrift {
  double initial_energy = 0.0, relative_drift = 0.0;
  kanegen::runtime::IntegrationResult result;
};

template <class System>
EnergyDrift energy_drift(std::vector<double> x, double t_end, long max_steps) {
  typename System::Params p;
  EnergyDrift d;
  d.initial_energy = energy<System>(p, x.data());
  double worst = 0.0;
  kanegen::runtime::IntegrationOptions opt;
  opt.t_end = t_end;
  opt.dt = 0.01;
  opt.rtol = 1e-10;
  opt.atol = 1e-12;
  opt.max_steps = max_steps;
  d.result = kanegen::runtime::integrate(kanegen::runtime::Method::kDopri5, rhs<System>(p), 0.0, x.data(),
                                         static_cast<int>(x.size()), opt, [&](double, const double* state) {
                                           worst = std::max(
                                               worst, std::abs(energy<System>(p, state) - d.initial_energy));
                                           return true;
                                         });
  d.relative_drift = worst / std::abs(d.initial_energy);
  return d;
}

/// A state with q uniform in [-q_range, q_range] and u in [-u_range, u_range].
template <class System>
std::vector<double> random_state(std::mt19937& rng, double q_range, double u_range) {
  std::uniform_real_distribution<double> q(-q_range, q_range), u(-u_range, u_range);
  std::vector<double> x(System::nq + System::nu);
  for (int i = 0; i < System::nq; ++i) x[i] = q(rng);
  for (int i = 0; i < System::nu; ++i) x[System::nq + i] = u(rng);
  return x;
}

}  // namespace kanegen_test
