// SPDX-License-Identifier: GPL-2.0-or-later
// The generalized-alpha integrator against exact and independent
// solutions: second order on a stiff linear chain (modal solution), the
// damping of unresolved modes for rho_inf < 1 and energy conservation for
// rho_inf = 1, a pendulum as a constrained point mass (index 3) against
// the exact period and a tight DOPRI5 run of the minimal-coordinate ODE, a
// pendulum on a cart (M(q), free and with the cart prescribed) against
// DOPRI5 of the same model, and the failure paths.
#include "kanegen/runtime/genalpha.hpp"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "genalpha_models.hpp"
#include "kanegen/runtime/integrators.hpp"

using namespace kanegen::runtime;
using namespace genalpha_models;

namespace {

const double kPi = std::acos(-1.0);

/// Steps `steps` times; fails the test if a step fails.
void advance(GenAlpha& ga, long steps, const std::function<void(const GenAlpha&)>& check = nullptr) {
  std::string why;
  bool ok = true;
  for (long i = 0; i < steps && ok; ++i) {
    ok = ga.step(nullptr, &why);
    if (ok && check) check(ga);
  }
  INFO(why);
  REQUIRE(ok);
}

GenAlphaOptions options(double h, double rho_inf) {
  GenAlphaOptions o;
  o.h = h;
  o.rho_inf = rho_inf;
  return o;
}

// --- the chain: modal solution -------------------------------------------

/// The chain's modes: with q~ = M^1/2 q, z = R^T q~ decouples into
/// z_i'' = -omega_i^2 z_i (R the rotation diagonalizing M^-1/2 K M^-1/2).
struct ChainModes {
  double sm[2], c, s, omega[2];
  explicit ChainModes(const ChainParams& p) {
    sm[0] = std::sqrt(p.m1);
    sm[1] = std::sqrt(p.m2);
    const double k00 = (p.k1 + p.k2) / p.m1, k11 = p.k2 / p.m2, k01 = -p.k2 / (sm[0] * sm[1]);
    const double phi = 0.5 * std::atan2(2.0 * k01, k00 - k11);
    c = std::cos(phi);
    s = std::sin(phi);
    omega[0] = std::sqrt(k00 * c * c + 2.0 * k01 * s * c + k11 * s * s);
    omega[1] = std::sqrt(k00 * s * s - 2.0 * k01 * s * c + k11 * c * c);
  }
  void to_modal(const double* x, double* z) const {
    const double a = sm[0] * x[0], b = sm[1] * x[1];
    z[0] = c * a + s * b;
    z[1] = -s * a + c * b;
  }
  void from_modal(const double* z, double* x) const {
    x[0] = (c * z[0] - s * z[1]) / sm[0];
    x[1] = (s * z[0] + c * z[1]) / sm[1];
  }
  /// Exact state at t from (q0, u0).
  void exact(const double* q0, const double* u0, double t, double* q, double* u) const {
    double z[2], zd[2], zt[2], zdt[2];
    to_modal(q0, z);
    to_modal(u0, zd);
    for (int i = 0; i < 2; ++i) {
      const double w = omega[i];
      zt[i] = z[i] * std::cos(w * t) + zd[i] / w * std::sin(w * t);
      zdt[i] = -z[i] * w * std::sin(w * t) + zd[i] * std::cos(w * t);
    }
    from_modal(zt, q);
    from_modal(zdt, u);
  }
  int low() const { return omega[0] < omega[1] ? 0 : 1; }
  int high() const { return 1 - low(); }
  /// Energy of mode i.
  double energy(const double* q, const double* u, int i) const {
    double z[2], zd[2];
    to_modal(q, z);
    to_modal(u, zd);
    return 0.5 * (zd[i] * zd[i] + omega[i] * omega[i] * z[i] * z[i]);
  }
};

/// Largest error in q and u of the chain at t_end against the exact solution.
double chain_error(double k2, double h, double rho_inf, double t_end) {
  Model model(chain_table());
  model.set_parameter("k2", k2);
  ChainParams p;
  p.k2 = k2;
  const ChainModes modes(p);
  const double q0[] = {0.1, 0.12}, u0[] = {0.0, 0.5};
  GenAlphaOptions o = options(h, rho_inf);
  o.tolerance = 1e-12;
  GenAlpha ga(model, o);
  std::string why;
  REQUIRE(ga.start(0.0, q0, u0, nullptr, &why));
  advance(ga, std::lround(t_end / h));
  double q[2], u[2];
  modes.exact(q0, u0, ga.t(), q, u);
  double err = 0.0;
  for (int i = 0; i < 2; ++i) err = std::max({err, std::abs(ga.q()[i] - q[i]), std::abs(ga.u()[i] - u[i])});
  return err;
}

// --- the pendulum: exact period ------------------------------------------

/// Complete elliptic integral of the first kind K(k) by the AGM.
double elliptic_k(double k) {
  double a = 1.0, b = std::sqrt(1.0 - k * k);
  for (int i = 0; i < 40; ++i) {
    const double m = 0.5 * (a + b);
    b = std::sqrt(a * b);
    a = m;
  }
  return kPi / (2.0 * a);
}

struct PendulumRun {
  double error;    ///< distance from the lowest point after 5/4 of the exact period
  double max_phi;  ///< largest |Phi| over all steps
  double max_cu;   ///< largest |C u| over all steps
  double newton_per_step;
};

/// The pendulum released at rest at theta0 passes the lowest point (0, -L)
/// at a quarter of its period T = 4 sqrt(L/g) K(sin(theta0 / 2)), and again
/// at 5/4 T, at full speed (so a phase error shows, unlike at a turning point).
PendulumRun pendulum_period(double theta0, long steps_per_period, bool reuse) {
  Model model(point_pendulum_table());
  const PointParams p;
  const double period = 4.0 * std::sqrt(p.L / p.g) * elliptic_k(std::sin(theta0 / 2.0));
  GenAlphaOptions o = options(period / static_cast<double>(steps_per_period), 0.8);
  o.tolerance = 1e-10;
  o.reuse_jacobian = reuse;
  GenAlpha ga(model, o);
  const double q0[] = {p.L * std::sin(theta0), -p.L * std::cos(theta0)}, u0[] = {0.0, 0.0};
  std::string why;
  REQUIRE(ga.start(0.0, q0, u0, nullptr, &why));
  PendulumRun run{0.0, 0.0, 0.0, 0.0};
  const long steps = 5 * steps_per_period / 4;
  REQUIRE(4 * steps == 5 * steps_per_period);
  advance(ga, steps, [&](const GenAlpha& g) {
    const double* q = g.q();
    const double* u = g.u();
    run.max_phi = std::max(run.max_phi, std::abs(q[0] * q[0] + q[1] * q[1] - p.L * p.L));
    run.max_cu = std::max(run.max_cu, std::abs(2.0 * q[0] * u[0] + 2.0 * q[1] * u[1]));
  });
  run.error = std::hypot(ga.q()[0], ga.q()[1] + p.L);
  run.newton_per_step = static_cast<double>(ga.stats().newton_iterations) / static_cast<double>(steps);
  return run;
}

/// theta(t) of theta'' = -(g/L) sin(theta) from rest at theta0, by DOPRI5 at rtol 1e-12.
double pendulum_dopri(double theta0, double t_end, const PointParams& p) {
  double x[2] = {theta0, 0.0};
  IntegrationOptions opt;
  opt.t_end = t_end;
  opt.dt = t_end;
  opt.rtol = 1e-12;
  opt.atol = 1e-14;
  const auto rhs = [&](double, const double* s, double* sd) {
    sd[0] = s[1];
    sd[1] = -p.g / p.L * std::sin(s[0]);
    return true;
  };
  const IntegrationResult r = integrate(Method::kDopri5, rhs, 0.0, x, 2, opt, nullptr);
  REQUIRE(r.ok());
  return x[0];
}

/// The state at t_end of a model by DOPRI5 at rtol 1e-12 on its forward_dynamics.
std::vector<double> model_dopri(const Model& model, const double* q0, const double* u0, double t_end) {
  const int n = model.info().nu;
  std::vector<double> x(q0, q0 + n);
  x.insert(x.end(), u0, u0 + n);
  IntegrationOptions opt;
  opt.t_end = t_end;
  opt.dt = t_end;
  opt.rtol = 1e-12;
  opt.atol = 1e-14;
  const auto rhs = [&](double t, const double* s, double* sd) {
    std::copy(s + n, s + 2 * n, sd);
    return model.forward_dynamics(t, s, s + n, nullptr, sd + n) == 0;
  };
  REQUIRE(integrate(Method::kDopri5, rhs, 0.0, x.data(), 2 * n, opt, nullptr).ok());
  return x;
}

/// Largest state error of genalpha at t_end against `reference` (q then u).
double cart_error(bool prescribed, double h, const std::vector<double>& reference, double t_end) {
  Model model(cart_pendulum_table(prescribed));
  double q0[2], u0[2];
  model.initial_state(q0, u0);
  GenAlphaOptions o = options(h, 0.8);
  o.tolerance = 1e-12;
  GenAlpha ga(model, o);
  std::string why;
  REQUIRE(ga.start(0.0, q0, u0, nullptr, &why));
  advance(ga, std::lround(t_end / h));
  REQUIRE(ga.t() == Approx(t_end).margin(1e-12));
  double err = 0.0;
  for (int i = 0; i < 2; ++i)
    err = std::max({err, std::abs(ga.q()[i] - reference[i]), std::abs(ga.u()[i] - reference[2 + i])});
  return err;
}

}  // namespace

