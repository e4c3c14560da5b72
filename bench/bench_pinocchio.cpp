// SPDX-License-Identifier: GPL-2.0-or-later
// bench_pinocchio: kanegen's generated kernels against Pinocchio in one
// process, on arm7 and spatial chains of 7, 20, 50 and 100 links (the
// Pinocchio model is built from kanegen's own parsed URDF, joints mapped by
// name; bench/pinocchio_peer.hpp):
//
//   forward_dynamics  vs  aba
//   inverse_dynamics  vs  rnea
//   mass_matrix       vs  crba (its upper triangle mirrored for the check)
//   linearize         vs  computeABADerivatives (ddq_dq, ddq_dv, Minv), for
//                         the models generated with --controller (arm7, chain7)
//
// First the values at 64 random states (fixed seed) must agree to 1e-9,
// relative to the largest entry of each result; the program exits 1
// otherwise. Then each pair is timed, alternating kanegen and Pinocchio run
// by run: per run, one call per state cycling through the 64 states, the
// thread's CPU time over about --run-ms milliseconds; the median of --reps
// runs per side. Output: a markdown table of ns per call and the ratio
// kanegen / Pinocchio (below 1: kanegen is faster).
//
// Usage: bench_pinocchio [--reps N] [--run-ms MS] [--check-only]
#include <time.h>

#include <algorithm>
#include <arm7.hpp>
#include <chain100.hpp>
#include <chain20.hpp>
#include <chain50.hpp>
#include <chain7.hpp>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "model/load.hpp"
#include "pinocchio_peer.hpp"

