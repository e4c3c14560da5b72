// SPDX-License-Identifier: GPL-2.0-or-later
// M(q) is symmetric positive definite at random states, for every shipped model.
#include <catch2/catch.hpp>

#include <Eigen/Dense>
#include <random>

#include "arm7.hpp"
#include "chain20.hpp"
#include "double_pendulum.hpp"
#include "simple_pendulum.hpp"
#include "system_helpers.hpp"

namespace {

template <class System>
void check_spd(int samples) {
  typename System::Params p;
  std::mt19937 rng(20261121);
  for (int k = 0; k < samples; ++k) {
    const auto x = kanegen_test::random_state<System>(rng, M_PI, 2.0);
    Eigen::Matrix<double, System::nu, System::nu, Eigen::RowMajor> m;
    System::mass_matrix(p, x.data(), m.data());
    INFO(System::name << " sample " << k);
    CHECK((m - m.transpose()).cwiseAbs().maxCoeff() <= 1e-14 * m.cwiseAbs().maxCoeff());
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(m);
    CHECK(eig.eigenvalues().minCoeff() > 0.0);
    // forward_dynamics solves M udot = f: its residual is at round-off level.
    double tau[System::ntau] = {}, f[System::nu], udot[System::nu];
    System::forcing(p, 0.0, x.data(), x.data() + System::nq, tau, f);
    REQUIRE(System::forward_dynamics(p, 0.0, x.data(), x.data() + System::nq, tau, udot) == 0);
    const Eigen::Map<Eigen::Matrix<double, System::nu, 1>> a(udot), b(f);
    CHECK((m * a - b).norm() <= 1e-10 * (m.norm() * a.norm() + b.norm()));
  }
}

}  // namespace

TEST_CASE("mass matrices are symmetric positive definite", "[regression][mass]") {
  check_spd<kanegen_models::simple_pendulum::System>(20);
  check_spd<kanegen_models::double_pendulum::System>(50);
  check_spd<kanegen_models::arm7::System>(50);
  check_spd<kanegen_models::chain20::System>(20);
}
