// SPDX-License-Identifier: GPL-2.0-or-later
// The kernels every model has for controllers, on every shipped model:
// inverse_dynamics undoes forward_dynamics to round-off, and gravity is
// the forcing at rest (u = 0) where no other force acts then.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <vector>

#include "andrews_squeezer.hpp"
#include "arm7.hpp"
#include "beam_tip_mass.hpp"
#include "cantilever.hpp"
#include "chain20.hpp"
#include "double_pendulum.hpp"
#include "flexible_arm2.hpp"
#include "four_bar.hpp"
#include "l_frame.hpp"
#include "nfourbar2.hpp"
#include "nfourbar40.hpp"
#include "simeon_crank.hpp"
#include "simeon_crank_fe.hpp"
#include "simple_pendulum.hpp"
#include "slider_crank.hpp"
#include "spatial_arm2.hpp"
#include "spatial_slider_crank.hpp"
#include "spin_up_beam.hpp"
#include "spin_up_beam_linear.hpp"
#include "spinning_beam.hpp"

namespace {

using Vector = std::vector<double>;

double max_abs(const Vector& v) {
  double m = 0;
  for (double x : v) m = std::max(m, std::abs(x));
  return m;
}

/// A random state: the initial one moved by up to 1 in each joint
/// coordinate and 1e-3 in each elastic one, random speeds and inputs.
template <class S>
void random_state(const typename S::Params& p, int joints, std::mt19937& rng, Vector& q, Vector& u,
                  Vector& tau) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  q.assign(S::nq, 0.0);
  u.assign(S::nu, 0.0);
  tau.assign(S::ntau > 0 ? S::ntau : 1, 0.0);
  S::initial_state(p, q.data(), u.data());
  for (int i = 0; i < S::nq; ++i) {
    const double size = i < joints ? 1.0 : 1e-3;
    q[i] += size * unit(rng);
    u[i] = 2 * size * unit(rng);
  }
  for (int i = 0; i < S::ntau; ++i) tau[i] = unit(rng);
}

/// tau_id = inverse_dynamics(q, u, udot) with udot from the dynamics at the
/// inputs tau must be what the inputs and the loop forces add to f:
/// f(tau) - f(0) + C^T lambda (no loops: lambda empty), on every row that
/// is solved for (`prescribed`: the rows whose acceleration is given).
/// Tolerance: 1e-11 of the size of the terms, |M udot| + |f|.
template <class S>
void check_round_trip(const Vector& q, const Vector& u, const Vector& tau, const Vector& udot,
                      const Vector& ct_lambda, const std::vector<int>& prescribed) {
  const typename S::Params p;
  const int n = S::nu;
  Vector tau_id(n), f(n), f0(n), M(n * n), zero(tau.size(), 0.0), m_udot(n, 0.0);
  S::inverse_dynamics(p, 0.3, q.data(), u.data(), udot.data(), tau_id.data());
  S::forcing(p, 0.3, q.data(), u.data(), tau.data(), f.data());
  S::forcing(p, 0.3, q.data(), u.data(), zero.data(), f0.data());
  S::mass_matrix(p, q.data(), M.data());
  for (int r = 0; r < n; ++r)
    for (int c = 0; c < n; ++c) m_udot[r] += M[r * n + c] * udot[c];
  const double scale = max_abs(m_udot) + max_abs(f);
  for (int r = 0; r < n; ++r) {
    if (std::find(prescribed.begin(), prescribed.end(), r) != prescribed.end()) continue;
    const double expected = f[r] - f0[r] + (ct_lambda.empty() ? 0.0 : ct_lambda[r]);
    INFO(S::name << " row " << r << ": inverse_dynamics " << tau_id[r] << ", expected " << expected
                 << ", scale " << scale);
    CHECK(std::abs(tau_id[r] - expected) <= 1e-11 * scale);
  }
}

template <class S>
void check_tree(int joints, std::vector<int> prescribed = {}) {
  const typename S::Params p;
  std::mt19937 rng(11);
  for (int sample = 0; sample < 3; ++sample) {
    Vector q, u, tau, udot(S::nu);
    random_state<S>(p, joints, rng, q, u, tau);
    REQUIRE(S::forward_dynamics(p, 0.3, q.data(), u.data(), tau.data(), udot.data()) == 0);
    check_round_trip<S>(q, u, tau, udot, {}, prescribed);
  }
}

