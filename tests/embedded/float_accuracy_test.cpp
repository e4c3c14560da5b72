// SPDX-License-Identifier: GPL-2.0-or-later
// The float kernels (kanegen generate --precision float) against the double
// ones of the same model, on every shipped rigid model (open trees and
// closed loops): both evaluated at the same float-representable states, so
// that the difference is the float kernels' rounding alone. The largest
// difference over the samples relative to the largest entry over the
// samples (an entry near zero, where terms cancel, has no meaningful
// relative error of its own); for the outputs, whose entries have different
// units, per output. Printed for docs/embedded.md.
//
// Which states: M, f, the loop residuals Phi, their Jacobian C and the bias
// gamma are defined at any q and u, so they are compared at random states.
// The dynamics of a model with loops (udot and the loop forces lambda, and
// the outputs, which hold lambda) only mean something where the loops are
// closed, and C M^-1 C^T is singular at some random q; they are compared
// along the model's own motion: from its initial state, a short RK4 run of
// the double kernels (|Phi| stays below 1e-6 m, checked), each sample
// rounded to float.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "andrews_squeezer.hpp"
#include "andrews_squeezer_float.hpp"
#include "arm7.hpp"
#include "arm7_float.hpp"
#include "chain20.hpp"
#include "chain20_float.hpp"
#include "double_pendulum.hpp"
#include "double_pendulum_float.hpp"
#include "four_bar.hpp"
#include "four_bar_float.hpp"
#include "kanegen/runtime/rk4.hpp"
#include "nfourbar2.hpp"
#include "nfourbar2_float.hpp"
#include "nfourbar40.hpp"
#include "nfourbar40_float.hpp"
#include "simple_pendulum.hpp"
#include "simple_pendulum_float.hpp"
#include "slider_crank.hpp"
#include "slider_crank_float.hpp"

