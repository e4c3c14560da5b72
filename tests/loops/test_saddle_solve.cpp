// SPDX-License-Identifier: GPL-2.0-or-later
// The generated saddle-point solve (sparse LDL^T unrolled for the model's
// structure, or dense, as the generator chose) on every loop model: its
// udot and lambda satisfy M udot = f + C^T lambda and C udot = gamma, built
// from the model's other kernels, to rounding, and equal those of
// templates/solve_saddle.hpp (dense in everything) where no speed is prescribed.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "andrews_squeezer.hpp"
#include "four_bar.hpp"
#include "nfourbar2.hpp"
#include "nfourbar40.hpp"
#include "quick_return.hpp"
#include "ring_slider.hpp"
#include "ring_slider_flexible.hpp"
#include "rsur_revolute.hpp"
#include "rsur_spherical.hpp"
#include "simeon_crank.hpp"
#include "simeon_crank_fe.hpp"
#include "slider_crank.hpp"
#include "slider_crank_free.hpp"
#include "solve_saddle.hpp"
#include "spatial_slider_crank.hpp"

namespace {

struct Worst {
  double dynamics = 0.0, constraints = 0.0, udot = 0.0, lambda = 0.0;
};

/// At the initial state and seven states near it (q moved by up to 0.02, u by up to 1).
template <class System>
Worst check_saddle() {
  constexpr int nu = System::nu, nc = System::nc;
  static_assert(System::nq == nu, "q_dot = u");
  typename System::Params p;
  double q0[nu], u0[nu];
  System::initial_state(p, q0, u0);
  bool prescribed = false;
  for (int i = 0; i < nu; ++i) prescribed = prescribed || System::coordinate_roles()[i] == 2;
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> dq(-0.02, 0.02), du(-1.0, 1.0);
  Worst worst;
  for (int state = 0; state < 8; ++state) {
    double q[nu], u[nu], tau[System::ntau > 0 ? System::ntau : 1] = {}, a[nu], lambda[nc];
    for (int i = 0; i < nu; ++i) {
      const bool moves = state > 0 && System::coordinate_roles()[i] != 2;
      q[i] = q0[i] + (moves ? dq(rng) : 0.0);
      u[i] = u0[i] + (moves ? du(rng) : 0.0);
    }
    REQUIRE(System::constrained_dynamics(p, 0.0, q, u, tau, a, lambda) == 0);
    std::vector<double> M(nu * nu), f(nu), C(nc * nu), gamma(nc);
    System::mass_matrix(p, q, M.data());
    System::forcing(p, 0.0, q, u, tau, f.data());
    System::constraint_jacobian(p, q, C.data());
    System::constraint_bias(p, q, u, gamma.data());
    // The scales: the acceleration the forces alone give, and the loop
    // force that balances them (a state may be at rest, with udot = 0).
    double accel = 0.0, c_largest = 0.0, f_largest = 0.0;
    for (int i = 0; i < nu; ++i) {
      accel = std::max(accel, std::abs(f[i]) / M[i * nu + i]);
      f_largest = std::max(f_largest, std::abs(f[i]));
    }
    for (double c : C) c_largest = std::max(c_largest, std::abs(c));
    // Each residual against the size of its largest term.
    for (int i = 0; i < nu; ++i) {
      if (System::coordinate_roles()[i] == 2) continue;  // its force is whatever the drive gives
      double r = -f[i], scale = std::abs(f[i]);
      for (int j = 0; j < nu; ++j) {
        r += M[i * nu + j] * a[j];
        scale = std::max(scale, std::abs(M[i * nu + j] * a[j]));
      }
      for (int c = 0; c < nc; ++c) {
        r -= C[c * nu + i] * lambda[c];
        scale = std::max(scale, std::abs(C[c * nu + i] * lambda[c]));
      }
      worst.dynamics = std::max(worst.dynamics, std::abs(r) / std::max(scale, 1e-300));
    }
    for (int c = 0; c < nc; ++c) {
      double r = -gamma[c], scale = std::max(std::abs(gamma[c]), c_largest * accel);
      for (int j = 0; j < nu; ++j) {
        r += C[c * nu + j] * a[j];
        scale = std::max(scale, std::abs(C[c * nu + j] * a[j]));
      }
      worst.constraints = std::max(worst.constraints, std::abs(r) / std::max(scale, 1e-300));
    }
    if (prescribed) continue;
    std::vector<double> dense_lambda(nc);
    REQUIRE(kanegen_templates::solve_saddle<nu, nc>(M.data(), f.data(), C.data(), gamma.data(),
                                                    dense_lambda.data()) == 0);
    double udot_scale = accel, lambda_scale = f_largest / c_largest;
    for (int i = 0; i < nu; ++i) udot_scale = std::max(udot_scale, std::abs(f[i]));
    for (int c = 0; c < nc; ++c) lambda_scale = std::max(lambda_scale, std::abs(dense_lambda[c]));
    for (int i = 0; i < nu; ++i) worst.udot = std::max(worst.udot, std::abs(a[i] - f[i]) / udot_scale);
    for (int c = 0; c < nc; ++c)
      worst.lambda = std::max(worst.lambda, std::abs(lambda[c] - dense_lambda[c]) / lambda_scale);
  }
  return worst;
}

#define KANEGEN_CHECK_SADDLE(model)                                                                   \
  do {                                                                                                \
    const Worst w = check_saddle<kanegen_models::model::System>();                                    \
    INFO(#model ": residuals " << w.dynamics << ", " << w.constraints << "; against the dense solve " \
                               << w.udot << ", " << w.lambda);                                        \
    CHECK(w.dynamics < 1e-10);                                                                        \
    CHECK(w.constraints < 1e-10);                                                                     \
    CHECK(w.udot < 1e-10);                                                                            \
    CHECK(w.lambda < 1e-10);                                                                          \
  } while (false)

}  // namespace

TEST_CASE("the generated saddle-point solve satisfies the equations and equals the dense solve",
          "[loops][saddle]") {
  KANEGEN_CHECK_SADDLE(four_bar);
  KANEGEN_CHECK_SADDLE(slider_crank);
  KANEGEN_CHECK_SADDLE(slider_crank_free);
  KANEGEN_CHECK_SADDLE(nfourbar2);
  KANEGEN_CHECK_SADDLE(nfourbar40);
  KANEGEN_CHECK_SADDLE(andrews_squeezer);
  KANEGEN_CHECK_SADDLE(simeon_crank);
  KANEGEN_CHECK_SADDLE(simeon_crank_fe);
  KANEGEN_CHECK_SADDLE(spatial_slider_crank);
  KANEGEN_CHECK_SADDLE(rsur_spherical);
  KANEGEN_CHECK_SADDLE(rsur_revolute);
  KANEGEN_CHECK_SADDLE(ring_slider);
  KANEGEN_CHECK_SADDLE(ring_slider_flexible);
  KANEGEN_CHECK_SADDLE(quick_return);
}