/// With loops: the loop forces C^T lambda join the inputs; `roles` marks the prescribed coordinates (2).
template <class S>
void check_loops(int joints, const int* roles) {
  const typename S::Params p;
  std::mt19937 rng(12);
  std::vector<int> prescribed;
  for (int i = 0; i < S::nu; ++i)
    if (roles[i] == 2) prescribed.push_back(i);
  int solved = 0;
  for (int sample = 0; sample < 3; ++sample) {
    Vector q, u, tau, udot(S::nu), lambda(S::nc), C(S::nc * S::nu), ct_lambda(S::nu, 0.0);
    random_state<S>(p, joints, rng, q, u, tau);
    if (S::constrained_dynamics(p, 0.3, q.data(), u.data(), tau.data(), udot.data(), lambda.data()) != 0)
      continue;
    ++solved;
    S::constraint_jacobian(p, q.data(), C.data());
    for (int r = 0; r < S::nu; ++r)
      for (int c = 0; c < S::nc; ++c) ct_lambda[r] += C[c * S::nu + r] * lambda[c];
    check_round_trip<S>(q, u, tau, udot, ct_lambda, prescribed);
  }
  CHECK(solved > 0);
}

/// gravity(q) = -f(q, u = 0, tau = 0) where nothing but gravity acts at rest
/// (no springs; elastic coordinates at 0, where the strain has no force).
template <class S>
void check_gravity(int joints) {
  const typename S::Params p;
  std::mt19937 rng(13);
  for (int sample = 0; sample < 3; ++sample) {
    Vector q, u, tau, g(S::nu), f(S::nu);
    random_state<S>(p, joints, rng, q, u, tau);
    for (int i = joints; i < S::nq; ++i) q[i] = 0.0;
    std::fill(u.begin(), u.end(), 0.0);
    std::fill(tau.begin(), tau.end(), 0.0);
    S::gravity(p, q.data(), g.data());
    S::forcing(p, 0.0, q.data(), u.data(), tau.data(), f.data());
    CHECK(max_abs(g) > 0.1);  // the models are in gravity
    for (int r = 0; r < S::nu; ++r) {
      INFO(S::name << " row " << r << ": gravity " << g[r] << ", -forcing at rest " << -f[r]);
      CHECK(std::abs(g[r] + f[r]) <= 1e-12 * (max_abs(f) + 1.0));
    }
  }
}

}  // namespace

namespace km = kanegen_models;

TEST_CASE("inverse_dynamics undoes forward_dynamics on the rigid trees") {
  check_tree<km::simple_pendulum::System>(1);
  check_tree<km::double_pendulum::System>(2);
  check_tree<km::arm7::System>(7);
  check_tree<km::chain20::System>(20);
}

TEST_CASE("inverse_dynamics undoes forward_dynamics with flexible bodies") {
  check_tree<km::cantilever::System>(0);
  check_tree<km::l_frame::System>(0);
  check_tree<km::beam_tip_mass::System>(1);
  check_tree<km::flexible_arm2::System>(2);
  check_tree<km::spatial_arm2::System>(2);
  // The hub's speed (0) is prescribed: its row is the effort that drives it.
  check_tree<km::spinning_beam::System>(1, {0});
  check_tree<km::spin_up_beam::System>(1, {0});
  check_tree<km::spin_up_beam_linear::System>(1, {0});
}

TEST_CASE("inverse_dynamics with loops gives the inputs and the loop forces") {
  check_loops<km::four_bar::System>(km::four_bar::NQ, km::four_bar::coordinate_roles);
  check_loops<km::slider_crank::System>(km::slider_crank::NQ, km::slider_crank::coordinate_roles);
  check_loops<km::andrews_squeezer::System>(km::andrews_squeezer::NQ, km::andrews_squeezer::coordinate_roles);
  check_loops<km::nfourbar2::System>(km::nfourbar2::NQ, km::nfourbar2::coordinate_roles);
  check_loops<km::nfourbar40::System>(km::nfourbar40::NQ, km::nfourbar40::coordinate_roles);
  check_loops<km::spatial_slider_crank::System>(4, km::spatial_slider_crank::coordinate_roles);
  check_loops<km::simeon_crank::System>(3, km::simeon_crank::coordinate_roles);
  check_loops<km::simeon_crank_fe::System>(3, km::simeon_crank_fe::coordinate_roles);
}

TEST_CASE("gravity is the forcing at rest") {
  check_gravity<km::simple_pendulum::System>(1);
  check_gravity<km::double_pendulum::System>(2);
  check_gravity<km::arm7::System>(7);
  check_gravity<km::chain20::System>(20);
  check_gravity<km::flexible_arm2::System>(2);  // the gradient of the gravity potential, with elastic bodies
  check_gravity<km::spatial_arm2::System>(2);
}