namespace {

constexpr int kStates = 64;  // a power of two: the index wraps with a mask
constexpr double kTolerance = 1e-9;

struct Options {
  int reps = 11;
  double run_ms = 20.0;
  bool check_only = false;
};

struct Row {
  std::string model, operation;
  double kanegen_ns = 0.0, pinocchio_ns = 0.0;
};

[[noreturn]] void die(const std::string& msg) {
  std::fprintf(stderr, "bench_pinocchio: %s\n", msg.c_str());
  std::exit(1);
}

double cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

// Largest |a - b| over the largest |b| of a block of n values.
double relative_error(const double* a, const double* b, int n) {
  double diff = 0.0, scale = 0.0;
  for (int i = 0; i < n; ++i) {
    diff = std::max(diff, std::abs(a[i] - b[i]));
    scale = std::max(scale, std::abs(b[i]));
  }
  return diff / std::max(scale, 1e-300);
}

// The states: q in [-3, 3], u, udot in [-2, 2], tau in [-5, 5] (kanegen order).
struct States {
  int n = 0;
  std::vector<double> q, u, a, tau;
  explicit States(int n_) : n(n_), q(kStates * n_), u(kStates * n_), a(kStates * n_), tau(kStates * n_) {
    std::mt19937_64 rng(20261205);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    for (int i = 0; i < kStates * n; ++i) {
      q[i] = -3.0 + 6.0 * unit(rng);
      u[i] = -2.0 + 4.0 * unit(rng);
      a[i] = -2.0 + 4.0 * unit(rng);
      tau[i] = -5.0 + 10.0 * unit(rng);
    }
  }
};

// One side's call on state k, timed: the median ns per call over the runs.
template <class F>
long calibrate(F&& call, double run_ms) {
  long calls = 1;
  for (;;) {
    const double t0 = cpu_seconds();
    for (long i = 0; i < calls; ++i) call(static_cast<int>(i & (kStates - 1)));
    const double dt = cpu_seconds() - t0;
    if (dt > 2e-3) return std::max(1L, static_cast<long>(static_cast<double>(calls) * run_ms * 1e-3 / dt));
    calls *= 2;
  }
}

template <class F>
double run_once(F&& call, long calls) {
  const double t0 = cpu_seconds();
  for (long i = 0; i < calls; ++i) call(static_cast<int>(i & (kStates - 1)));
  return (cpu_seconds() - t0) * 1e9 / static_cast<double>(calls);
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t m = v.size() / 2;
  return v.size() % 2 == 1 ? v[m] : 0.5 * (v[m - 1] + v[m]);
}

// The two sides alternate run by run, so that a disturbance hits both.
template <class K, class P>
Row time_pair(const std::string& model, const std::string& op, K&& kanegen, P&& pinocchio, const Options& o) {
  const long nk = calibrate(kanegen, o.run_ms), np = calibrate(pinocchio, o.run_ms);
  std::vector<double> tk, tp;
  for (int r = 0; r < o.reps; ++r) {
    tk.push_back(run_once(kanegen, nk));
    tp.push_back(run_once(pinocchio, np));
  }
  Row row{model, op, median(tk), median(tp)};
  std::fprintf(stderr, "  %-8s %-18s kanegen %10.1f ns  Pinocchio %10.1f ns  ratio %.3f\n", model.c_str(),
               op.c_str(), row.kanegen_ns, row.pinocchio_ns, row.kanegen_ns / row.pinocchio_ns);
  return row;
}

// The worst relative error per operation, checked against kTolerance.
struct Check {
  std::string model;
  double fd = 0.0, id = 0.0, mm = 0.0, lin = -1.0;
  void report() const {
    std::fprintf(stderr, "%s: max relative error vs Pinocchio: aba %.1e, rnea %.1e, crba %.1e", model.c_str(),
                 fd, id, mm);
    if (lin >= 0.0)
      std::fprintf(stderr, ", computeABADerivatives %.1e\n", lin);
    else
      std::fprintf(stderr, ", linearize not generated (no --controller)\n");
    if (std::max({fd, id, mm, lin}) > kTolerance) die(model + ": kanegen and Pinocchio disagree");
  }
};

template <class S>
void check_inputs() {
  if (S::ntau != S::nu || S::nq != S::nu) die(std::string(S::name) + ": expected NQ = NU = NTAU");
  for (int i = 0; i < S::nu; ++i)
    if (std::string(S::input_names()[i]) != std::string(S::coordinate_names()[i]) + "_tau")
      die(std::string(S::name) + ": input " + std::to_string(i) + " is not the torque of coordinate " +
          std::to_string(i));
}

// linearize's A (2n x 2n) and B (2n x n) against [0 I; ddq_dq ddq_dv] and
// [0; Minv]: the worst relative error over the blocks.
double compare_linearize(const double* A, const double* B, const double* ddq_dq, const double* ddq_dv,
                         const double* Minv, int n) {
  std::vector<double> ka(n * n), kb(n * n), kc(n * n), top(n * n), eye(n * n, 0.0);
  std::vector<double> kbt(n * n), kd(n * n);
  for (int i = 0; i < n; ++i) eye[i * n + i] = 1.0;
  double worst = 0.0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      top[i * n + j] = A[i * 2 * n + j];           // dqdot/dq
      kd[i * n + j] = A[i * 2 * n + n + j];        // dqdot/du
      ka[i * n + j] = A[(n + i) * 2 * n + j];      // dudot/dq
      kb[i * n + j] = A[(n + i) * 2 * n + n + j];  // dudot/du
      kbt[i * n + j] = B[i * n + j];               // dqdot/dtau
      kc[i * n + j] = B[(n + i) * n + j];          // dudot/dtau
    }
  for (int i = 0; i < n * n; ++i)
    worst = std::max({worst, std::abs(top[i]), std::abs(kbt[i]), std::abs(kd[i] - eye[i])});
  worst = std::max(worst, relative_error(ka.data(), ddq_dq, n * n));
  worst = std::max(worst, relative_error(kb.data(), ddq_dv, n * n));
  return std::max(worst, relative_error(kc.data(), Minv, n * n));
}

// The values at every state: forward and inverse dynamics, M and (with the
// controller kernels) linearize, against Pinocchio.
template <class S, bool kController>
Check check_model(const std::string& label, kanegen_bench::PinocchioPeer& pin, const States& st) {
  const int n = S::nu;
  const typename S::Params p{};
  std::vector<double> x(n), y(n), M(n * n), Mp(n * n), A(4 * n * n), B(2 * n * n), dq(n * n), dv(n * n),
      mi(n * n);
  Check c{label};
  for (int k = 0; k < kStates; ++k) {
    const double *q = &st.q[k * n], *u = &st.u[k * n], *a = &st.a[k * n], *tau = &st.tau[k * n];
    if (S::forward_dynamics(p, 0.0, q, u, tau, x.data()) != 0) die(label + ": singular M");
    pin.aba(q, u, tau, y.data());
    c.fd = std::max(c.fd, relative_error(x.data(), y.data(), n));
    S::inverse_dynamics(p, 0.0, q, u, a, x.data());
    pin.rnea(q, u, a, y.data());
    c.id = std::max(c.id, relative_error(x.data(), y.data(), n));
    S::mass_matrix(p, q, M.data());
    pin.crba(q, Mp.data());
    c.mm = std::max(c.mm, relative_error(M.data(), Mp.data(), n * n));
    if constexpr (kController) {
      if (S::linearize(p, 0.0, q, u, tau, A.data(), B.data()) != 0) die(label + ": singular M in linearize");
      pin.aba_derivatives(q, u, tau, dq.data(), dv.data(), mi.data());
      c.lin = std::max(c.lin, compare_linearize(A.data(), B.data(), dq.data(), dv.data(), mi.data(), n));
    }
  }
  return c;
}

