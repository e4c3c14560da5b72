// SPDX-License-Identifier: GPL-2.0-or-later
// A closed-loop simulation as `simulate` runs it: assembly, the index-1
// equations with multipliers, and the projection of every accepted step
// (and of the output rows between steps), with the loop residual and the
// energy recorded at each output time.
#pragma once

#include <algorithm>
#include <cmath>
#include <functional>
#include <kanegen/runtime/integrators.hpp>
#include <kanegen/runtime/loops.hpp>
#include <kanegen/runtime/model.hpp>
#include <string>
#include <vector>

namespace kanegen_test {

struct LoopRun {
  kanegen::runtime::IntegrationResult result;
  kanegen::runtime::Assembly assembly;
  std::string why;              ///< the right-hand side's reason, if it failed
  double worst_residual = 0.0;  ///< largest |Phi| over the output rows
  double initial_energy = 0.0, worst_energy_change = 0.0;
  std::vector<double> times;                ///< output times
  std::vector<std::vector<double>> states;  ///< x = [q; u] at each
};

template <class System>
LoopRun run_loops(double t_end, double dt, double rtol,
                  const std::function<void(typename System::Params&)>& configure = {},
                  const std::function<void(double*)>& adjust = {}) {
  kanegen::runtime::Model model = kanegen::runtime::make_model<System>();
  typename System::Params p;
  if (configure) {
    configure(p);
    for (int i = 0; i < System::np; ++i)
      model.set_parameter(System::parameter_names()[i], System::get_parameter(p, i));
  }
  const int nq = System::nq, n = System::nq + System::nu;
  std::vector<double> x(n), copy(n);
  model.initial_state(x.data(), x.data() + nq);
  if (adjust) adjust(x.data());
  const kanegen::runtime::LoopSolver loops(model);
  LoopRun run;
  run.assembly = loops.assemble(x.data(), x.data() + nq);
  const auto energy = [&](const double* s) {
    return System::kinetic_energy(p, s, s + nq) + System::potential_energy(p, s);
  };
  run.initial_energy = energy(x.data());
  kanegen::runtime::IntegrationOptions opt;
  opt.t_end = t_end;
  opt.dt = dt;
  opt.rtol = rtol;
  opt.atol = rtol * 1e-2;
  opt.max_steps = 10000000;
  opt.project = [&](double, double* s, std::string* why) { return loops.project(s, s + nq, why); };
  const kanegen::runtime::Rhs rhs = [&](double t, const double* s, double* sdot) {
    double tau[System::ntau > 0 ? System::ntau : 1] = {};
    System::coordinate_rates(s, s + nq, sdot);
    double lambda[System::nc > 0 ? System::nc : 1];
    const int status = loops.dynamics(t, s, s + nq, tau, sdot + nq, lambda);
    if (status < 0) run.why = "singular configuration";
    return status == 0;
  };
  run.result = kanegen::runtime::integrate(
      kanegen::runtime::Method::kDopri5, rhs, 0.0, x.data(), n, opt, [&](double t, const double* s) {
        std::copy(s, s + n, copy.begin());
        std::string ignored;
        loops.project(copy.data(), copy.data() + nq, &ignored);
        run.worst_residual = std::max(run.worst_residual, loops.residual(copy.data()));
        run.worst_energy_change =
            std::max(run.worst_energy_change, std::abs(energy(copy.data()) - run.initial_energy));
        run.times.push_back(t);
        run.states.push_back(copy);
        return true;
      });
  return run;
}

}  // namespace kanegen_test
