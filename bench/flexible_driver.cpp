// SPDX-License-Identifier: GPL-2.0-or-later
// flexible_driver: the time per call of one generated flexible model's
// forward_dynamics. bench/flexible_arm.py compiles it once per --dynamics
// (recursive, composite), with
//   -DKANEGEN_FLEX_HEADER="<flexible_arm10.hpp>" -DKANEGEN_FLEX_NAMESPACE=flexible_arm10
// and compares the runs; bench/solid_slider_crank.py once per number of modes.
// A model with loops (System::nc) is timed the same way: its forward_dynamics
// solves the saddle point [M C^T; C 0] [u_dot; -lambda] = [f; gamma], which
// the checks below then use in place of M u_dot = f. It prints one JSON object:
//   {"forward_dynamics_ns": ..., "backward_error": ..., "udot_vs_ldlt": ...,
//    "condition_of_M": ..., "udot": [...]}
// the median time per call over a fixed set of states; at those states the
// largest backward error of u_dot in the same kernels' M u_dot = f, the
// largest difference (relative to max |u_dot|) from a dense LDL^T (Eigen) of
// M and f, and M's largest condition number; u_dot at the first state (the
// script checks that both methods agree on it). It exits 1 if a kernel fails
// or its backward error passes 1e-12, so a wrong kernel is never timed.
#include <Eigen/Dense>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <type_traits>
#include <vector>

#include KANEGEN_FLEX_HEADER

namespace {

namespace model = ::kanegen_models::KANEGEN_FLEX_NAMESPACE;
using S = model::System;
constexpr int kStates = 64;

/// The model's loop-closure equations (0 for a tree, whose System has no nc).
template <class T, class = void>
struct Loops : std::integral_constant<int, 0> {};
template <class T>
struct Loops<T, std::void_t<decltype(T::nc)>> : std::integral_constant<int, T::nc> {};
constexpr int kNc = Loops<S>::value;

/// Whether speed i is prescribed (q_dot = u: coordinate i is speed i); only models with a prescribed
/// motion have coordinate_roles.
template <class T, class = void>
struct Roles {
  static bool prescribed(int) { return false; }
};
template <class T>
struct Roles<T, std::void_t<decltype(T::coordinate_roles())>> {
  static bool prescribed(int i) { return T::coordinate_roles()[i] == 2; }
};

/// M and f at a state; with loops, the saddle point's matrix [M C^T; C 0] and [f; gamma] (C^T lambda is
/// the loop force on f, so that the solution is [u_dot; -lambda]). The row of a prescribed speed says
/// that it takes the acceleration `udot` has there (its motion's; its row of M u_dot = f is the drive).
/// Returns the condition number of M.
/// (Templates, so that a tree's System need not have the loop kernels.)
template <class Sys = S>
double system(const typename Sys::Params& p, const double* q, const double* u, const double* tau,
              const double* udot, Eigen::MatrixXd& m, Eigen::VectorXd& f) {
  std::vector<double> mass(Sys::nu * Sys::nu), forcing(Sys::nu);
  Sys::mass_matrix(p, q, mass.data());
  Sys::forcing(p, 0.0, q, u, tau, forcing.data());
  m = Eigen::MatrixXd::Zero(Sys::nu + kNc, Sys::nu + kNc);
  f = Eigen::VectorXd::Zero(Sys::nu + kNc);
  m.topLeftCorner(Sys::nu, Sys::nu) = Eigen::Map<const Eigen::MatrixXd>(mass.data(), Sys::nu, Sys::nu);
  f.head(Sys::nu) = Eigen::Map<const Eigen::VectorXd>(forcing.data(), Sys::nu);
  if constexpr (kNc > 0) {
    std::vector<double> jacobian(kNc * Sys::nu), gamma(kNc);
    Sys::constraint_jacobian(p, q, jacobian.data());
    Sys::constraint_bias(p, q, u, gamma.data());
    const Eigen::Map<const Eigen::Matrix<double, kNc, Sys::nu, Eigen::RowMajor>> c(jacobian.data());
    m.bottomLeftCorner(kNc, Sys::nu) = c;
    m.topRightCorner(Sys::nu, kNc) = c.transpose();
    f.tail(kNc) = Eigen::Map<const Eigen::VectorXd>(gamma.data(), kNc);
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(m.topLeftCorner(Sys::nu, Sys::nu),
                                                             Eigen::EigenvaluesOnly);
  for (int i = 0; i < Sys::nu; ++i)
    if (Roles<Sys>::prescribed(i)) {
      m.row(i).setZero();
      m(i, i) = 1;
      f[i] = udot[i];
    }
  return eigen.eigenvalues().maxCoeff() / eigen.eigenvalues().minCoeff();
}

/// The solution [u_dot; -lambda] of the system at state k, from the model's own kernels.
template <class Sys = S>
Eigen::VectorXd solution(const typename Sys::Params& p, const double* q, const double* u, const double* tau,
                         double* udot) {
  Eigen::VectorXd x(Sys::nu + kNc);
  if constexpr (kNc > 0) {
    double lambda[kNc > 0 ? kNc : 1];
    if (Sys::constrained_dynamics(p, 0.0, q, u, tau, udot, lambda) != 0) return {};
    for (int i = 0; i < kNc; ++i) x[Sys::nu + i] = -lambda[i];
  } else if (Sys::forward_dynamics(p, 0.0, q, u, tau, udot) != 0) {
    return {};
  }
  x.head(Sys::nu) = Eigen::Map<const Eigen::VectorXd>(udot, Sys::nu);
  return x;
}

[[noreturn]] void die(const std::string& msg) {
  std::fprintf(stderr, "flexible_driver: %s\n", msg.c_str());
  std::exit(1);
}

/// Median nanoseconds per call of `call(k)` over batches of all states (as scaling_driver.cpp).
template <class Call>
double median_ns(Call call) {
  const auto batch = [&] {
    const auto start = std::chrono::steady_clock::now();
    for (int k = 0; k < kStates; ++k) call(k);
    return std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - start).count() /
           kStates;
  };
  double total = 0;
  int warmup = 0;
  while (total < 2e8 && warmup < 1000) total += batch() * kStates, ++warmup;  // about 0.2 s
  std::vector<double> times;
  const int batches = std::max(21, std::min(2001, static_cast<int>(1e9 / std::max(total / warmup, 1.0))));
  for (int b = 0; b < batches; ++b) times.push_back(batch());
  std::nth_element(times.begin(), times.begin() + batches / 2, times.end());
  return times[batches / 2];
}

}  // namespace