TEST_CASE("genalpha: Chung-Hulbert coefficients", "[genalpha]") {
  // rho_inf = 1: the trapezoidal rule; rho_inf = 0: asymptotic annihilation.
  const GenAlphaCoefficients one = genalpha_coefficients(1.0);
  CHECK(one.alpha_m == Approx(0.5));
  CHECK(one.alpha_f == Approx(0.5));
  CHECK(one.gamma == Approx(0.5));
  CHECK(one.beta == Approx(0.25));
  const GenAlphaCoefficients zero = genalpha_coefficients(0.0);
  CHECK(zero.alpha_m == Approx(-1.0));
  CHECK(zero.alpha_f == Approx(0.0));
  CHECK(zero.gamma == Approx(1.5));
  CHECK(zero.beta == Approx(1.0));
}

TEST_CASE("genalpha: second order on the stiff chain against its modal solution", "[genalpha]") {
  for (double rho : {0.0, 0.8, 1.0}) {
    // omega = 0.70 and 14.2 rad/s; omega h of the fast mode from 0.057 to 0.014.
    const double e1 = chain_error(100.0, 0.004, rho, 2.0);
    const double e2 = chain_error(100.0, 0.002, rho, 2.0);
    const double e3 = chain_error(100.0, 0.001, rho, 2.0);
    INFO("rho_inf " << rho << ": errors " << e1 << " " << e2 << " " << e3);
    CHECK(e1 / e2 > 3.5);
    CHECK(e2 / e3 == Approx(4.0).epsilon(0.1));
    // rho_inf = 0 damps the fast mode most (damping ratio O((omega h)^3)).
    CHECK(e3 < (rho == 0.0 ? 5e-4 : 1e-4));
  }
}

