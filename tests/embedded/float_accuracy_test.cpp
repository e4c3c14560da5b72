// SPDX-License-Identifier: GPL-2.0-or-later
// The float kernels (kanegen generate --precision float) against the double
// ones of the same model, on every shipped rigid model with an open tree:
// both evaluated at the same float-representable states, so that the
// difference is the float kernels' rounding alone. The largest difference
// over the samples relative to the largest entry over the samples (an entry
// near zero, where terms cancel, has no meaningful relative error of its
// own); printed for docs/embedded.md.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <vector>

#include "arm7.hpp"
#include "arm7_float.hpp"
#include "chain20.hpp"
#include "chain20_float.hpp"
#include "double_pendulum.hpp"
#include "double_pendulum_float.hpp"
#include "simple_pendulum.hpp"
#include "simple_pendulum_float.hpp"

namespace {

/// The kernels of one model in both precisions.
struct Pair {
  const char* name;
  int nq, nu, ntau;
  void (*mass_matrix_d)(const double*, double*);
  void (*mass_matrix_f)(const float*, float*);
  void (*forcing_d)(const double*, const double*, const double*, double*);
  void (*forcing_f)(const float*, const float*, const float*, float*);
  int (*dynamics_d)(const double*, const double*, const double*, double*);
  int (*dynamics_f)(const float*, const float*, const float*, float*);
};

#define KANEGEN_PAIR(NAME)                                                                               \
  Pair {                                                                                                 \
#NAME, kanegen_models::NAME::NQ, kanegen_models::NAME::NU, kanegen_models::NAME::NTAU,                 \
        [](const double* q, double* M) { kanegen_models::NAME::mass_matrix({}, q, M); },                   \
        [](const float* q, float* M) { kanegen_models::NAME##_float::mass_matrix({}, q, M); },             \
        [](const double* q, const double* u, const double* tau, double* f) {                               \
          kanegen_models::NAME::forcing({}, 0.0, q, u, tau, f);                                            \
        },                                                                                                 \
        [](const float* q, const float* u, const float* tau, float* f) {                                   \
          kanegen_models::NAME##_float::forcing({}, 0.0f, q, u, tau, f);                                   \
        },                                                                                                 \
        [](const double* q, const double* u, const double* tau, double* a) {                               \
          return kanegen_models::NAME::forward_dynamics({}, 0.0, q, u, tau, a);                            \
        },                                                                                                 \
        [](const float* q, const float* u, const float* tau, float* a) {                                   \
          return kanegen_models::NAME##_float::forward_dynamics({}, 0.0f, q, u, tau, a);                   \
        } \
  }

/// max |float - double| and max |double| over every entry of every sample.
struct Error {
  double difference = 0.0, scale = 0.0;
  void add(const std::vector<float>& f, const std::vector<double>& d) {
    for (std::size_t i = 0; i < d.size(); ++i) {
      difference = std::max(difference, std::abs(static_cast<double>(f[i]) - d[i]));
      scale = std::max(scale, std::abs(d[i]));
    }
  }
  double relative() const { return scale > 0.0 ? difference / scale : difference; }
};

struct Worst {
  double mass_matrix = 0.0, forcing = 0.0, dynamics = 0.0;
};

/// 200 states: q in [-pi, pi], u in [-2, 2] rad/s, tau in [-5, 5] N m, from a fixed seed.
Worst compare(const Pair& m) {
  std::uint64_t seed = 12345;
  const auto uniform = [&seed](double lo, double hi) {
    seed = seed * 6364136223846793005ull + 1442695040888963407ull;
    return lo + (hi - lo) * static_cast<double>(seed >> 11) / 9007199254740992.0;
  };
  Error mass, force, dynamics;
  for (int sample = 0; sample < 200; ++sample) {
    std::vector<float> qf(m.nq), uf(m.nu), tauf(std::max(m.ntau, 1));
    for (float& v : qf) v = static_cast<float>(uniform(-M_PI, M_PI));
    for (float& v : uf) v = static_cast<float>(uniform(-2.0, 2.0));
    for (float& v : tauf) v = static_cast<float>(uniform(-5.0, 5.0));
    const std::vector<double> q(qf.begin(), qf.end()), u(uf.begin(), uf.end()), tau(tauf.begin(), tauf.end());
    std::vector<double> Md(m.nu * m.nu), fd(m.nu), ad(m.nu);
    std::vector<float> Mf(m.nu * m.nu), ff(m.nu), af(m.nu);
    m.mass_matrix_d(q.data(), Md.data());
    m.mass_matrix_f(qf.data(), Mf.data());
    m.forcing_d(q.data(), u.data(), tau.data(), fd.data());
    m.forcing_f(qf.data(), uf.data(), tauf.data(), ff.data());
    REQUIRE(m.dynamics_d(q.data(), u.data(), tau.data(), ad.data()) == 0);
    REQUIRE(m.dynamics_f(qf.data(), uf.data(), tauf.data(), af.data()) == 0);
    mass.add(Mf, Md);
    force.add(ff, fd);
    dynamics.add(af, ad);
  }
  const Worst worst{mass.relative(), force.relative(), dynamics.relative()};
  std::printf(
      "%-16s float against double, largest difference over 200 states relative to the largest entry: "
      "mass_matrix %.1e, "
      "forcing %.1e, forward_dynamics %.1e\n",
      m.name, worst.mass_matrix, worst.forcing, worst.dynamics);
  return worst;
}

}  // namespace

// Float rounding is 6e-8 (2^-24); a kernel of a thousand operations loses a
// few digits more, and forward_dynamics also the condition number of M.
TEST_CASE("float kernels agree with double on every rigid open-tree model") {
  for (const Pair& m : {KANEGEN_PAIR(simple_pendulum), KANEGEN_PAIR(double_pendulum), KANEGEN_PAIR(arm7),
                        KANEGEN_PAIR(chain20)}) {
    INFO(m.name);
    const Worst w = compare(m);
    CHECK(w.mass_matrix < 1e-5);
    CHECK(w.forcing < 1e-5);
    CHECK(w.dynamics < 1e-3);
  }
}
