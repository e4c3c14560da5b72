// SPDX-License-Identifier: GPL-2.0-or-later
// The batched kernels (kanegen generate --batch W) lane by lane against the
// scalar kernels of the same model: W random states per call, each lane's
// udot (forward_dynamics) and tau (inverse_dynamics) within 1e-13 relative
// of the scalar kernel's, and a lane made singular (NaN coordinates) gives
// the scalar kernel's status in that lane only. tests.cmake lists the models
// (vector extension and portable lanes, W = 4 and 8).
#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <stdexcept>
#include <vector>

#include "arm7_b4v_batch4.hpp"
#include "arm7_b8p_batch8.hpp"
#include "arm7_b8v_batch8.hpp"
#include "arm7_s4v_batch4.hpp"
#include "codegen/batch_kernels.hpp"
#include "dp_b4p_batch4.hpp"
#include "dp_b4v_batch4.hpp"
#include "flex_b4p_batch4.hpp"
#include "flex_b8v_batch8.hpp"

namespace {

constexpr double kRelative = 1e-13;

/// One model's scalar and batched kernels, by its namespace.
#define KANEGEN_BATCH_MODEL(ns, W)                                                                       \
  struct ns##_kernels {                                                                                  \
    using Params = kanegen_models::ns::Params;                                                           \
    static constexpr int lanes = W, nq = kanegen_models::ns::NQ, nu = kanegen_models::ns::NU,            \
                         ntau = kanegen_models::ns::NTAU;                                                \
    static int forward(const Params& p, double t, const double* q, const double* u, const double* tau,   \
                       double* udot) {                                                                   \
      return kanegen_models::ns::forward_dynamics(p, t, q, u, tau, udot);                                \
    }                                                                                                    \
    static void inverse(const Params& p, double t, const double* q, const double* u, const double* udot, \
                        double* tau) {                                                                   \
      kanegen_models::ns::inverse_dynamics(p, t, q, u, udot, tau);                                       \
    }                                                                                                    \
    static int forward_batch(const Params& p, const double* t, const double* q, const double* u,         \
                             const double* tau, double* udot, int* status) {                             \
      return kanegen_models::ns::forward_dynamics_batch##W(p, t, q, u, tau, udot, status);               \
    }                                                                                                    \
    static void inverse_batch(const Params& p, const double* t, const double* q, const double* u,        \
                              const double* udot, double* tau) {                                         \
      kanegen_models::ns::inverse_dynamics_batch##W(p, t, q, u, udot, tau);                              \
    }                                                                                                    \
  };

KANEGEN_BATCH_MODEL(arm7_b4v, 4)
KANEGEN_BATCH_MODEL(arm7_b8p, 8)
KANEGEN_BATCH_MODEL(arm7_b8v, 8)
KANEGEN_BATCH_MODEL(arm7_s4v, 4)
KANEGEN_BATCH_MODEL(dp_b4v, 4)
KANEGEN_BATCH_MODEL(dp_b4p, 4)
KANEGEN_BATCH_MODEL(flex_b8v, 8)
KANEGEN_BATCH_MODEL(flex_b4p, 4)

/// Entry i of lane l of a structure of arrays of W lanes.
std::vector<double> lane(const std::vector<double>& soa, int lanes, int l) {
  std::vector<double> out(soa.size() / lanes);
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = soa[i * lanes + l];
  return out;
}

std::vector<double> random_soa(std::mt19937_64& rng, int n, int lanes, double scale) {
  std::uniform_real_distribution<double> draw(-scale, scale);
  std::vector<double> v(static_cast<std::size_t>(n > 0 ? n : 1) * lanes);
  for (double& x : v) x = draw(rng);
  return v;
}

/// |batched - scalar| <= 1e-13 |scalar| entry by entry; the largest ratio seen is kept.
void compare(const std::vector<double>& batched, const std::vector<double>& scalar, double& worst) {
  REQUIRE(batched.size() == scalar.size());
  for (std::size_t i = 0; i < scalar.size(); ++i) {
    const double difference = std::abs(batched[i] - scalar[i]);
    if (difference > 0) worst = std::max(worst, difference / std::abs(scalar[i]));
    INFO("entry " << i << ": batched " << batched[i] << ", scalar " << scalar[i]);
    CHECK(difference <= kRelative * std::abs(scalar[i]));
  }
}

