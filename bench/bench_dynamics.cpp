// SPDX-License-Identifier: GPL-2.0-or-later
// bench_dynamics: the generated kernels of arm7 and chain20 against MuJoCo,
// in one run, on the same fixed set of states (cycled, one state per call).
//
// kanegen:  mass_matrix (dense M), forcing (f, tau = 0), forward_dynamics
//           (udot = M^-1 f, LDL^T inside).
// MuJoCo (the same URDF, fusestatic on, contacts disabled):
//   mj_forward        the full pipeline as a simulator calls it: kinematics,
//                     com, crb (M) and its factorisation, collision (nothing:
//                     no geoms), constraint set-up (joint limits: none active
//                     at the states used), transmission, velocity stage
//                     (com velocities, passive forces, RNE bias), actuation,
//                     qacc_smooth, constraint solver (no constraints), sensors
//                     (none) — contacts disabled (mjDSBL_CONTACT);
//   mj_forward_lean   mj_forward with every optional stage disabled as well
//                     (constraint, passive, actuation, sensor);
//   smooth            only what forward_dynamics computes: mj_kinematics,
//                     mj_comPos, mj_crb, mj_factorM, mj_comVel, mj_rne (bias),
//                     mj_solveM (qacc = -M^-1 bias);
//   mass_matrix       mj_kinematics, mj_comPos, mj_crb (qM, MuJoCo's sparse
//                     lower triangle; for a chain that is all of it);
//   bias              mj_kinematics, mj_comPos, mj_comVel, mj_rne (qfrc_bias).
// Inverse dynamics (tau for given q, u, udot; udot in [-2, 2] per state):
//   kanegen/inverse_dynamics      the recursive kernel (M never formed);
//   kanegen/M_udot_minus_f        the same from the existing kernels:
//                                 mass_matrix, forcing (tau = 0), M udot - f;
//   mujoco/mj_inverse             MuJoCo's inverse pipeline (qfrc_inverse),
//                                 contacts disabled;
//   mujoco/rne                    only what inverse_dynamics computes:
//                                 mj_kinematics, mj_comPos, mj_comVel,
//                                 mj_rne with accelerations.
// Batched (arm7 only; kanegen generate --batch W, W = 4 and 8):
//   kanegen/forward_dynamics_batchW, kanegen/inverse_dynamics_batchW
//                                 one call evaluates W states (structure of
//                                 arrays); the time is per call, bench/run.sh
//                                 divides it by W for the time per state.
// Before timing, each model checks that the kernels and the MuJoCo variants
// compute the same udot and tau at the benchmark states; it aborts otherwise.
#include <benchmark/benchmark.h>
#include <mujoco/mujoco.h>

#include <algorithm>
#include <arm7.hpp>
#include <arm7_batch4_batch4.hpp>
#include <arm7_batch8_batch8.hpp>
#include <chain20.hpp>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include "mujoco_urdf.hpp"

namespace {

constexpr int kStates = 64;  // a power of two: index wraps with a mask

[[noreturn]] void die(const std::string& msg) {
  std::fprintf(stderr, "bench_dynamics: %s\n", msg.c_str());
  std::exit(1);
}

mjModel* load_mujoco(const std::string& path) {
  std::string error;
  mjModel* m = kanegen_bench::load_urdf(path, error);
  if (m == nullptr) die(error);
  return m;
}

// One model: kanegen System S and its MuJoCo counterpart, the states, the
// index maps and the output buffers.
template <class S>
struct Fixture {
  std::string label;
  mjModel* m = nullptr;
  mjData* d = nullptr;
  typename S::Params p{};
  std::vector<int> qadr, dadr;     // MuJoCo qpos / dof address of coordinate i
  std::vector<double> q, u, a;     // kStates x nu, kanegen order (a: the udot given to inverse dynamics)
  std::vector<double> mq, mu, ma;  // kStates x nv, MuJoCo qpos / qvel / qacc layout
  std::vector<double> M, f, udot, tau, tmp;

