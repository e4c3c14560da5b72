// SPDX-License-Identifier: GPL-2.0-or-later
// The spin-up beam (10 elements, Ws = 6 rad/s, 20 s) by generalized-alpha
// at a fixed step against DOPRI5 (rtol 1e-8, as tests/flexible): wall time,
// real-time factor (simulated time / wall time), Newton statistics and the
// tip deflection's minimum. Run by bench/genalpha.sh; see docs/benchmarks.md.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <string>
#include <vector>

#include "kanegen/runtime/genalpha.hpp"
#include "kanegen/runtime/integrators.hpp"
#include "spin_up_beam.hpp"

using namespace kanegen::runtime;
using Clock = std::chrono::steady_clock;

namespace {

/// CPU time of this thread (s): on a loaded machine the wall time also
/// counts the waits for a core, which the real-time factor should not.
double cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

constexpr double kEnd = 20.0;
constexpr int kTip = 1;  // output tip.y

struct Result {
  bool ok = false;
  std::string why;
  double wall = 0.0;                     ///< seconds, the integration alone
  double cpu = 0.0;                      ///< its CPU time
  double tip_min = 0.0, tip_time = 0.0;  ///< minimum of tip.y and its time
  double tip_end = 0.0;                  ///< tip.y at t = 20 s
  ImplicitStats stats;
  long dopri_steps = 0, dopri_rejected = 0;
};

void track_tip(const Model& model, double t, const double* q, const double* u, Result* r) {
  double y[4];
  model.outputs(t, q, u, y);
  if (y[kTip] < r->tip_min) {
    r->tip_min = y[kTip];
    r->tip_time = t;
  }
  r->tip_end = y[kTip];
}

Result run_genalpha(const Model& model, double h, double rho_inf, bool reuse) {
  const int n = model.info().nu;
  std::vector<double> q(n), u(n);
  model.initial_state(q.data(), u.data());
  GenAlphaOptions o;
  o.h = h;
  o.rho_inf = rho_inf;
  o.reuse_jacobian = reuse;
  GenAlpha ga(model, o);
  Result r;
  const double tau = 0.0;
  const long steps = std::lround(kEnd / h);
  const auto start = Clock::now();
  const double cpu0 = cpu_seconds();
  r.ok = ga.start(0.0, q.data(), u.data(), &tau, &r.why);
  for (long i = 0; i < steps && r.ok; ++i) {
    r.ok = ga.step(&tau, &r.why);
    track_tip(model, ga.t(), ga.q(), ga.u(), &r);  // as a real-time loop would output
  }
  r.wall = std::chrono::duration<double>(Clock::now() - start).count();
  r.cpu = cpu_seconds() - cpu0;
  r.stats = ga.stats();
  return r;
}

Result run_dopri(const Model& model) {
  const int n = model.info().nu;
  std::vector<double> x(2 * static_cast<size_t>(n));
  model.initial_state(x.data(), x.data() + n);
  IntegrationOptions opt;
  opt.t_end = kEnd;
  opt.dt = 1e-3;  // the same output grid as genalpha's steps
  opt.rtol = 1e-8;
  opt.atol = 1e-10;
  opt.max_steps = 20000000;
  const double tau = 0.0;
  const Rhs rhs = [&](double t, const double* s, double* sd) {
    std::copy(s + n, s + 2 * n, sd);
    return model.forward_dynamics(t, s, s + n, &tau, sd + n) == 0;
  };
  Result r;
  const auto start = Clock::now();
  const double cpu0 = cpu_seconds();
  const IntegrationResult ir =
      integrate(Method::kDopri5, rhs, 0.0, x.data(), 2 * n, opt, [&](double t, const double* s) {
        track_tip(model, t, s, s + n, &r);
        return true;
      });
  r.wall = std::chrono::duration<double>(Clock::now() - start).count();
  r.cpu = cpu_seconds() - cpu0;
  r.ok = ir.ok();
  r.why = ir.message;
  r.dopri_steps = ir.stats.accepted;
  r.dopri_rejected = ir.stats.rejected;
  return r;
}

/// The run of least CPU time among `reps` (the others differ only by machine noise).
template <class F>
Result best_of(int reps, F run) {
  Result best = run();
  for (int i = 1; i < reps && best.ok; ++i) {
    const Result r = run();
    if (r.cpu < best.cpu) best = r;
  }
  return best;
}

void print(const char* name, const Result& r, const Result& reference) {
  if (!r.ok) {
    std::printf("%-32s FAILED: %s\n", name, r.why.c_str());
    return;
  }
  std::printf("%-32s %8.3f %8.3f %6.0f %6.0f %10.6f %6.3f %9.2e %9.2e", name, r.wall, r.cpu, kEnd / r.wall,
              kEnd / r.cpu, r.tip_min, r.tip_time,
              std::abs(r.tip_min - reference.tip_min) / std::abs(reference.tip_min),
              std::abs(r.tip_end - reference.tip_end));
  if (r.dopri_steps > 0)
    std::printf("   %ld steps, %ld rejected\n", r.dopri_steps, r.dopri_rejected);
  else
    std::printf("   %ld steps, %ld Newton, %ld Jacobians, %ld LU\n", r.stats.steps, r.stats.newton_iterations,
                r.stats.jacobian_evaluations, r.stats.factorizations);
}

}  // namespace

int main(int argc, char** argv) {
  const int reps = argc > 1 ? std::atoi(argv[1]) : 3;
  Model model = make_model<kanegen_models::spin_up_beam::System>();
  model.set_parameter("Ws", 6.0);
  std::printf(
      "spin_up_beam (10 elements, %d coordinates), Ws = 6 rad/s, Ts = 15 s, %g s simulated; best of %d\n",
      model.info().nq, kEnd, reps);
  std::printf("%-32s %8s %8s %6s %6s %10s %6s %9s %9s\n", "method", "wall [s]", "CPU [s]", "RTF", "RTFcpu",
              "tip min", "at [s]", "rel diff", "|d tip20|");
  const Result dopri = best_of(std::min(reps, 1), [&] { return run_dopri(model); });
  print("DOPRI5 rtol 1e-8 (reference)", dopri, dopri);
  print("genalpha h = 1 ms, rho 0.8", best_of(reps, [&] { return run_genalpha(model, 1e-3, 0.8, true); }),
        dopri);
  print("genalpha h = 1 ms, rho 0.8, no reuse",
        best_of(reps, [&] { return run_genalpha(model, 1e-3, 0.8, false); }), dopri);
  print("genalpha h = 1 ms, rho 1", best_of(reps, [&] { return run_genalpha(model, 1e-3, 1.0, true); }),
        dopri);
  print("genalpha h = 0.5 ms, rho 0.8", best_of(reps, [&] { return run_genalpha(model, 5e-4, 0.8, true); }),
        dopri);
  print("genalpha h = 2 ms, rho 0.8", best_of(reps, [&] { return run_genalpha(model, 2e-3, 0.8, true); }),
        dopri);
  return 0;
}