namespace {

/// The kernels of one model in one precision, with the default parameters.
template <typename Real>
struct Kernels {
  void (*initial_state)(Real* q, Real* u);
  void (*mass_matrix)(const Real* q, Real* M);
  void (*forcing)(Real t, const Real* q, const Real* u, const Real* tau, Real* f);
  int (*forward_dynamics)(Real t, const Real* q, const Real* u, const Real* tau, Real* udot);
  void (*coordinate_rates)(const Real* q, const Real* u, Real* qdot);
  void (*outputs)(Real t, const Real* q, const Real* u, Real* y);
  // Models with loops only (nullptr for an open tree).
  void (*constraints)(const Real* q, Real* phi);
  void (*constraint_jacobian)(const Real* q, Real* C);
  void (*constraint_bias)(const Real* q, const Real* u, Real* gamma);
  int (*constrained_dynamics)(Real t, const Real* q, const Real* u, const Real* tau, Real* udot,
                              Real* lambda);
};

#define KANEGEN_KERNELS(NS, Real)                                                         \
  [](Real* q, Real* u) { NS::initial_state({}, q, u); },                                  \
      [](const Real* q, Real* M) { NS::mass_matrix({}, q, M); },                          \
      [](Real t, const Real* q, const Real* u, const Real* tau, Real* f) {                \
        NS::forcing({}, t, q, u, tau, f);                                                 \
      },                                                                                  \
      [](Real t, const Real* q, const Real* u, const Real* tau, Real* a) {                \
        return NS::forward_dynamics({}, t, q, u, tau, a);                                 \
      },                                                                                  \
      [](const Real* q, const Real* u, Real* qdot) { NS::coordinate_rates(q, u, qdot); }, \
      [](Real t, const Real* q, const Real* u, Real* y) { NS::outputs({}, t, q, u, y); }

#define KANEGEN_LOOP_KERNELS(NS, Real)                                                         \
  [](const Real* q, Real* phi) { NS::constraints({}, q, phi); },                               \
      [](const Real* q, Real* C) { NS::constraint_jacobian({}, q, C); },                       \
      [](const Real* q, const Real* u, Real* gamma) { NS::constraint_bias({}, q, u, gamma); }, \
      [](Real t, const Real* q, const Real* u, const Real* tau, Real* udot, Real* lambda) {    \
        return NS::constrained_dynamics({}, t, q, u, tau, udot, lambda);                       \
      }

/// One model in both precisions; for one with loops, how long its motion is
/// followed (RK4 steps of dt, a sample every `every` steps).
struct Model {
  const char* name;
  int nq, nu, ntau, ny, nc;
  Kernels<double> d;
  Kernels<float> f;
  double dt = 0.0;
  int steps = 0, every = 1;
};

#define KANEGEN_TREE(NAME)                                                                      \
  Model {                                                                                       \
#NAME, kanegen_models::NAME::NQ, kanegen_models::NAME::NU, kanegen_models::NAME::NTAU,      \
        kanegen_models::NAME::NY, 0,                                                            \
        {KANEGEN_KERNELS(kanegen_models::NAME, double), nullptr, nullptr, nullptr, nullptr }, { \
      KANEGEN_KERNELS(kanegen_models::NAME##_float, float), nullptr, nullptr, nullptr, nullptr  \
    }                                                                                           \
  }

#define KANEGEN_LOOPS(NAME, DT, STEPS)                                                     \
  Model {                                                                                  \
#NAME, kanegen_models::NAME::NQ, kanegen_models::NAME::NU, kanegen_models::NAME::NTAU, \
        kanegen_models::NAME::NY, kanegen_models::NAME::NC,                                \
        {KANEGEN_KERNELS(kanegen_models::NAME, double),                                    \
         KANEGEN_LOOP_KERNELS(kanegen_models::NAME, double) },                             \
         {KANEGEN_KERNELS(kanegen_models::NAME##_float, float),                            \
          KANEGEN_LOOP_KERNELS(kanegen_models::NAME##_float, float) },                     \
          DT, STEPS, (STEPS) / 100                                                         \
  }

/// max |float - double| and max |double| over every entry of every sample
/// (per entry with `per_entry`, for quantities of different units).
class Error {
 public:
  explicit Error(bool per_entry = false) : per_entry_(per_entry) {}
  void add(const std::vector<float>& f, const std::vector<double>& d) {
    difference_.resize(d.size(), 0.0);
    scale_.resize(d.size(), 0.0);
    for (std::size_t i = 0; i < d.size(); ++i) {
      difference_[i] = std::max(difference_[i], std::abs(static_cast<double>(f[i]) - d[i]));
      scale_[i] = std::max(scale_[i], std::abs(d[i]));
    }
  }
  double relative() const {
    if (per_entry_) {
      double worst = 0.0;
      for (std::size_t i = 0; i < scale_.size(); ++i)
        worst = std::max(worst, ratio(difference_[i], scale_[i]));
      return worst;
    }
    double difference = 0.0, scale = 0.0;
    for (std::size_t i = 0; i < scale_.size(); ++i) {
      difference = std::max(difference, difference_[i]);
      scale = std::max(scale, scale_[i]);
    }
    return ratio(difference, scale);
  }

 private:
  static double ratio(double difference, double scale) {
    return scale > 0.0 ? difference / scale : difference;
  }
  bool per_entry_;
  std::vector<double> difference_, scale_;
};

std::vector<float> rounded(const std::vector<double>& v) { return std::vector<float>(v.begin(), v.end()); }
std::vector<double> widened(const std::vector<float>& v) { return std::vector<double>(v.begin(), v.end()); }

/// A fixed-seed uniform sampler.
class Uniform {
 public:
  double operator()(double lo, double hi) {
    seed_ = seed_ * 6364136223846793005ull + 1442695040888963407ull;
    return lo + (hi - lo) * static_cast<double>(seed_ >> 11) / 9007199254740992.0;
  }

 private:
  std::uint64_t seed_ = 12345;
};

struct Figures {
  double mass_matrix = 0.0, forcing = 0.0, dynamics = 0.0, outputs = 0.0;
  double constraints = 0.0, jacobian = 0.0, bias = 0.0, lambda = 0.0;
};

/// The kernels defined at any state, at 200 random ones: q in [-pi, pi],
/// u in [-2, 2] rad/s, tau in [-5, 5] N m. For an open tree also the
/// dynamics and outputs.
void compare_at_random_states(const Model& m, Figures& out) {
  Uniform uniform;
  Error mass, force, dynamics, outputs(true), phi, jacobian, bias;
  for (int sample = 0; sample < 200; ++sample) {
    std::vector<float> qf(m.nq), uf(m.nu), tauf(std::max(m.ntau, 1));
    for (float& v : qf) v = static_cast<float>(uniform(-M_PI, M_PI));
    for (float& v : uf) v = static_cast<float>(uniform(-2.0, 2.0));
    for (float& v : tauf) v = static_cast<float>(uniform(-5.0, 5.0));
    const std::vector<double> q = widened(qf), u = widened(uf), tau = widened(tauf);
    std::vector<double> Md(m.nu * m.nu), fd(m.nu);
    std::vector<float> Mf(m.nu * m.nu), ff(m.nu);
    m.d.mass_matrix(q.data(), Md.data());
    m.f.mass_matrix(qf.data(), Mf.data());
    m.d.forcing(0.0, q.data(), u.data(), tau.data(), fd.data());
    m.f.forcing(0.0f, qf.data(), uf.data(), tauf.data(), ff.data());
    mass.add(Mf, Md);
    force.add(ff, fd);
    if (m.nc == 0) {
      std::vector<double> ad(m.nu), yd(std::max(m.ny, 1));
      std::vector<float> af(m.nu), yf(std::max(m.ny, 1));
      REQUIRE(m.d.forward_dynamics(0.0, q.data(), u.data(), tau.data(), ad.data()) == 0);
      REQUIRE(m.f.forward_dynamics(0.0f, qf.data(), uf.data(), tauf.data(), af.data()) == 0);
      m.d.outputs(0.0, q.data(), u.data(), yd.data());
      m.f.outputs(0.0f, qf.data(), uf.data(), yf.data());
      dynamics.add(af, ad);
      outputs.add(yf, yd);
      continue;
    }
    std::vector<double> phid(m.nc), Cd(m.nc * m.nu), gd(m.nc);
    std::vector<float> phif(m.nc), Cf(m.nc * m.nu), gf(m.nc);
    m.d.constraints(q.data(), phid.data());
    m.f.constraints(qf.data(), phif.data());
    m.d.constraint_jacobian(q.data(), Cd.data());
    m.f.constraint_jacobian(qf.data(), Cf.data());
    m.d.constraint_bias(q.data(), u.data(), gd.data());
    m.f.constraint_bias(qf.data(), uf.data(), gf.data());
    phi.add(phif, phid);
    jacobian.add(Cf, Cd);
    bias.add(gf, gd);
  }
  out.mass_matrix = mass.relative();
  out.forcing = force.relative();
  if (m.nc == 0) {
    out.dynamics = dynamics.relative();
    out.outputs = outputs.relative();
  } else {
    out.constraints = phi.relative();
    out.jacobian = jacobian.relative();
    out.bias = bias.relative();
  }
}

/// A model with loops: udot, lambda and the outputs along its own motion
/// (inputs 0), 100 samples of a double RK4 run from the initial state.
void compare_along_the_motion(const Model& m, Figures& out) {
  std::vector<double> x(m.nq + m.nu);
  m.d.initial_state(x.data(), x.data() + m.nq);
  const std::vector<double> no_inputs(std::max(m.ntau, 1), 0.0);
  int failed_solves = 0;
  const auto rates = [&m, &no_inputs, &failed_solves](double t, const double* state, double* dxdt) {
    m.d.coordinate_rates(state, state + m.nq, dxdt);
    failed_solves += m.d.forward_dynamics(t, state, state + m.nq, no_inputs.data(), dxdt + m.nq) != 0;
  };
  std::vector<double> work(5 * x.size());
  Error dynamics, lambda, outputs(true);
  double t = 0.0, drift = 0.0;
  for (int step = 0; step <= m.steps; ++step) {
    if (step % m.every == 0) {
      std::vector<double> phi(m.nc);
      m.d.constraints(x.data(), phi.data());
      for (double r : phi) drift = std::max(drift, std::abs(r));
      const float tf = static_cast<float>(t);
      const std::vector<float> qf = rounded({x.begin(), x.begin() + m.nq}),
                               uf = rounded({x.begin() + m.nq, x.end()});
      const std::vector<float> tauf(no_inputs.size(), 0.0f);
      const std::vector<double> q = widened(qf), u = widened(uf);
      std::vector<double> ad(m.nu), ld(m.nc), yd(std::max(m.ny, 1));
      std::vector<float> af(m.nu), lf(m.nc), yf(std::max(m.ny, 1));
      REQUIRE(m.d.constrained_dynamics(tf, q.data(), u.data(), no_inputs.data(), ad.data(), ld.data()) == 0);
      REQUIRE(m.f.constrained_dynamics(tf, qf.data(), uf.data(), tauf.data(), af.data(), lf.data()) == 0);
      m.d.outputs(tf, q.data(), u.data(), yd.data());
      m.f.outputs(tf, qf.data(), uf.data(), yf.data());
      dynamics.add(af, ad);
      lambda.add(lf, ld);
      outputs.add(yf, yd);
    }
    if (step < m.steps) {
      kanegen::runtime::rk4_step(rates, t, m.dt, x.data(), static_cast<int>(x.size()), work.data());
      REQUIRE(failed_solves == 0);
      t += m.dt;
    }
  }
  INFO("largest |Phi| along the motion " << drift);
  REQUIRE(drift < 1e-6);
  out.dynamics = dynamics.relative();
  out.lambda = lambda.relative();
  out.outputs = outputs.relative();
}

Figures compare(const Model& m) {
  Figures out;
  compare_at_random_states(m, out);
  if (m.nc > 0) compare_along_the_motion(m, out);
  std::printf("%-16s mass_matrix %.1e, forcing %.1e, forward_dynamics %.1e, outputs %.1e", m.name,
              out.mass_matrix, out.forcing, out.dynamics, out.outputs);
  if (m.nc > 0)
    std::printf(", constraints %.1e, constraint_jacobian %.1e, constraint_bias %.1e, lambda %.1e",
                out.constraints, out.jacobian, out.bias, out.lambda);
  std::printf("\n");
  return out;
}

}  // namespace

// Float rounding is 6e-8 (2^-24); a kernel of a thousand operations loses a
// few digits more, and the dynamics also the condition number of M (and of
// C M^-1 C^T with loops).
TEST_CASE("float kernels agree with double on every shipped rigid model") {
  std::printf(
      "float against double: the largest difference over the samples relative to the largest entry\n");
  // Each loop model's motion over a part of its cycle, where its loops stay regular.
  for (const Model& m : {KANEGEN_TREE(simple_pendulum), KANEGEN_TREE(double_pendulum), KANEGEN_TREE(arm7),
                         KANEGEN_TREE(chain20), KANEGEN_LOOPS(four_bar, 1e-3, 500),
                         KANEGEN_LOOPS(slider_crank, 2e-5, 2000), KANEGEN_LOOPS(nfourbar2, 1e-3, 500),
                         KANEGEN_LOOPS(nfourbar40, 1e-3, 500), KANEGEN_LOOPS(andrews_squeezer, 1e-5, 1000)}) {
    INFO(m.name);
    const Figures w = compare(m);
    // About ten times the largest figure measured over these models
    // (docs/embedded.md), so that a loss of a digit fails; nfourbar40's loop
    // forces pass through its 80 x 80 C M^-1 C^T and get their own bound.
    CHECK(w.mass_matrix < 5e-6);
    CHECK(w.forcing < 5e-6);
    CHECK(w.outputs < 1e-4);
    CHECK(w.dynamics < 5e-5);
    CHECK(w.constraints < 5e-6);
    CHECK(w.jacobian < 5e-6);
    CHECK(w.bias < 5e-6);
    CHECK(w.lambda < (std::string(m.name) == "nfourbar40" ? 2e-3 : 2e-5));
  }
}
