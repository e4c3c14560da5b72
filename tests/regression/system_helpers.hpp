// Helpers over a generated model's System: a right-hand side for the
// runtime integrators, total energy, and random states.
#pragma once

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