TEST_CASE("genalpha: rho_inf < 1 damps an unresolved mode and keeps the resolved one", "[genalpha]") {
  Model model(chain_table());
  const double k2 = 1e6;  // omega = 0.707 and 1414 rad/s
  model.set_parameter("k2", k2);
  ChainParams p;
  p.k2 = k2;
  const ChainModes modes(p);
  const double q0[] = {0.1, 0.1001}, u0[] = {0.0, 0.2};
  const double h = 0.01;  // omega h = 0.007 and 14
  for (double rho : {0.8, 1.0}) {
    GenAlpha ga(model, options(h, rho));
    std::string why;
    REQUIRE(ga.start(0.0, q0, u0, nullptr, &why));
    const double low0 = modes.energy(q0, u0, modes.low()), high0 = modes.energy(q0, u0, modes.high());
    REQUIRE(high0 > 1e-3 * low0);
    advance(ga, 300);
    const double low = modes.energy(ga.q(), ga.u(), modes.low());
    const double high = modes.energy(ga.q(), ga.u(), modes.high());
    INFO("rho_inf " << rho << ": low mode " << low / low0 << ", high mode " << high / high0);
    if (rho < 1.0) {
      CHECK(high / high0 < 1e-12);
      CHECK(low / low0 == Approx(1.0).epsilon(1e-6));  // algorithmic damping O((omega h)^3)
    } else {
      CHECK(high / high0 == Approx(1.0).epsilon(1e-9));
      CHECK(low / low0 == Approx(1.0).epsilon(1e-9));
    }
  }
}

