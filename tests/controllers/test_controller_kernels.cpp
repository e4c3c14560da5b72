// SPDX-License-Identifier: GPL-2.0-or-later
// The kernels of kanegen generate --controller against references made
// without them: coriolis_matrix against the velocity terms of forcing and
// Mdot - 2C skew-symmetric (Mdot by central differences of mass_matrix along
// u), the output Jacobians against central differences of outputs, and
// linearize against central differences of forward_dynamics. Each
// difference takes one Richardson step (error O(h^4)).
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <functional>
#include <random>
#include <vector>

#include "arm7.hpp"
#include "double_pendulum.hpp"
#include "flexible_arm2.hpp"

namespace {

using Vector = std::vector<double>;
using Function = std::function<Vector(const Vector&)>;

double max_abs(const Vector& v) {
  double m = 0;
  for (double x : v) m = std::max(m, std::abs(x));
  return m;
}

/// d g(x + s d)/ds at s = 0 by central differences with one Richardson step.
Vector directional(const Function& g, const Vector& x, const Vector& d, double h) {
  const auto central = [&](double step) {
    Vector plus = x, minus = x;
    for (std::size_t k = 0; k < x.size(); ++k) {
      plus[k] += step * d[k];
      minus[k] -= step * d[k];
    }
    Vector a = g(plus);
    const Vector b = g(minus);
    for (std::size_t i = 0; i < a.size(); ++i) a[i] = (a[i] - b[i]) / (2 * step);
    return a;
  };
  const Vector coarse = central(h), fine = central(h / 2);
  Vector out(coarse.size());
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = (4 * fine[i] - coarse[i]) / 3;
  return out;
}

/// Column k of the Jacobian of g: the directional derivative along e_k.
Vector column(const Function& g, const Vector& x, std::size_t k, double h) {
  Vector e(x.size(), 0.0);
  e[k] = 1.0;
  return directional(g, x, e, h);
}

/// Entries agree to `tolerance` of the largest of the reference (and 1).
void check_close(const char* what, const Vector& kernel, const Vector& reference, double tolerance) {
  REQUIRE(kernel.size() == reference.size());
  const double scale = std::max(1.0, max_abs(reference));
  for (std::size_t k = 0; k < kernel.size(); ++k) {
    INFO(what << " entry " << k << ": kernel " << kernel[k] << ", reference " << reference[k]);
    CHECK(std::abs(kernel[k] - reference[k]) <= tolerance * scale);
  }
}

template <class S>
struct State {
  typename S::Params p;
  Vector q, u, tau;
  State(int joints, std::mt19937& rng) : q(S::nq), u(S::nu), tau(S::ntau) {
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    S::initial_state(p, q.data(), u.data());
    for (int i = 0; i < S::nq; ++i) {
      const double size = i < joints ? 1.0 : 1e-3;
      q[i] += size * unit(rng);
      u[i] = 2 * size * unit(rng);
    }
    for (double& t : tau) t = unit(rng);
  }
};

/// C u = -(f(q, u, 0) - f(q, 0, 0)) - (damping, linear in u: `damping`
/// per speed), and N = Mdot - 2C skew: N + N^T = 0.
template <class S>
void check_coriolis(int joints, const Vector& damping) {
  std::mt19937 rng(21);
  const int n = S::nu;
  for (int sample = 0; sample < 3; ++sample) {
    const State<S> s(joints, rng);
    Vector C(n * n), f(n), f0(n), zero_tau(S::ntau > 0 ? S::ntau : 1, 0.0), rest(n, 0.0), cu(n, 0.0),
        velocity(n);
    S::coriolis_matrix(s.p, s.q.data(), s.u.data(), C.data());
    S::forcing(s.p, 0.0, s.q.data(), s.u.data(), zero_tau.data(), f.data());
    S::forcing(s.p, 0.0, s.q.data(), rest.data(), zero_tau.data(), f0.data());
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j < n; ++j) cu[i] += C[i * n + j] * s.u[j];
      velocity[i] = -(f[i] - f0[i]) - damping[i] * s.u[i];
    }
    check_close("C u", cu, velocity, 1e-10);
    const Function mass = [&](const Vector& q) {
      Vector M(n * n);
      S::mass_matrix(s.p, q.data(), M.data());
      return M;
    };
    const Vector mdot = directional(mass, s.q, s.u, 1e-3);
    Vector skew(n * n), zero(n * n, 0.0);
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j)
        skew[i * n + j] = (mdot[i * n + j] - 2 * C[i * n + j]) + (mdot[j * n + i] - 2 * C[j * n + i]);
    CHECK(max_abs(C) > 1e-3);
    check_close("N + N^T", skew, zero, 1e-8 * std::max(1.0, max_abs(mdot)));
  }
}