  Fixture(std::string label_, const std::string& urdf) : label(std::move(label_)) {
    m = load_mujoco(urdf);
    d = mj_makeData(m);
    if (m->nv != S::nu || m->nq != S::nq) die(label + ": MuJoCo and kanegen sizes differ");
    for (int i = 0; i < S::nq; ++i) {
      const int j = mj_name2id(m, mjOBJ_JOINT, S::coordinate_names()[i]);
      if (j < 0) die(label + ": MuJoCo has no joint " + S::coordinate_names()[i]);
      qadr.push_back(m->jnt_qposadr[j]);
      dadr.push_back(m->jnt_dofadr[j]);
    }
    // fixed seed; q inside the joint range (limits inactive), u in [-2, 2]
    std::mt19937_64 rng(12345);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const int n = S::nu;
    q.resize(kStates * n);
    u.resize(kStates * n);
    a.resize(kStates * n);
    mq.assign(kStates * m->nq, 0.0);
    mu.assign(kStates * m->nv, 0.0);
    ma.assign(kStates * m->nv, 0.0);
    for (int k = 0; k < kStates; ++k) {
      for (int i = 0; i < n; ++i) {
        const int j = mj_name2id(m, mjOBJ_JOINT, S::coordinate_names()[i]);
        double lo = -3.0, hi = 3.0;
        if (m->jnt_limited[j]) {
          lo = std::max(lo, 0.9 * m->jnt_range[2 * j]);
          hi = std::min(hi, 0.9 * m->jnt_range[2 * j + 1]);
        }
        q[k * n + i] = lo + (hi - lo) * unit(rng);
        u[k * n + i] = -2.0 + 4.0 * unit(rng);
        mq[k * m->nq + qadr[i]] = q[k * n + i];
        mu[k * m->nv + dadr[i]] = u[k * n + i];
      }
      for (int i = 0; i < n; ++i) {  // after q and u: their draws stay those of the forward benchmarks
        a[k * n + i] = -2.0 + 4.0 * unit(rng);
        ma[k * m->nv + dadr[i]] = a[k * n + i];
      }
    }
    M.assign(n * n, 0.0);
    f.assign(n, 0.0);
    udot.assign(n, 0.0);
    tau.assign(std::max(S::ntau, 1), 0.0);
    tmp.assign(m->nv, 0.0);
    set_flags(false);
    verify();
    verify_inverse();
  }
  ~Fixture() {
    mj_deleteData(d);
    mj_deleteModel(m);
  }
  Fixture(const Fixture&) = delete;
  Fixture& operator=(const Fixture&) = delete;

  void set_flags(bool lean) {
    m->opt.disableflags = mjDSBL_CONTACT;
    if (lean) m->opt.disableflags |= mjDSBL_CONSTRAINT | mjDSBL_PASSIVE | mjDSBL_ACTUATION | mjDSBL_SENSOR;
  }
  void load_state(int k) {
    mju_copy(d->qpos, &mq[k * m->nq], m->nq);
    mju_copy(d->qvel, &mu[k * m->nv], m->nv);
  }
  void load_acceleration(int k) { mju_copy(d->qacc, &ma[k * m->nv], m->nv); }
  void rne() {
    mj_kinematics(m, d);
    mj_comPos(m, d);
    mj_comVel(m, d);
    mj_rne(m, d, 1, tmp.data());
  }
  // M udot - f from the existing kernels.
  void m_udot_minus_f(int k) {
    const int n = S::nu;
    S::mass_matrix(p, &q[k * n], M.data());
    S::forcing(p, 0.0, &q[k * n], &u[k * n], tau.data(), f.data());
    for (int i = 0; i < n; ++i) {
      double s = -f[i];
      for (int j = 0; j < n; ++j) s += M[i * n + j] * a[k * n + j];
      udot[i] = s;  // the buffer holds the efforts here
    }
  }

  // The inverse variants agree: inverse_dynamics, M udot - f, mj_inverse's
  // qfrc_inverse and mj_rne with accelerations.
  void verify_inverse() {
    const int n = S::nu;
    std::vector<double> effort(n);
    double worst = 0.0;
    for (int k = 0; k < kStates; ++k) {
      S::inverse_dynamics(p, 0.0, &q[k * n], &u[k * n], &a[k * n], effort.data());
      m_udot_minus_f(k);
      load_state(k);
      load_acceleration(k);
      mj_inverse(m, d);
      rne();
      double scale = 1.0;
      for (int i = 0; i < n; ++i) scale = std::max(scale, std::abs(d->qfrc_inverse[dadr[i]]));
      for (int i = 0; i < n; ++i) {
        const double ref = d->qfrc_inverse[dadr[i]];
        worst = std::max({worst, std::abs(effort[i] - ref) / scale, std::abs(udot[i] - ref) / scale,
                          std::abs(tmp[dadr[i]] - ref) / scale});
      }
    }
    if (worst > 1e-6)
      die(label + ": kanegen and MuJoCo inverse dynamics disagree, max rel. error " + std::to_string(worst));
    std::fprintf(stderr, "%s: kanegen vs MuJoCo inverse dynamics max rel. error %.1e\n", label.c_str(),
                 worst);
  }
  void smooth() {
    mj_kinematics(m, d);
    mj_comPos(m, d);
    mj_crb(m, d);
    mj_factorM(m, d);
    mj_comVel(m, d);
    mj_rne(m, d, 0, d->qfrc_bias);
    for (int i = 0; i < m->nv; ++i) tmp[i] = -d->qfrc_bias[i];
    mj_solveM(m, d, d->qacc, tmp.data(), 1);
  }

