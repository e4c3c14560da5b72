// SPDX-License-Identifier: GPL-2.0-or-later
// generalized_momentum, a kernel added by one kernel-table entry and its
// derivation, against dT/du by central differences of kinetic_energy (T is
// derived from the body velocities, independently of M). arm7 and chain20 take
// h from the recursion (the comment at the top of their kernel says which).
#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

#include "arm7.hpp"
#include "chain20.hpp"
#include "flexible_arm2.hpp"
#include "four_bar.hpp"

namespace {

template <class System>
void check_momentum_is_dT_du() {
  const typename System::Params p{};
  std::vector<double> q(System::nq), u(System::nu), h(System::nu);
  for (int i = 0; i < System::nq; ++i) q[i] = 0.3 + 0.17 * i;
  for (int i = 0; i < System::nu; ++i) u[i] = 0.5 - 0.23 * i;
  System::generalized_momentum(p, q.data(), u.data(), h.data());
  const double step = 1e-3;  // T is quadratic in u: central differences are exact but for rounding
  for (int r = 0; r < System::nu; ++r) {
    std::vector<double> plus(u), minus(u);
    plus[r] += step;
    minus[r] -= step;
    const double dT = (System::kinetic_energy(p, q.data(), plus.data()) -
                       System::kinetic_energy(p, q.data(), minus.data())) /
                      (2 * step);
    CHECK(h[r] == Approx(dT).epsilon(1e-8).margin(1e-9));
  }
}

}  // namespace

TEST_CASE("the generalized momenta are dT/du", "[kernels]") {
  check_momentum_is_dT_du<kanegen_models::arm7::System>();     // by the recursion
  check_momentum_is_dT_du<kanegen_models::chain20::System>();  // by the recursion, M as a loop
  check_momentum_is_dT_du<kanegen_models::flexible_arm2::System>();
  check_momentum_is_dT_du<kanegen_models::four_bar::System>();
}