TEST_CASE("genalpha: rho_inf = 1 conserves the chain's energy", "[genalpha]") {
  Model model(chain_table());
  const double q0[] = {0.1, -0.05}, u0[] = {0.3, 0.0};
  GenAlpha ga(model, options(0.05, 1.0));
  std::string why;
  REQUIRE(ga.start(0.0, q0, u0, nullptr, &why));
  const double e0 = model.kinetic_energy(q0, u0) + model.potential_energy(q0);
  double drift = 0.0;
  advance(ga, 4000, [&](const GenAlpha& g) {
    const double e = model.kinetic_energy(g.q(), g.u()) + model.potential_energy(g.q());
    drift = std::max(drift, std::abs(e - e0) / e0);
  });
  CHECK(drift < 1e-11);
  // A linear problem with the exact iteration matrix: converged after one
  // Newton iteration, which the second confirms; factored once.
  CHECK(ga.stats().newton_iterations <= 2 * ga.stats().steps);
  CHECK(ga.stats().factorizations == 1);
  CHECK(ga.stats().jacobian_evaluations == 1);
}

TEST_CASE("genalpha: one Newton iteration solves a linear constrained step exactly", "[genalpha]") {
  // Fresh Jacobians each step; the second iteration only confirms. An
  // inexact linear solve (the LU's row swaps applied out of order) shows
  // as linear convergence and more iterations.
  Model model(tied_table());
  double q0[3], u0[3];
  model.initial_state(q0, u0);
  GenAlphaOptions o = options(0.01, 0.8);
  o.reuse_jacobian = false;
  o.tolerance = 1e-12;
  GenAlpha ga(model, o);
  std::string why;
  REQUIRE(ga.start(0.0, q0, u0, nullptr, &why));
  double worst = 0.0;
  advance(ga, 500, [&](const GenAlpha& g) {
    worst = std::max(worst, std::abs(10.0 * g.q()[0] - 20.0 * g.q()[1] + 5.0 * g.q()[2]));
  });
  CHECK(ga.stats().newton_iterations == 2 * ga.stats().steps);
  CHECK(worst < 1e-12);
}

TEST_CASE("genalpha: the constrained pendulum returns after its exact period, on the circle", "[genalpha]") {
  const double theta0 = 2.0;  // 115 degrees: far from the linear pendulum
  const PendulumRun coarse = pendulum_period(theta0, 2000, true);
  const PendulumRun fine = pendulum_period(theta0, 4000, true);
  INFO("errors at the lowest point " << coarse.error << " " << fine.error << "; max |Phi| " << fine.max_phi
                                     << ", max |C u| " << fine.max_cu);
  CHECK(coarse.error / fine.error == Approx(4.0).epsilon(0.15));
  CHECK(fine.error < 1e-3);
  CHECK(coarse.max_phi < 1e-10);
  CHECK(fine.max_phi < 1e-10);
  CHECK(fine.max_cu < 1e-10);
}

TEST_CASE("genalpha: exact Jacobians give Newton's quadratic convergence on the pendulum", "[genalpha]") {
  // Fresh Jacobians each step: a wrong sign or term in the iteration matrix
  // (e.g. d(C^T lambda)/dq) would make Newton linear and slow.
  const PendulumRun run = pendulum_period(2.0, 1000, false);
  INFO("Newton iterations per step " << run.newton_per_step);
  CHECK(run.newton_per_step <= 3.0);
  CHECK(run.max_phi < 1e-10);
}