  // The variants compute the same thing: udot from kanegen, mj_forward's
  // qacc_smooth and qacc, and the smooth pipeline's qacc agree.
  void verify() {
    const int n = S::nu;
    double worst = 0.0;
    for (int k = 0; k < kStates; ++k) {
      if (S::forward_dynamics(p, 0.0, &q[k * n], &u[k * n], tau.data(), udot.data()) != 0) {
        die(label + ": forward_dynamics failed");
      }
      load_state(k);
      mj_forward(m, d);
      std::vector<double> ref(d->qacc_smooth, d->qacc_smooth + m->nv), qacc(d->qacc, d->qacc + m->nv);
      smooth();
      double scale = 1.0;
      for (int i = 0; i < n; ++i) scale = std::max(scale, std::abs(ref[dadr[i]]));
      for (int i = 0; i < n; ++i) {
        worst = std::max(worst, std::abs(udot[i] - ref[dadr[i]]) / scale);
        worst = std::max(worst, std::abs(qacc[dadr[i]] - ref[dadr[i]]) / scale);
        worst = std::max(worst, std::abs(d->qacc[dadr[i]] - ref[dadr[i]]) / scale);
      }
    }
    // 1e-6: MuJoCo's import of full inertia tensors is only accurate to ~1e-7
    // (see tests/consistency/mujoco_reference.hpp); the tests check 1e-9.
    if (worst > 1e-6)
      die(label + ": kanegen and MuJoCo disagree, max rel. udot error " + std::to_string(worst));
    std::fprintf(stderr, "%s: nv = %d, MuJoCo bodies = %d, kanegen vs MuJoCo udot max rel. error %.1e\n",
                 label.c_str(), m->nv, m->nbody, worst);
  }
};

template <class S>
void register_model(Fixture<S>* fx) {
  const int n = S::nu;
  const std::string l = fx->label + "/";
  benchmark::RegisterBenchmark((l + "kanegen/mass_matrix").c_str(), [fx, n](benchmark::State& st) {
    int k = 0;
    for (auto _ : st) {
      S::mass_matrix(fx->p, &fx->q[k * n], fx->M.data());
      benchmark::DoNotOptimize(fx->M.data());
      benchmark::ClobberMemory();
      k = (k + 1) & (kStates - 1);
    }
  });
  benchmark::RegisterBenchmark((l + "kanegen/forcing").c_str(), [fx, n](benchmark::State& st) {
    int k = 0;
    for (auto _ : st) {
      S::forcing(fx->p, 0.0, &fx->q[k * n], &fx->u[k * n], fx->tau.data(), fx->f.data());
      benchmark::DoNotOptimize(fx->f.data());
      benchmark::ClobberMemory();
      k = (k + 1) & (kStates - 1);
    }
  });
  benchmark::RegisterBenchmark((l + "kanegen/forward_dynamics").c_str(), [fx, n](benchmark::State& st) {
    int k = 0;
    for (auto _ : st) {
      const int rc =
          S::forward_dynamics(fx->p, 0.0, &fx->q[k * n], &fx->u[k * n], fx->tau.data(), fx->udot.data());
      benchmark::DoNotOptimize(rc);
      benchmark::DoNotOptimize(fx->udot.data());
      benchmark::ClobberMemory();
      k = (k + 1) & (kStates - 1);
    }
  });
  for (const bool lean : {false, true}) {
    const std::string name = l + (lean ? "mujoco/mj_forward_lean" : "mujoco/mj_forward");
    benchmark::RegisterBenchmark(name.c_str(), [fx, lean](benchmark::State& st) {
      fx->set_flags(lean);
      int k = 0;
      for (auto _ : st) {
        fx->load_state(k);
        mj_forward(fx->m, fx->d);
        benchmark::DoNotOptimize(fx->d->qacc);
        benchmark::ClobberMemory();
        k = (k + 1) & (kStates - 1);
      }
      fx->set_flags(false);
    });
  }
  benchmark::RegisterBenchmark((l + "mujoco/smooth").c_str(), [fx](benchmark::State& st) {
    int k = 0;
    for (auto _ : st) {
      fx->load_state(k);
      fx->smooth();
      benchmark::DoNotOptimize(fx->d->qacc);
      benchmark::ClobberMemory();
      k = (k + 1) & (kStates - 1);
    }
  });
  benchmark::RegisterBenchmark((l + "mujoco/mass_matrix").c_str(), [fx](benchmark::State& st) {
    int k = 0;
    for (auto _ : st) {
      fx->load_state(k);
      mj_kinematics(fx->m, fx->d);
      mj_comPos(fx->m, fx->d);
      mj_crb(fx->m, fx->d);
      benchmark::DoNotOptimize(fx->d->qM);
      benchmark::ClobberMemory();
      k = (k + 1) & (kStates - 1);
    }
  });
  benchmark::RegisterBenchmark((l + "kanegen/inverse_dynamics").c_str(), [fx, n](benchmark::State& st) {
    int k = 0;
    for (auto _ : st) {
      S::inverse_dynamics(fx->p, 0.0, &fx->q[k * n], &fx->u[k * n], &fx->a[k * n], fx->udot.data());
      benchmark::DoNotOptimize(fx->udot.data());
      benchmark::ClobberMemory();
      k = (k + 1) & (kStates - 1);
    }
  });
  benchmark::RegisterBenchmark((l + "kanegen/M_udot_minus_f").c_str(), [fx](benchmark::State& st) {
    int k = 0;
    for (auto _ : st) {
      fx->m_udot_minus_f(k);
      benchmark::DoNotOptimize(fx->udot.data());
      benchmark::ClobberMemory();
      k = (k + 1) & (kStates - 1);
    }
  });
  benchmark::RegisterBenchmark((l + "mujoco/mj_inverse").c_str(), [fx](benchmark::State& st) {
    int k = 0;
    for (auto _ : st) {
      fx->load_state(k);
      fx->load_acceleration(k);
      mj_inverse(fx->m, fx->d);
      benchmark::DoNotOptimize(fx->d->qfrc_inverse);
      benchmark::ClobberMemory();
      k = (k + 1) & (kStates - 1);
    }
  });
  benchmark::RegisterBenchmark((l + "mujoco/rne").c_str(), [fx](benchmark::State& st) {
    int k = 0;
    for (auto _ : st) {
      fx->load_state(k);
      fx->load_acceleration(k);
      fx->rne();
      benchmark::DoNotOptimize(fx->tmp.data());
      benchmark::ClobberMemory();
      k = (k + 1) & (kStates - 1);
    }
  });
  benchmark::RegisterBenchmark((l + "mujoco/bias").c_str(), [fx](benchmark::State& st) {
    int k = 0;
    for (auto _ : st) {
      fx->load_state(k);
      mj_kinematics(fx->m, fx->d);
      mj_comPos(fx->m, fx->d);
      mj_comVel(fx->m, fx->d);
      mj_rne(fx->m, fx->d, 0, fx->d->qfrc_bias);
      benchmark::DoNotOptimize(fx->d->qfrc_bias);
      benchmark::ClobberMemory();
      k = (k + 1) & (kStates - 1);
    }
  });
}

// The batched kernels of arm7 (the same model, renamed arm7_batch<W>).
struct Arm7Batch4 {
  using Params = kanegen_models::arm7_batch4::Params;
  static constexpr int lanes = 4;
  static int forward(const Params& p, const double* t, const double* q, const double* u, const double* tau,
                     double* udot, int* status) {
    return kanegen_models::arm7_batch4::forward_dynamics_batch4(p, t, q, u, tau, udot, status);
  }
  static void inverse(const Params& p, const double* t, const double* q, const double* u, const double* a,
                      double* tau) {
    kanegen_models::arm7_batch4::inverse_dynamics_batch4(p, t, q, u, a, tau);
  }
};
struct Arm7Batch8 {
  using Params = kanegen_models::arm7_batch8::Params;
  static constexpr int lanes = 8;
  static int forward(const Params& p, const double* t, const double* q, const double* u, const double* tau,
                     double* udot, int* status) {
    return kanegen_models::arm7_batch8::forward_dynamics_batch8(p, t, q, u, tau, udot, status);
  }
  static void inverse(const Params& p, const double* t, const double* q, const double* u, const double* a,
                      double* tau) {
    kanegen_models::arm7_batch8::inverse_dynamics_batch8(p, t, q, u, a, tau);
  }
};

// The fixture's states as kStates / W batches of W lanes, entry i of lane l
// of batch b at [(b * n + i) * W + l]; checked against the scalar kernels.
template <class B, class S>
struct Batched {
  static constexpr int W = B::lanes, batches = kStates / B::lanes;
  typename B::Params p{};
  std::vector<double> t, q, u, a, tau, out;
  std::vector<int> status;