/// J = d(outputs)/dq on the rows of position (`rows`); Jdot_u the rate of J u along q + s u.
template <class S>
void check_output_jacobians(int joints, const std::vector<int>& rows) {
  std::mt19937 rng(22);
  const int n = S::nu, ny = S::ny;
  for (int sample = 0; sample < 3; ++sample) {
    const State<S> s(joints, rng);
    Vector J(ny * n), jdot_u(ny);
    S::output_jacobian(s.p, 0.0, s.q.data(), J.data());
    S::output_jacobian_rate(s.p, 0.0, s.q.data(), s.u.data(), jdot_u.data());
    const Function outputs = [&](const Vector& q) {
      Vector y(ny);
      S::outputs(s.p, 0.0, q.data(), s.u.data(), y.data());
      return y;
    };
    const Function velocity = [&](const Vector& q) {
      Vector jq(ny * n), v(ny, 0.0);
      S::output_jacobian(s.p, 0.0, q.data(), jq.data());
      for (int i = 0; i < ny; ++i)
        for (int j = 0; j < n; ++j) v[i] += jq[i * n + j] * s.u[j];
      return v;
    };
    Vector kernel, reference;
    for (int j = 0; j < n; ++j) {
      const Vector by_q = column(outputs, s.q, j, j < joints ? 1e-3 : 1e-5);
      for (int i : rows) {
        kernel.push_back(J[i * n + j]);
        reference.push_back(by_q[i]);
      }
    }
    check_close("J", kernel, reference, 1e-8);
    const Vector rate = directional(velocity, s.q, s.u, 1e-4);
    Vector rate_rows, jdot_rows;
    for (int i : rows) {
      rate_rows.push_back(rate[i]);
      jdot_rows.push_back(jdot_u[i]);
    }
    CHECK(max_abs(jdot_rows) > 1e-3);
    check_close("Jdot_u", jdot_rows, rate_rows, 1e-8);
  }
}

/// A and B against central differences of xdot = (u, forward_dynamics) in
/// x = (q, u) and tau.
template <class S>
void check_linearize(int joints) {
  std::mt19937 rng(23);
  const int n = S::nu, nx = 2 * S::nu, ntau = S::ntau;
  for (int sample = 0; sample < 2; ++sample) {
    const State<S> s(joints, rng);
    Vector A(nx * nx), B(nx * ntau);
    REQUIRE(S::linearize(s.p, 0.0, s.q.data(), s.u.data(), s.tau.data(), A.data(), B.data()) == 0);
    const auto xdot = [&](const Vector& x, const Vector& tau) {
      Vector out(nx);
      for (int i = 0; i < n; ++i) out[i] = x[n + i];
      S::forward_dynamics(s.p, 0.0, x.data(), x.data() + n, tau.data(), out.data() + n);
      return out;
    };
    Vector x(s.q);
    x.insert(x.end(), s.u.begin(), s.u.end());
    Vector a_ref(nx * nx), b_ref(nx * ntau);
    for (int k = 0; k < nx; ++k) {
      const Vector c =
          column([&](const Vector& v) { return xdot(v, s.tau); }, x, k, k % n < joints ? 1e-3 : 1e-6);
      for (int i = 0; i < nx; ++i) a_ref[i * nx + k] = c[i];
    }
    for (int k = 0; k < ntau; ++k) {
      const Vector c = column([&](const Vector& tau) { return xdot(x, tau); }, s.tau, k, 1e-2);
      for (int i = 0; i < nx; ++i) b_ref[i * ntau + k] = c[i];
    }
    check_close("A", A, a_ref, 1e-7);
    check_close("B", B, b_ref, 1e-7);
  }
}

}  // namespace

namespace km = kanegen_models;

TEST_CASE("coriolis_matrix gives the velocity terms and Mdot - 2C is skew") {
  check_coriolis<km::arm7::System>(7, Vector(7, 0.0));
  check_coriolis<km::double_pendulum::System>(2, {0.0, 0.0});  // c1 = c2 = 0 by default
  check_coriolis<km::flexible_arm2::System>(2, Vector(km::flexible_arm2::NU, 0.0));
}

TEST_CASE("output_jacobian and output_jacobian_rate against differences of the outputs") {
  check_output_jacobians<km::double_pendulum::System>(2, {0, 1, 2, 3, 4});
  check_output_jacobians<km::flexible_arm2::System>(2, {0, 1, 2, 3, 4, 5, 6, 7, 8, 9});
}

TEST_CASE("linearize against differences of forward_dynamics") {
  check_linearize<km::arm7::System>(7);
  check_linearize<km::double_pendulum::System>(2);
  check_linearize<km::flexible_arm2::System>(2);
}