template <class S, bool kController>
void time_model(const std::string& label, kanegen_bench::PinocchioPeer& pin, const States& st,
                const Options& o, std::vector<Row>& rows) {
  const int n = S::nu;
  const typename S::Params p{};
  std::vector<double> out(n), M(n * n), A(4 * n * n), B(2 * n * n);
  volatile double sink = 0.0;
  pin.store_states(kStates, st.q.data(), st.u.data(), st.a.data(), st.tau.data());
  auto pin_call = [&](auto member) { return [&pin, member](int k) { (pin.*member)(k); }; };
  rows.push_back(time_pair(
      label, "forward dynamics",
      [&](int k) {
        sink = S::forward_dynamics(p, 0.0, &st.q[k * n], &st.u[k * n], &st.tau[k * n], out.data());
      },
      pin_call(&kanegen_bench::PinocchioPeer::aba_state), o));
  rows.push_back(time_pair(
      label, "inverse dynamics",
      [&](int k) { S::inverse_dynamics(p, 0.0, &st.q[k * n], &st.u[k * n], &st.a[k * n], out.data()); },
      pin_call(&kanegen_bench::PinocchioPeer::rnea_state), o));
  rows.push_back(time_pair(
      label, "mass matrix", [&](int k) { S::mass_matrix(p, &st.q[k * n], M.data()); },
      pin_call(&kanegen_bench::PinocchioPeer::crba_state), o));
  if constexpr (kController) {
    rows.push_back(time_pair(
        label, "linearize",
        [&](int k) {
          sink = S::linearize(p, 0.0, &st.q[k * n], &st.u[k * n], &st.tau[k * n], A.data(), B.data());
        },
        pin_call(&kanegen_bench::PinocchioPeer::aba_derivatives_state), o));
  }
  sink = sink + out[0] + M[0] + A[0] + pin.sink();
}

template <class S, bool kController>
void run_model(const char* urdf, const Options& o, std::vector<Row>& rows) {
  const std::string label = S::name;
  check_inputs<S>();
  std::vector<std::string> coordinates(S::coordinate_names(), S::coordinate_names() + S::nq);
  try {
    kanegen_bench::PinocchioPeer pin(kanegen::model::load_model(urdf), coordinates);
    const States st(S::nu);
    check_model<S, kController>(label, pin, st).report();
    if (!o.check_only) time_model<S, kController>(label, pin, st, o, rows);
  } catch (const std::exception& e) {
    die(label + ": " + e.what());
  }
}

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--check-only") {
      o.check_only = true;
    } else if (arg == "--reps" && i + 1 < argc) {
      o.reps = std::max(1, std::atoi(argv[++i]));
    } else if (arg == "--run-ms" && i + 1 < argc) {
      o.run_ms = std::max(0.1, std::atof(argv[++i]));
    } else {
      die("usage: bench_pinocchio [--reps N] [--run-ms MS] [--check-only]");
    }
  }
  return o;
}

}  // namespace

int main(int argc, char** argv) {
  const Options o = parse(argc, argv);
  std::vector<Row> rows;
  run_model<kanegen_models::arm7::System, true>(KANEGEN_ARM7_URDF, o, rows);
  run_model<kanegen_models::chain7::System, true>(KANEGEN_CHAIN7_URDF, o, rows);
  run_model<kanegen_models::chain20::System, false>(KANEGEN_CHAIN20_URDF, o, rows);
  run_model<kanegen_models::chain50::System, false>(KANEGEN_CHAIN50_URDF, o, rows);
  run_model<kanegen_models::chain100::System, false>(KANEGEN_CHAIN100_URDF, o, rows);
  if (o.check_only) return 0;
  std::printf("| model | operation | kanegen [ns] | Pinocchio [ns] | kanegen / Pinocchio |\n");
  std::printf("| --- | --- | ---: | ---: | ---: |\n");
  for (const Row& r : rows)
    std::printf("| %s | %s | %.1f | %.1f | %.3f |\n", r.model.c_str(), r.operation.c_str(), r.kanegen_ns,
                r.pinocchio_ns, r.kanegen_ns / r.pinocchio_ns);
  return 0;
}
