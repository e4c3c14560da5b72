// SPDX-License-Identifier: GPL-2.0-or-later
// scaling_driver: one generated model's forward_dynamics against MuJoCo's
// mj_forward on the same URDF, in one run; bench/scaling.py compiles it once
// per chain length, with
//   -DKANEGEN_SCALING_HEADER="<chainN.hpp>" -DKANEGEN_SCALING_NAMESPACE=chainN
// and runs it as `scaling_driver URDF`. It prints one JSON object:
//   {"kanegen_ns": ..., "mujoco_ns": ..., "max_udot_difference": ..., "mass": [...], "forcing": [...]}
// with the median time per call of a batch over a fixed set of states, and M
// (row-major) and f (tau = 0) at q_i = 0.3 sin(i), u_i = 0.5 cos(i), i = 1..N,
// which bench/scaling.py compares with SymPy's model (bench/sympy_chain.py).
//
// MuJoCo loads the URDF with fusestatic="true" and contacts disabled, as in
// bench_dynamics.cpp (the full mj_forward, as a simulator calls it). Before
// timing, both must compute the same udot at every state (relative 1e-6:
// MuJoCo's import of full inertia tensors is only accurate to about 1e-7, see
// tests/consistency/mujoco_reference.hpp); the driver exits 1 otherwise, so a
// wrong kernel is never timed.
#include <mujoco/mujoco.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include "mujoco_urdf.hpp"

#include KANEGEN_SCALING_HEADER

namespace {

namespace model = ::kanegen_models::KANEGEN_SCALING_NAMESPACE;
using S = model::System;
constexpr int kStates = 64;

[[noreturn]] void die(const std::string& msg) {
  std::fprintf(stderr, "scaling_driver: %s\n", msg.c_str());
  std::exit(1);
}

mjModel* load_mujoco(const std::string& path) {
  std::string error;
  mjModel* m = kanegen_bench::load_urdf(path, error);
  if (m == nullptr) die(error);
  m->opt.disableflags |= mjDSBL_CONTACT;
  return m;
}

/// Median nanoseconds per call of `call(k)` over batches of all states.
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

int main(int argc, char** argv) {
  if (argc != 2) die("usage: scaling_driver URDF");
  mjModel* m = load_mujoco(argv[1]);
  mjData* d = mj_makeData(m);
  if (m->nv != S::nu)
    die("MuJoCo has " + std::to_string(m->nv) + " dofs, the model " + std::to_string(S::nu));
  std::vector<int> qadr, dadr;
  for (int i = 0; i < S::nq; ++i) {
    const int j = mj_name2id(m, mjOBJ_JOINT, S::coordinate_names()[i]);
    if (j < 0) die(std::string("MuJoCo has no joint ") + S::coordinate_names()[i]);
    qadr.push_back(m->jnt_qposadr[j]);
    dadr.push_back(m->jnt_dofadr[j]);
  }
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> angle(-1.5, 1.5), rate(-2.0, 2.0);
  std::vector<double> q(kStates * S::nq), u(kStates * S::nu), udot(kStates * S::nu), tau(S::ntau, 0.0);
  for (double& x : q) x = angle(rng);
  for (double& x : u) x = rate(rng);
  S::Params p{};

  double worst = 0;
  for (int k = 0; k < kStates; ++k) {
    for (int i = 0; i < S::nq; ++i) d->qpos[qadr[i]] = q[k * S::nq + i];
    for (int i = 0; i < S::nu; ++i) d->qvel[dadr[i]] = u[k * S::nu + i];
    mj_forward(m, d);
    if (S::forward_dynamics(p, 0.0, &q[k * S::nq], &u[k * S::nu], tau.data(), &udot[k * S::nu]) != 0)
      die("forward_dynamics failed at state " + std::to_string(k));
    double scale = 1.0;
    for (int i = 0; i < S::nu; ++i) scale = std::max(scale, std::abs(d->qacc[dadr[i]]));
    for (int i = 0; i < S::nu; ++i)
      worst = std::max(worst, std::abs(udot[k * S::nu + i] - d->qacc[dadr[i]]) / scale);
  }
  if (!(worst < 1e-6)) die("kanegen and MuJoCo disagree on udot, relative " + std::to_string(worst));

  std::vector<double> sink(S::nu);
  const double kanegen_ns = median_ns([&](int k) {
    S::forward_dynamics(p, 0.0, &q[k * S::nq], &u[k * S::nu], tau.data(), sink.data());
    asm volatile("" : : "r"(sink.data()) : "memory");
  });
  const double mujoco_ns = median_ns([&](int k) {
    for (int i = 0; i < S::nq; ++i) d->qpos[qadr[i]] = q[k * S::nq + i];
    for (int i = 0; i < S::nu; ++i) d->qvel[dadr[i]] = u[k * S::nu + i];
    mj_forward(m, d);
  });
  std::vector<double> check_q(S::nq), check_u(S::nu), mass(S::nu * S::nu), forcing(S::nu);
  for (int i = 0; i < S::nq; ++i) check_q[i] = 0.3 * std::sin(i + 1.0);
  for (int i = 0; i < S::nu; ++i) check_u[i] = 0.5 * std::cos(i + 1.0);
  S::mass_matrix(p, check_q.data(), mass.data());
  S::forcing(p, 0.0, check_q.data(), check_u.data(), tau.data(), forcing.data());
  const auto list = [](const std::vector<double>& v) {
    std::string s = "[";
    char number[32];
    for (std::size_t i = 0; i < v.size(); ++i) {
      std::snprintf(number, sizeof number, "%.17g", v[i]);
      s += (i ? ", " : "") + std::string(number);
    }
    return s + "]";
  };
  std::printf(
      "{\"kanegen_ns\": %.1f, \"mujoco_ns\": %.1f, \"max_udot_difference\": %.3g, \"mass\": %s, "
      "\"forcing\": %s}\n",
      kanegen_ns, mujoco_ns, worst, list(mass).c_str(), list(forcing).c_str());
  mj_deleteData(d);
  mj_deleteModel(m);
  return 0;
}