TEST_CASE("genalpha: simplified Newton reaches the solution of full Newton with fewer Jacobians",
          "[genalpha]") {
  // A coarse step (omega h = 0.16) on a large swing: the kept matrix goes
  // stale quickly, and must be refreshed in time.
  Model model(point_pendulum_table());
  const double q0[] = {std::sin(2.0), -std::cos(2.0)}, u0[] = {0.0, 0.0};
  double q[2][2];
  long jacobians[2];
  for (int reuse = 0; reuse < 2; ++reuse) {
    GenAlphaOptions o = options(0.05, 0.8);
    o.reuse_jacobian = reuse == 1;
    GenAlpha ga(model, o);
    std::string why;
    REQUIRE(ga.start(0.0, q0, u0, nullptr, &why));
    advance(ga, 200);
    q[reuse][0] = ga.q()[0];
    q[reuse][1] = ga.q()[1];
    jacobians[reuse] = ga.stats().jacobian_evaluations;
    CHECK(ga.stats().factorizations == ga.stats().jacobian_evaluations);
  }
  CHECK(jacobians[0] == 200);
  CHECK(jacobians[1] < 200);
  // Both converge to the same discrete solution, to the Newton tolerance
  // (1e-10 relative) accumulated over 200 steps.
  CHECK(q[1][0] == Approx(q[0][0]).margin(1e-6));
  CHECK(q[1][1] == Approx(q[0][1]).margin(1e-6));
}

TEST_CASE("genalpha: the constrained pendulum against DOPRI5 of the angle's ODE", "[genalpha]") {
  const PointParams p;
  const double theta0 = 1.0, t_end = 3.7, h = 1e-3;
  Model model(point_pendulum_table());
  GenAlpha ga(model, options(h, 0.8));
  const double q0[] = {p.L * std::sin(theta0), -p.L * std::cos(theta0)}, u0[] = {0.0, 0.0};
  std::string why;
  REQUIRE(ga.start(0.0, q0, u0, nullptr, &why));
  advance(ga, std::lround(t_end / h));
  const double theta = std::atan2(ga.q()[0], -ga.q()[1]);
  const double reference = pendulum_dopri(theta0, t_end, p);
  INFO("theta " << theta << ", DOPRI5 " << reference);
  // Second order: about (omega h)^2 t omega / 12 ~ 1e-5 rad of phase over 2 periods.
  CHECK(std::abs(theta - reference) < 5e-5);
}

TEST_CASE("genalpha: a mass matrix that depends on q, free and with a prescribed coordinate", "[genalpha]") {
  for (bool prescribed : {false, true}) {
    Model model(cart_pendulum_table(prescribed));
    double q0[2], u0[2];
    model.initial_state(q0, u0);
    const double t_end = 2.0;
    const std::vector<double> reference = model_dopri(model, q0, u0, t_end);
    const double e1 = cart_error(prescribed, 2e-3, reference, t_end);
    const double e2 = cart_error(prescribed, 1e-3, reference, t_end);
    INFO((prescribed ? "prescribed cart" : "free cart") << ": errors " << e1 << " " << e2);
    CHECK(e1 / e2 == Approx(4.0).epsilon(0.15));
    CHECK(e2 < 1e-4);
  }
}

TEST_CASE("genalpha: the prescribed coordinate follows its motion", "[genalpha]") {
  Model model(cart_pendulum_table(true));
  const CartParams p;
  double q0[2], u0[2];
  model.initial_state(q0, u0);
  GenAlpha ga(model, options(1e-3, 0.8));
  std::string why;
  REQUIRE(ga.start(0.0, q0, u0, nullptr, &why));
  double worst = 0.0;
  advance(ga, 2000, [&](const GenAlpha& g) {
    worst = std::max(worst, std::abs(g.q()[0] - p.A * std::sin(p.W * g.t())));
    CHECK(g.udot()[0] == Approx(-p.A * p.W * p.W * std::sin(p.W * g.t())).margin(1e-12));
  });
  CHECK(worst < 1e-6);  // second order in h from the given acceleration
}

TEST_CASE("genalpha: finds the prescribed coordinates of a model without roles", "[genalpha]") {
  // Generated open trees carry no coordinate_roles (only models with loops do).
  ModelTable prescribed = cart_pendulum_table(true);
  prescribed.coordinate_roles = nullptr;
  Model with(prescribed), without(cart_pendulum_table(false));
  const GenAlpha a(with, options(1e-3, 0.8)), b(without, options(1e-3, 0.8));
  CHECK(a.prescribed(0));
  CHECK_FALSE(a.prescribed(1));
  CHECK_FALSE(b.prescribed(0));
  CHECK_FALSE(b.prescribed(1));
}

