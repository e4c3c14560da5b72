// SPDX-License-Identifier: GPL-2.0-or-later
// bench_loops: forward_dynamics of the loop models (four_bar, nfourbar2,
// nfourbar40) against the dense saddle-point solve, in one run, on the same
// fixed states (cycled, one state per call).
//
//   <model>/forward_dynamics   the generated kernel: M, C and the right-hand
//                              sides, then the saddle-point solve the
//                              generator chose (sparse LDL^T unrolled for the
//                              model's structure, or dense);
//   <model>/dense              the same from the model's other kernels
//                              (mass_matrix, forcing, constraint_jacobian,
//                              constraint_bias) and templates/solve_saddle.hpp,
//                              the solve dense in everything that every loop
//                              model used before the sparse one.
// Before timing, each model checks that both give the same udot (to 1e-9
// relative) at every state; it aborts otherwise.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <four_bar.hpp>
#include <nfourbar2.hpp>
#include <nfourbar40.hpp>
#include <random>
#include <string>
#include <vector>

#include "solve_saddle.hpp"

namespace {

constexpr int kStates = 64;  // a power of two: index wraps with a mask

[[noreturn]] void die(const std::string& msg) {
  std::fprintf(stderr, "bench_loops: %s\n", msg.c_str());
  std::exit(1);
}

/// The model's initial state with q and u disturbed, per state.
template <class System>
struct States {
  typename System::Params p;
  std::vector<double> q, u;
  States() : q(kStates * System::nq), u(kStates * System::nu) {
    std::mt19937 rng(17);
    std::uniform_real_distribution<double> dq(-0.05, 0.05), du(-1.0, 1.0);
    double q0[System::nq], u0[System::nu];
    System::initial_state(p, q0, u0);
    for (int s = 0; s < kStates; ++s) {
      for (int i = 0; i < System::nq; ++i) q[s * System::nq + i] = q0[i] + dq(rng);
      for (int i = 0; i < System::nu; ++i) u[s * System::nu + i] = u0[i] + du(rng);
    }
  }
};

/// udot by the dense path: the separate kernels, then solve_saddle (no prescribed speeds).
template <class System>
struct Dense {
  std::vector<double> M, C, gamma, lambda;
  Dense() : M(System::nu * System::nu), C(System::nc * System::nu), gamma(System::nc), lambda(System::nc) {}
  int operator()(const typename System::Params& p, const double* q, const double* u, const double* tau,
                 double* udot) {
    System::mass_matrix(p, q, M.data());
    System::forcing(p, 0.0, q, u, tau, udot);
    System::constraint_jacobian(p, q, C.data());
    System::constraint_bias(p, q, u, gamma.data());
    return kanegen_templates::solve_saddle<System::nu, System::nc>(M.data(), udot, C.data(), gamma.data(),
                                                                   lambda.data());
  }
};

template <class System>
void check(const char* name) {
  for (int i = 0; i < System::nq; ++i)
    if (System::coordinate_roles()[i] == 2) die(std::string(name) + " has a prescribed speed");
  States<System> states;
  Dense<System> dense;
  double tau[System::ntau > 0 ? System::ntau : 1] = {}, lambda[System::nc], a[System::nu], b[System::nu];
  for (int s = 0; s < kStates; ++s) {
    const double* q = &states.q[s * System::nq];
    const double* u = &states.u[s * System::nu];
    if (System::constrained_dynamics(states.p, 0.0, q, u, tau, a, lambda) != 0 ||
        dense(states.p, q, u, tau, b) != 0)
      die(std::string(name) + ": a solve failed at state " + std::to_string(s));
    double scale = 0.0;
    for (int i = 0; i < System::nu; ++i) scale = std::max(scale, std::abs(b[i]));
    for (int i = 0; i < System::nu; ++i)
      if (!(std::abs(a[i] - b[i]) <= 1e-9 * scale))
        die(std::string(name) + ": forward_dynamics and the dense solve differ at state " +
            std::to_string(s));
  }
}

template <class System>
void bm_forward(benchmark::State& st) {
  static const States<System> states;
  double tau[System::ntau > 0 ? System::ntau : 1] = {}, udot[System::nu];
  int s = 0;
  for (auto _ : st) {
    const int status = System::forward_dynamics(states.p, 0.0, &states.q[s * System::nq],
                                                &states.u[s * System::nu], tau, udot);
    benchmark::DoNotOptimize(status);
    benchmark::DoNotOptimize(udot);
    s = (s + 1) & (kStates - 1);
  }
}

template <class System>
void bm_dense(benchmark::State& st) {
  static const States<System> states;
  Dense<System> dense;
  double tau[System::ntau > 0 ? System::ntau : 1] = {}, udot[System::nu];
  int s = 0;
  for (auto _ : st) {
    const int status = dense(states.p, &states.q[s * System::nq], &states.u[s * System::nu], tau, udot);
    benchmark::DoNotOptimize(status);
    benchmark::DoNotOptimize(udot);
    s = (s + 1) & (kStates - 1);
  }
}

using kanegen_models::four_bar::System;
namespace nf2 = kanegen_models::nfourbar2;
namespace nf40 = kanegen_models::nfourbar40;

BENCHMARK(bm_forward<System>)->Name("four_bar/forward_dynamics");
BENCHMARK(bm_dense<System>)->Name("four_bar/dense");
BENCHMARK(bm_forward<nf2::System>)->Name("nfourbar2/forward_dynamics");
BENCHMARK(bm_dense<nf2::System>)->Name("nfourbar2/dense");
BENCHMARK(bm_forward<nf40::System>)->Name("nfourbar40/forward_dynamics");
BENCHMARK(bm_dense<nf40::System>)->Name("nfourbar40/dense");

}  // namespace

int main(int argc, char** argv) {
  check<System>("four_bar");
  check<nf2::System>("nfourbar2");
  check<nf40::System>("nfourbar40");
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
