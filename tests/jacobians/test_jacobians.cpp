// SPDX-License-Identifier: GPL-2.0-or-later
// The Jacobian kernels of implicit integration (kanegen generate
// --jacobians) against central differences, with one Richardson step, of
// the compiled kernels they differentiate: forcing_jacobian of forcing,
// mass_matrix_product_jacobian of mass_matrix times a, and
// constraint_force_jacobian of constraint_jacobian transposed times lambda,
// at random states. Each check is shown to fail when any one entry of the
// kernel's matrix that is clearly nonzero has its sign flipped.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include "arm7.hpp"
#include "double_pendulum.hpp"
#include "four_bar.hpp"
#include "kanegen/runtime/model.hpp"
#include "simeon_crank_fe.hpp"
#include "slider_crank.hpp"
#include "spin_up_beam.hpp"

namespace {

using kanegen::runtime::Model;
using Vector = std::vector<double>;
using Function = std::function<Vector(const Vector&)>;

/// Tolerance of an entry's error, relative to its scale (see Matrices::scale).
constexpr double kTolerance = 1e-6;

/// Central differences of g at x, step h[k] in x[k], with one Richardson
/// step ((4 D(h/2) - D(h)) / 3, error O(h^4)), m x n row-major, and in
/// `noise` each entry's round-off: about eps |g_i| / h_k, here with a factor
/// 100 for the terms of g_i that cancel (an elastic row's stiffness force is
/// far larger than the derivatives of its other terms).
Vector central_differences(const Function& g, const Vector& x, const Vector& h, Vector& noise) {
  constexpr double kEpsilon = 2.2e-16;
  const std::size_t n = x.size();
  const Vector g0 = g(x);
  Vector jacobian(g0.size() * n);
  noise.assign(g0.size() * n, 0.0);
  for (std::size_t k = 0; k < n; ++k) {
    const auto central = [&](double step) {
      Vector plus = x, minus = x;
      plus[k] += step;
      minus[k] -= step;
      Vector d = g(plus);
      const Vector b = g(minus);
      for (std::size_t i = 0; i < d.size(); ++i) d[i] = (d[i] - b[i]) / (2 * step);
      return d;
    };
    const Vector coarse = central(h[k]), fine = central(h[k] / 2);
    for (std::size_t i = 0; i < g0.size(); ++i) {
      jacobian[i * n + k] = (4 * fine[i] - coarse[i]) / 3;
      noise[i * n + k] = 100 * kEpsilon * std::abs(g0[i]) / h[k];
    }
  }
  return jacobian;
}

/// A kernel's matrix and its finite-difference reference, compared entry by
/// entry: the error, less the differences' round-off, relative to the
/// entry's size, not below 1e-3 of the largest entry of its row nor 1e-6 of
/// the largest entry overall (an entry that is zero by structure is held to
/// the round-off of its neighbours).
struct Matrices {
  std::string name;
  int rows = 0, columns = 0;
  Vector kernel, reference, noise;

