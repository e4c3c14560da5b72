// SPDX-License-Identifier: GPL-2.0-or-later
// flexible_driver: the time per call of one generated flexible model's
// forward_dynamics. bench/flexible_arm.py compiles it once per --dynamics
// (recursive, composite), with
//   -DKANEGEN_FLEX_HEADER="<flexible_arm10.hpp>" -DKANEGEN_FLEX_NAMESPACE=flexible_arm10
// and compares the runs. It prints one JSON object:
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
#include <vector>

#include KANEGEN_FLEX_HEADER

namespace {

namespace model = ::kanegen_models::KANEGEN_FLEX_NAMESPACE;
using S = model::System;
constexpr int kStates = 64;

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
  const int joints = S::ntau;  // one input per joint coordinate, none for the elastic ones
  std::vector<double> q(kStates * S::nq), u(kStates * S::nu), udot(kStates * S::nu), tau(S::ntau, 0.0);
  for (int k = 0; k < kStates; ++k)
    for (int i = 0; i < S::nq; ++i) {
      const double scale = i < joints ? 1.5 : 1e-3;
      q[k * S::nq + i] = scale * unit(rng);
      u[k * S::nu + i] = 2 * scale * unit(rng);
    }
  S::Params p{};

  // The backward error of u_dot, |M u_dot - f| / (|M| |u_dot| + |f|) (max
  // norms): M of the flexible arm is ill-conditioned (stiff modes beside
  // the joints), so the forward difference from an LDL^T of M is reported,
  // not checked.
  double backward = 0, forward = 0, condition = 0;
  std::vector<double> mass(S::nu * S::nu), forcing(S::nu);
  for (int k = 0; k < kStates; ++k) {
    const double* qk = &q[k * S::nq];
    const double* uk = &u[k * S::nu];
    if (S::forward_dynamics(p, 0.0, qk, uk, tau.data(), &udot[k * S::nu]) != 0)
      die("forward_dynamics failed at state " + std::to_string(k));
    S::mass_matrix(p, qk, mass.data());
    S::forcing(p, 0.0, qk, uk, tau.data(), forcing.data());
    const Eigen::Map<const Eigen::MatrixXd> m(mass.data(), S::nu, S::nu);
    const Eigen::Map<const Eigen::VectorXd> f(forcing.data(), S::nu), a(&udot[k * S::nu], S::nu);
    const double scale =
        m.cwiseAbs().rowwise().sum().maxCoeff() * a.cwiseAbs().maxCoeff() + f.cwiseAbs().maxCoeff();
    backward = std::max(backward, (m * a - f).cwiseAbs().maxCoeff() / scale);
    const Eigen::VectorXd reference = m.ldlt().solve(f);
    forward = std::max(forward, (a - reference).cwiseAbs().maxCoeff() / reference.cwiseAbs().maxCoeff());
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(m, Eigen::EigenvaluesOnly);
    condition = std::max(condition, eigen.eigenvalues().maxCoeff() / eigen.eigenvalues().minCoeff());
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
