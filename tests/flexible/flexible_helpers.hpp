// SPDX-License-Identifier: GPL-2.0-or-later
// Integrating a generated flexible model and reading an output column.
#pragma once

#include <algorithm>
#include <cstring>
#include <kanegen/runtime/integrators.hpp>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "system_helpers.hpp"

namespace kanegen_test {

/// The index of the named output of System.
template <class System>
int output_index(const char* name) {
  for (int i = 0; i < System::ny; ++i)
    if (std::strcmp(System::output_names()[i], name) == 0) return i;
  throw std::invalid_argument(std::string("no output ") + name);
}

/// One output sampled every dt from the model's initial state (dopri5).
struct Series {
  std::vector<double> t, y;
  bool ok = false;
  long steps = 0;
};

/// The model's initial state: q0, then u0.
template <class System>
std::vector<double> initial_state() {
  std::vector<double> x(System::q0(), System::q0() + System::nq);
  x.insert(x.end(), System::u0(), System::u0() + System::nu);
  return x;
}

/// Integrates from x with Dormand-Prince (atol = rtol / 100), calling
/// sample(t, state) every dt; sample returns false to stop the run.
template <class System, class Sample>
auto integrate_sampled(const typename System::Params& p, std::vector<double> x, double t_end, double dt,
                       double rtol, Sample&& sample) {
  kanegen::runtime::IntegrationOptions opt;
  opt.t_end = t_end;
  opt.dt = dt;
  opt.rtol = rtol;
  opt.atol = rtol * 1e-2;
  opt.max_steps = 20000000;
  return kanegen::runtime::integrate(kanegen::runtime::Method::kDopri5, rhs<System>(p), 0.0, x.data(),
                                     static_cast<int>(x.size()), opt, std::forward<Sample>(sample));
}

template <class System>
Series simulate_output(const typename System::Params& p, const char* output, double t_end, double dt,
                       double rtol = 1e-8) {
  const int k = output_index<System>(output);
  Series s;
  const auto result = integrate_sampled<System>(
      p, initial_state<System>(), t_end, dt, rtol, [&](double t, const double* state) {
        double y[System::ny > 0 ? System::ny : 1];
        System::outputs(p, t, state, state + System::nq, y);
        s.t.push_back(t);
        s.y.push_back(y[k]);
        return std::isfinite(y[k]) && std::abs(y[k]) < 1e6;  // stop a diverging run early
      });
  s.ok = result.ok();
  s.steps = result.stats.accepted;
  return s;
}

/// The minimum of a series and its time.
inline std::pair<double, double> minimum(const Series& s) {
  const auto it = std::min_element(s.y.begin(), s.y.end());
  return {*it, s.t[static_cast<std::size_t>(it - s.y.begin())]};
}

}  // namespace kanegen_test