TEST_CASE("genalpha: options and models it cannot use", "[genalpha]") {
  Model chain(chain_table());
  CHECK_THROWS_AS(GenAlpha(chain, options(0.0, 0.8)), std::invalid_argument);
  CHECK_THROWS_AS(GenAlpha(chain, options(1e-3, 1.5)), std::invalid_argument);
  CHECK_THROWS_AS(GenAlpha(chain, options(1e-3, -0.1)), std::invalid_argument);
  GenAlphaOptions o = options(1e-3, 0.8);
  o.max_newton = 0;
  CHECK_THROWS_AS(GenAlpha(chain, o), std::invalid_argument);
  ModelTable table = chain_table();
  table.forcing_jacobian = nullptr;
  Model without(table);
  CHECK_THROWS_WITH(GenAlpha(without, options(1e-3, 0.8)), Catch::Contains("--jacobians"));
}

TEST_CASE("genalpha: a start off the loops and a step before start fail with a reason", "[genalpha]") {
  Model model(point_pendulum_table());
  GenAlpha ga(model, options(1e-3, 0.8));
  std::string why;
  CHECK_FALSE(ga.step(nullptr, &why));
  CHECK_THAT(why, Catch::Contains("before a successful start"));
  const double q[] = {1.0, 0.01}, u[] = {0.0, 0.0};
  CHECK_FALSE(ga.start(0.0, q, u, nullptr, &why));
  CHECK_THAT(why, Catch::Contains("do not close the loops"));
  // The speeds are put on C u = 0 by the change of least kinetic energy.
  const double q1[] = {1.0, 0.0}, u1[] = {0.3, 0.4};
  REQUIRE(ga.start(0.0, q1, u1, nullptr, &why));
  CHECK(ga.u()[0] == Approx(0.0).margin(1e-15));
  CHECK(ga.u()[1] == Approx(0.4));
}

TEST_CASE("genalpha: failed steps leave the last good state and say when and why", "[genalpha]") {
  std::string why;
  SECTION("Newton does not converge within max_newton") {
    Model model(point_pendulum_table());
    GenAlphaOptions o = options(0.05, 0.8);
    o.max_newton = 1;
    o.tolerance = 1e-14;
    GenAlpha ga(model, o);
    const double q0[] = {std::sin(1.0), -std::cos(1.0)}, u0[] = {0.0, 0.0};
    REQUIRE(ga.start(0.0, q0, u0, nullptr, &why));
    CHECK_FALSE(ga.step(nullptr, &why));
    CHECK_THAT(why,
               Catch::Contains("from t = 0 to 0.05") && Catch::Contains("did not converge in 1 iteration"));
    CHECK(ga.t() == 0.0);
    CHECK(ga.q()[0] == q0[0]);
    CHECK(ga.stats().rejected == 1);
    CHECK(ga.stats().steps == 0);
  }
  SECTION("a residual that is not finite") {
    Model model(chain_table());
    GenAlpha ga(model, options(0.01, 0.8));
    const double q0[] = {0.1, 0.0}, u0[] = {0.0, 0.0};
    REQUIRE(ga.start(0.0, q0, u0, nullptr, &why));
    advance(ga, 3);
    const double q_before = ga.q()[0];
    model.set_parameter("k2", NAN);
    CHECK_FALSE(ga.step(nullptr, &why));
    CHECK_THAT(why, Catch::Contains("from t = 0.03 ") && Catch::Contains("not finite") &&
                        Catch::Contains("x1=" + std::to_string(q_before).substr(0, 6)));
    CHECK(ga.t() == Approx(0.03));
    CHECK(ga.q()[0] == q_before);
  }
  // An open tree's residual solves with forward_dynamics, which meets the
  // singular M first (the iteration matrix's own check stays for loops).
  SECTION("a singular mass matrix at the trial state") {
    Model model(chain_table());
    GenAlphaOptions o = options(0.01, 0.8);
    o.reuse_jacobian = false;
    GenAlpha ga(model, o);
    const double q0[] = {0.1, 0.0}, u0[] = {0.0, 0.0};
    REQUIRE(ga.start(0.0, q0, u0, nullptr, &why));
    for (const char* name : {"m1", "k1", "k2"}) model.set_parameter(name, 0.0);  // row 1 vanishes
    CHECK_FALSE(ga.step(nullptr, &why));
    CHECK_THAT(why, Catch::Contains("the mass matrix is singular (pivot 1) at the trial state"));
    CHECK(ga.t() == 0.0);
  }
}