/// Random states, `calls` batched calls of W lanes each; in the last call
/// lane 1 has NaN coordinates (a pivot that is not positive).
template <class K>
void check_model(int calls) {
  const typename K::Params p{};
  const int W = K::lanes;
  std::mt19937_64 rng(20261206);
  double worst = 0.0;
  for (int call = 0; call < calls; ++call) {
    std::vector<double> t = random_soa(rng, 1, W, 2.0), q = random_soa(rng, K::nq, W, 3.0),
                        u = random_soa(rng, K::nu, W, 2.0), tau = random_soa(rng, K::ntau, W, 5.0),
                        a = random_soa(rng, K::nu, W, 4.0);
    const bool singular = call + 1 == calls;
    if (singular)
      for (int i = 0; i < K::nq; ++i) q[static_cast<std::size_t>(i) * W + 1] = std::nan("");
    std::vector<double> udot(static_cast<std::size_t>(K::nu) * W), force(static_cast<std::size_t>(K::nu) * W);
    std::vector<int> status(W, -1);
    const int failed =
        K::forward_batch(p, t.data(), q.data(), u.data(), tau.data(), udot.data(), status.data());
    K::inverse_batch(p, t.data(), q.data(), u.data(), a.data(), force.data());
    int failed_scalar = 0;
    for (int l = 0; l < W; ++l) {
      INFO("call " << call << ", lane " << l);
      const std::vector<double> ql = lane(q, W, l), ul = lane(u, W, l), taul = lane(tau, W, l),
                                al = lane(a, W, l);
      std::vector<double> udot_l(K::nu), force_l(K::nu);
      const int s = K::forward(p, t[l], ql.data(), ul.data(), taul.data(), udot_l.data());
      CHECK(status[l] == s);
      failed_scalar += s != 0;
      if (singular && l == 1) {
        CHECK(s != 0);  // else the test of the status would test nothing
        continue;
      }
      REQUIRE(s == 0);
      compare(lane(udot, W, l), udot_l, worst);
      K::inverse(p, t[l], ql.data(), ul.data(), al.data(), force_l.data());
      compare(lane(force, W, l), force_l, worst);
    }
    CHECK(failed == failed_scalar);
  }
  WARN("largest relative difference from the scalar kernels: " << worst);
}

}  // namespace

TEST_CASE("arm7: batched kernels, 4 lanes (vector extension), lane by lane as the scalar ones") {
  check_model<arm7_b4v_kernels>(25);
}

TEST_CASE("arm7: batched kernels, 8 lanes (portable lanes), lane by lane as the scalar ones") {
  check_model<arm7_b8p_kernels>(13);
}

TEST_CASE("arm7: batched kernels, 8 lanes (vector extension), lane by lane as the scalar ones") {
  check_model<arm7_b8v_kernels>(13);
}

TEST_CASE("arm7 split into parts of ~300 operations: batched kernels, 4 lanes, as the scalar ones") {
  check_model<arm7_s4v_kernels>(25);
}

TEST_CASE("double_pendulum (composite inertias, LDL^T): batched kernels as the scalar ones, both lanes") {
  check_model<dp_b4v_kernels>(25);
  check_model<dp_b4p_kernels>(25);
}

TEST_CASE(
    "flexible_arm2 (flexible tree): batched kernels as the scalar ones, 8 vector and 4 portable lanes") {
  check_model<flex_b8v_kernels>(13);
  check_model<flex_b4p_kernels>(25);
}

TEST_CASE("batch_body: pivot checks per lane, numbers made vectors, branches refused") {
  using kanegen::codegen::batch_body;
  const std::string body =
      "  // a comment with if and double\n"
      "  const double x0 = cos(q[1]);\n"
      "  const double x1 = 2.0*p.m + sin(p.l);\n"
      "  const double pivot0 = x0*x1;\n"
      "  udot[0] = 1.0/pivot0;\n"
      "  if (!(pivot0 > 0.0)) return 1;\n"
      "  return 0;\n";
  CHECK(batch_body(body) ==
        "  // a comment with if and double\n"
        "  const Lanes x0 = lanes_cos(q[1]);\n"
        "  const Lanes x1 = lanes_zero + (2.0*p.m + lanes_sin(p.l));\n"
        "  const Lanes pivot0 = x0*x1;\n"
        "  udot[0] = 1.0/pivot0;\n"
        "  lanes_check(status, pivot0, 1);\n");
  // sin and cos of one argument: one lane loop at the first; not across a scope.
  CHECK(batch_body(
            "  const double x1 = cos(q[0]);\n  const double x2 = x1*x1;\n  const double x3 = sin(q[0]);\n") ==
        "  Lanes x3, x1;\n  lanes_sincos(q[0], x3, x1);\n  const Lanes x2 = x1*x1;\n");
  CHECK(batch_body("  const double x1 = cos(q[0]);\n  {\n  const double x3 = sin(q[0]);\n") ==
        "  const Lanes x1 = lanes_cos(q[0]);\n  {\n  const Lanes x3 = lanes_sin(q[0]);\n");
  CHECK_THROWS_AS(batch_body("  if (t < 0.5) {\n  }\n"), std::logic_error);
  CHECK_THROWS_AS(batch_body("  for (int k = 0; k < NU; ++k) M[k] = 0.0;\n"), std::logic_error);
  CHECK_THROWS_AS(batch_body("  return 3;\n  return 0;\n"), std::logic_error);
}
