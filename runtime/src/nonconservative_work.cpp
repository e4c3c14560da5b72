// SPDX-License-Identifier: MIT
#include "nonconservative_work.hpp"

#include <algorithm>
#include <cstddef>

namespace kanegen::runtime {

NonconservativePower::NonconservativePower(const Model& model)
    : model_(model),
      M_(static_cast<std::size_t>(std::max(model.info().nu * model.info().nu, 1))),
      f_(static_cast<std::size_t>(std::max(model.info().nu, 1))),
      C_(static_cast<std::size_t>(std::max(model.info().nc * model.info().nu, 1))) {}

double NonconservativePower::operator()(double t, const double* q, const double* u, const double* tau,
                                        const double* udot, const double* lambda) {
  const int nu = model_.info().nu, nc = model_.info().nc;
  double power = model_.nonconservative_power(t, q, u, tau);
  model_.mass_matrix(q, M_.data());
  model_.forcing(t, q, u, tau, f_.data());
  if (nc > 0) model_.constraint_jacobian(q, C_.data());
  for (int r = 0; r < nu; ++r) {
    double effort = -f_[r];
    for (int s = 0; s < nu; ++s) effort += M_[r * nu + s] * udot[s];
    for (int c = 0; c < nc; ++c) effort -= C_[c * nu + r] * lambda[c];
    power += u[r] * effort;
  }
  return power;
}

}  // namespace kanegen::runtime