int main() {
  // Joint angles and rates of order 1, elastic coordinates and rates of the
  // order of the arm's deflections (modal amplitudes).
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::vector<double> q(kStates * S::nq), u(kStates * S::nu), udot(kStates * S::nu), tau(S::ntau, 0.0);
  for (int k = 0; k < kStates; ++k)
    for (int i = 0; i < S::nq; ++i) {
      const bool joint = model::coordinate_joints[i][0] != '\0';  // "" for an elastic coordinate
      const double scale = joint ? 1.5 : 1e-3;
      q[k * S::nq + i] = scale * unit(rng);
      u[k * S::nu + i] = 2 * scale * unit(rng);
    }
  S::Params p{};

  // The backward error of u_dot, |M u_dot - f| / (|M| |u_dot| + |f|) (max
  // norms; with loops, of the saddle point): M of the flexible arm is
  // ill-conditioned (stiff modes beside the joints), so the forward
  // difference from a dense solve (LDL^T of M, LU of a saddle point) is
  // reported, not checked.
  double backward = 0, forward = 0, condition = 0;
  for (int k = 0; k < kStates; ++k) {
    const double* qk = &q[k * S::nq];
    const double* uk = &u[k * S::nu];
    const Eigen::VectorXd a = solution(p, qk, uk, tau.data(), &udot[k * S::nu]);
    if (a.size() == 0) die("forward_dynamics failed at state " + std::to_string(k));
    Eigen::MatrixXd m;
    Eigen::VectorXd f;
    condition = std::max(condition, system(p, qk, uk, tau.data(), &udot[k * S::nu], m, f));
    const double scale =
        m.cwiseAbs().rowwise().sum().maxCoeff() * a.cwiseAbs().maxCoeff() + f.cwiseAbs().maxCoeff();
    backward = std::max(backward, (m * a - f).cwiseAbs().maxCoeff() / scale);
    const Eigen::VectorXd reference = kNc > 0 ? Eigen::VectorXd(m.fullPivLu().solve(f)) : m.ldlt().solve(f);
    forward = std::max(forward, (a - reference).head(S::nu).cwiseAbs().maxCoeff() /
                                    reference.head(S::nu).cwiseAbs().maxCoeff());
  }
  if (!(backward < 1e-12)) {
    char text[64];
    std::snprintf(text, sizeof text, "%.3g", backward);
    die(std::string("forward_dynamics does not solve M u_dot = f: backward error ") + text);
  }

  std::vector<double> sink(S::nu);
  const double ns = median_ns([&](int k) {
    S::forward_dynamics(p, 0.0, &q[k * S::nq], &u[k * S::nu], tau.data(), sink.data());
    asm volatile("" : : "r"(sink.data()) : "memory");
  });
  std::printf(
      "{\"forward_dynamics_ns\": %.1f, \"backward_error\": %.3g, \"udot_vs_ldlt\": %.3g, "
      "\"condition_of_M\": %.3g, \"udot\": [",
      ns, backward, forward, condition);
  for (int i = 0; i < S::nu; ++i) std::printf("%s%.17g", i ? ", " : "", udot[i]);
  std::printf("]}\n");
  return 0;
}
