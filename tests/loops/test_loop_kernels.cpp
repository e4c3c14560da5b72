// SPDX-License-Identifier: GPL-2.0-or-later
// The generated constraint kernels against finite differences of the
// generated Phi: the Jacobian C = dPhi/dq, and gamma = -(dC/dt) u along u.
#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <vector>

#include "four_bar.hpp"
#include "nfourbar2.hpp"
#include "quick_return.hpp"
#include "ring_slider.hpp"
#include "rsur_revolute.hpp"
#include "rsur_spherical.hpp"
#include "slider_crank.hpp"

namespace {

struct Worst {
  double jacobian = 0.0, bias = 0.0;
};

/// Largest errors over random states, each relative to the entry's scale.
template <class System>
Worst check_kernels(int samples) {
  constexpr int nq = System::nq, nu = System::nu, nc = System::nc;
  const typename System::Params p;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> angle(-3.0, 3.0), speed(-5.0, 5.0);
  Worst worst;
  for (int s = 0; s < samples; ++s) {
    std::vector<double> q(nq), u(nu), C(nc * nu), gamma(nc), phi_plus(nc), phi_minus(nc);
    for (double& v : q) v = angle(rng);
    for (double& v : u) v = speed(rng);
    System::constraint_jacobian(p, q.data(), C.data());
    System::constraint_bias(p, q.data(), u.data(), gamma.data());
    const double h = 1e-6;
    for (int k = 0; k < nq; ++k) {
      std::vector<double> qp(q), qm(q);
      qp[k] += h;
      qm[k] -= h;
      System::constraints(p, qp.data(), phi_plus.data());
      System::constraints(p, qm.data(), phi_minus.data());
      for (int r = 0; r < nc; ++r) {
        const double fd = (phi_plus[r] - phi_minus[r]) / (2 * h);
        worst.jacobian =
            std::max(worst.jacobian, std::abs(fd - C[r * nu + k]) / (1.0 + std::abs(C[r * nu + k])));
      }
    }
    // d/dt (C u) with u held: (C(q + h u) u - C(q - h u) u) / 2h = -gamma.
    std::vector<double> qp(q), qm(q), Cp(nc * nu), Cm(nc * nu);
    for (int k = 0; k < nq; ++k) {
      qp[k] += h * u[k];
      qm[k] -= h * u[k];
    }
    System::constraint_jacobian(p, qp.data(), Cp.data());
    System::constraint_jacobian(p, qm.data(), Cm.data());
    for (int r = 0; r < nc; ++r) {
      double rate = 0.0;
      for (int k = 0; k < nu; ++k) rate += (Cp[r * nu + k] - Cm[r * nu + k]) * u[k] / (2 * h);
      worst.bias = std::max(worst.bias, std::abs(rate + gamma[r]) / (1.0 + std::abs(gamma[r])));
    }
  }
  return worst;
}

}  // namespace

TEMPLATE_TEST_CASE("generated constraint kernels agree with finite differences", "[loops][kernels]",
                   kanegen_models::four_bar::System, kanegen_models::slider_crank::System,
                   kanegen_models::nfourbar2::System, kanegen_models::rsur_spherical::System,
                   kanegen_models::rsur_revolute::System, kanegen_models::ring_slider::System,
                   kanegen_models::quick_return::System) {
  const Worst worst = check_kernels<TestType>(50);
  INFO(TestType::name);
  CHECK(worst.jacobian < 1e-8);
  CHECK(worst.bias < 1e-7);
}

TEST_CASE("a corrupted Jacobian entry is caught by the finite-difference check", "[loops][kernels]") {
  // The check itself must be able to fail: compare C against the FD of a Phi scaled by 1.001.
  using System = kanegen_models::four_bar::System;
  const System::Params p;
  double q[System::nq] = {0.4, 0.9, 1.7}, C[System::nc * System::nu], plus[System::nc], minus[System::nc];
  System::constraint_jacobian(p, q, C);
  const double h = 1e-6;
  double qp[System::nq] = {0.4 + h, 0.9, 1.7}, qm[System::nq] = {0.4 - h, 0.9, 1.7};
  System::constraints(p, qp, plus);
  System::constraints(p, qm, minus);
  const double fd = 1.001 * (plus[0] - minus[0]) / (2 * h);
  CHECK(std::abs(fd - C[0]) / (1.0 + std::abs(C[0])) > 1e-5);
}