  explicit Batched(Fixture<S>& fx) : t(W, 0.0), tau(std::max(S::ntau, 1) * W, 0.0), status(W, 0) {
    const int n = S::nu;
    for (const auto& [from, to] :
         {std::make_pair(&fx.q, &q), std::make_pair(&fx.u, &u), std::make_pair(&fx.a, &a)}) {
      to->assign(from->size(), 0.0);
      for (int k = 0; k < kStates; ++k)
        for (int i = 0; i < n; ++i) (*to)[((k / W) * n + i) * W + k % W] = (*from)[k * n + i];
    }
    out.assign(n * W, 0.0);
    verify(fx);
  }
  const double* at(const std::vector<double>& v, int b) const { return &v[b * S::nu * W]; }
  int forward(int b) {
    return B::forward(p, t.data(), at(q, b), at(u, b), tau.data(), out.data(), status.data());
  }
  void inverse(int b) { B::inverse(p, t.data(), at(q, b), at(u, b), at(a, b), out.data()); }

  // Each lane against the scalar kernel: equal but for the compiler's
  // contractions (FMA with -march=native), which may differ between the two.
  void verify(Fixture<S>& fx) {
    const int n = S::nu;
    double worst = 0.0;
    std::vector<double> scalar(n);
    for (int pass = 0; pass < 2; ++pass)
      for (int b = 0; b < batches; ++b) {
        if (pass == 0 && forward(b) != 0) die(fx.label + ": forward_dynamics_batch failed");
        if (pass == 1) inverse(b);
        for (int l = 0; l < W; ++l) {
          const int k = b * W + l;
          if (pass == 0)
            S::forward_dynamics(fx.p, 0.0, &fx.q[k * n], &fx.u[k * n], fx.tau.data(), scalar.data());
          else
            S::inverse_dynamics(fx.p, 0.0, &fx.q[k * n], &fx.u[k * n], &fx.a[k * n], scalar.data());
          for (int i = 0; i < n; ++i)
            worst =
                std::max(worst, std::abs(out[i * W + l] - scalar[i]) / std::max(std::abs(scalar[i]), 1e-300));
        }
      }
    if (worst > 1e-9)
      die(fx.label + ": batched and scalar kernels disagree, max rel. error " + std::to_string(worst));
    std::fprintf(stderr, "%s: batched (%d lanes) vs scalar kernels max rel. error %.1e\n", fx.label.c_str(),
                 W, worst);
  }
};

template <class B, class S>
void register_batched(Batched<B, S>* bx, const std::string& label) {
  const std::string w = std::to_string(B::lanes);
  benchmark::RegisterBenchmark((label + "/kanegen/forward_dynamics_batch" + w).c_str(),
                               [bx](benchmark::State& st) {
                                 int b = 0;
                                 for (auto _ : st) {
                                   const int rc = bx->forward(b);
                                   benchmark::DoNotOptimize(rc);
                                   benchmark::DoNotOptimize(bx->out.data());
                                   benchmark::ClobberMemory();
                                   b = (b + 1) % Batched<B, S>::batches;
                                 }
                               });
  benchmark::RegisterBenchmark((label + "/kanegen/inverse_dynamics_batch" + w).c_str(),
                               [bx](benchmark::State& st) {
                                 int b = 0;
                                 for (auto _ : st) {
                                   bx->inverse(b);
                                   benchmark::DoNotOptimize(bx->out.data());
                                   benchmark::ClobberMemory();
                                   b = (b + 1) % Batched<B, S>::batches;
                                 }
                               });
}

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::AddCustomContext("mujoco", mj_versionString());
  Fixture<kanegen_models::arm7::System> arm7("arm7", KANEGEN_ARM7_URDF);
  Fixture<kanegen_models::chain20::System> chain20("chain20", KANEGEN_CHAIN20_URDF);
  Batched<Arm7Batch4, kanegen_models::arm7::System> arm7_batch4(arm7);
  Batched<Arm7Batch8, kanegen_models::arm7::System> arm7_batch8(arm7);
  register_model(&arm7);
  register_batched(&arm7_batch4, "arm7");
  register_batched(&arm7_batch8, "arm7");
  register_model(&chain20);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