  double scale(int k) const {
    const int row = k / columns;
    double row_max = 0, all_max = 0;
    for (int c = 0; c < columns; ++c) row_max = std::max(row_max, std::abs(reference[row * columns + c]));
    for (double x : reference) all_max = std::max(all_max, std::abs(x));
    const double s = std::max({std::abs(reference[k]), 1e-3 * row_max, 1e-6 * all_max});
    return s > 0 ? s : 1.0;
  }
  double error(const Vector& values, int k) const {
    return std::max(0.0, std::abs(values[k] - reference[k]) - noise[k]) / scale(k);
  }
  /// The first entry of `values` off the reference, or -1.
  int mismatch(const Vector& values) const {
    for (int k = 0; k < rows * columns; ++k)
      if (!(error(values, k) <= kTolerance)) return k;
    return -1;
  }
};

void check(const Matrices& m) {
  INFO(m.name);
  const int k = m.mismatch(m.kernel);
  if (k >= 0) {
    INFO("entry [" << k / m.columns << "," << k % m.columns << "]: kernel " << m.kernel[k] << ", differences "
                   << m.reference[k]);
    CHECK(k < 0);
  }
  // The check can fail: a sign error in any clearly nonzero entry is caught.
  int flipped = 0;
  for (int e = 0; e < m.rows * m.columns; ++e) {
    if (std::abs(m.kernel[e]) < 10 * kTolerance * m.scale(e) || std::abs(m.kernel[e]) < m.noise[e]) continue;
    Vector wrong = m.kernel;
    wrong[e] = -wrong[e];
    INFO("sign of entry " << e << " flipped");
    CHECK(m.mismatch(wrong) >= 0);
    ++flipped;
  }
  CHECK(flipped > 0);
}

/// A random state near the initial one: joint coordinates within 1 (rad or
/// m) of it, elastic ones of a small deformation (1e-3), and the steps of
/// the differences.
struct State {
  Vector q, u, tau, a, lambda, q_step, u_step;
};

State random_state(const Model& model, int joints, std::mt19937& rng) {
  const auto& info = model.info();
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  State s;
  for (int i = 0; i < info.nq; ++i) {
    const double size = i < joints ? 1.0 : 1e-3;
    s.q.push_back(info.q0[i] + size * unit(rng));
    s.u.push_back(2 * size * unit(rng));
    // Steps as large as truncation allows, as round-off (eps |f| / h) is
    // large where f holds large elastic forces: the error of the Richardson
    // step is of 4th order, and f is quadratic in u.
    s.q_step.push_back((i < joints ? 1e-3 : 1e-2) * size);
    s.u_step.push_back(0.1 * size);
    s.a.push_back(unit(rng));
  }
  for (int i = 0; i < info.ntau; ++i) s.tau.push_back(unit(rng));
  for (int c = 0; c < info.nc; ++c) s.lambda.push_back(unit(rng));
  return s;
}

void check_forcing_jacobian(const Model& model, const State& s, double t) {
  const int n = model.info().nu;
  Vector dfdq(n * n), dfdu(n * n);
  model.forcing_jacobian(t, s.q.data(), s.u.data(), s.tau.data(), dfdq.data(), dfdu.data());
  const Function f_of_q = [&](const Vector& q) {
    Vector f(n);
    model.forcing(t, q.data(), s.u.data(), s.tau.data(), f.data());
    return f;
  };
  const Function f_of_u = [&](const Vector& u) {
    Vector f(n);
    model.forcing(t, s.q.data(), u.data(), s.tau.data(), f.data());
    return f;
  };
  Vector noise;
  Vector by_q = central_differences(f_of_q, s.q, s.q_step, noise);
  check({"dfdq", n, n, dfdq, by_q, noise});
  Vector by_u = central_differences(f_of_u, s.u, s.u_step, noise);
  check({"dfdu", n, n, dfdu, by_u, noise});
}

void check_mass_matrix_product_jacobian(const Model& model, const State& s) {
  const int n = model.info().nu;
  Vector dMa(n * n);
  model.mass_matrix_product_jacobian(s.q.data(), s.a.data(), dMa.data());
  const Function Ma_of_q = [&](const Vector& q) {
    Vector M(n * n), Ma(n, 0.0);
    model.mass_matrix(q.data(), M.data());
    for (int r = 0; r < n; ++r)
      for (int c = 0; c < n; ++c) Ma[r] += M[r * n + c] * s.a[c];
    return Ma;
  };
  Vector noise;
  Vector reference = central_differences(Ma_of_q, s.q, s.q_step, noise);
  check({"d(M a)/dq", n, n, dMa, reference, noise});
}

void check_constraint_force_jacobian(const Model& model, const State& s) {
  const int n = model.info().nu, nc = model.info().nc;
  Vector dCl(n * n);
  model.constraint_force_jacobian(s.q.data(), s.lambda.data(), dCl.data());
  const Function Cl_of_q = [&](const Vector& q) {
    Vector C(nc * n), Cl(n, 0.0);
    model.constraint_jacobian(q.data(), C.data());
    for (int r = 0; r < n; ++r)
      for (int c = 0; c < nc; ++c) Cl[r] += C[c * n + r] * s.lambda[c];
    return Cl;
  };
  Vector noise;
  Vector reference = central_differences(Cl_of_q, s.q, s.q_step, noise);
  check({"d(C^T lambda)/dq", n, n, dCl, reference, noise});
}

/// Every Jacobian kernel of the model at a few random states; `joints`:
/// its number of joint coordinates (the others are elastic).
template <class System>
void check_model(int joints) {
  const Model model = kanegen::runtime::make_model<System>();
  REQUIRE(model.has_jacobians());
  std::mt19937 rng(7);
  for (int sample = 0; sample < 3; ++sample) {
    INFO("sample " << sample);
    const State s = random_state(model, joints, rng);
    check_forcing_jacobian(model, s, 0.1 + 0.37 * sample);
    check_mass_matrix_product_jacobian(model, s);
    if (model.info().nc > 0) check_constraint_force_jacobian(model, s);
  }
}

}  // namespace

TEST_CASE("rigid trees: the Jacobian kernels are the derivatives of forcing and M a", "[jacobians]") {
  check_model<kanegen_models::double_pendulum::System>(2);
  check_model<kanegen_models::arm7::System>(7);
}

TEST_CASE("a flexible beam with geometric stiffening on a prescribed hub", "[jacobians]") {
  check_model<kanegen_models::spin_up_beam::System>(1);
}

TEST_CASE("closed loops: also the derivative of the loop forces C^T lambda", "[jacobians]") {
  check_model<kanegen_models::slider_crank::System>(3);
  check_model<kanegen_models::simeon_crank_fe::System>(3);
}

TEST_CASE("a model generated without jacobians has none", "[jacobians]") {
  const Model model = kanegen::runtime::make_model<kanegen_models::four_bar::System>();
  CHECK_FALSE(model.has_jacobians());
}
