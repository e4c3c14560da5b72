// SPDX-License-Identifier: GPL-2.0-or-later
// The integrators against analytic solutions: convergence order of RK4,
// DOPRI5 accuracy and dense output on the harmonic oscillator and a Kepler
// orbit, the output grid, step statistics and the failure paths.
#include "kanegen/runtime/integrators.hpp"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdlib>
#include <string>
#include <vector>

using namespace kanegen::runtime;

// embedded_rk4.cpp, built without exceptions and without the C++ library.
void embedded_oscillator(double h, int steps, double* q, double* v);

namespace {

const double kPi = std::acos(-1.0);

// x' = -x, x(0) = 1: x = exp(-t).
bool decay(double, const double* x, double* xdot) {
  xdot[0] = -x[0];
  return true;
}

// q'' = -q as [q, v], q(0) = 1, v(0) = 0: q = cos t, v = -sin t.
bool oscillator(double, const double* x, double* xdot) {
  xdot[0] = x[1];
  xdot[1] = -x[0];
  return true;
}

// Kepler problem, GM = 1, state [x, y, vx, vy].
bool kepler(double, const double* s, double* sdot) {
  const double r = std::hypot(s[0], s[1]);
  const double r3 = r * r * r;
  sdot[0] = s[2];
  sdot[1] = s[3];
  sdot[2] = -s[0] / r3;
  sdot[3] = -s[1] / r3;
  return true;
}

// Exact Kepler orbit with a = 1, GM = 1 (period 2 pi), eccentricity e,
// starting at periapsis on the +x axis: Kepler's equation E - e sin E = t.
void kepler_exact(double e, double t, double* s) {
  double E = t + e * std::sin(t);
  for (int i = 0; i < 50; ++i) E -= (E - e * std::sin(E) - t) / (1 - e * std::cos(E));
  const double b = std::sqrt(1 - e * e), rdot = 1.0 / (1 - e * std::cos(E));
  s[0] = std::cos(E) - e;
  s[1] = b * std::sin(E);
  s[2] = -std::sin(E) * rdot;
  s[3] = b * std::cos(E) * rdot;
}

double kepler_energy(const double* s) {
  return 0.5 * (s[2] * s[2] + s[3] * s[3]) - 1.0 / std::hypot(s[0], s[1]);
}

struct Recorded {
  std::vector<double> t;
  std::vector<std::vector<double>> x;
};

// Runs integrate() recording every output.
IntegrationResult record(Method m, const Rhs& rhs, double t0, std::vector<double>& x,
                         const IntegrationOptions& opt, Recorded& out) {
  const int n = static_cast<int>(x.size());
  return integrate(m, rhs, t0, x.data(), n, opt, [&](double t, const double* xs) {
    out.t.push_back(t);
    out.x.emplace_back(xs, xs + n);
    return true;
  });
}

// The number after "t=" in a failure message.
double time_in_message(const std::string& message) {
  const size_t at = message.find("t=");
  REQUIRE(at != std::string::npos);
  return std::strtod(message.c_str() + at + 2, nullptr);
}

}  // namespace

TEST_CASE("RK4 converges with order 4 on x' = -x", "[rk4]") {
  std::vector<double> errors;
  for (double h : {0.1, 0.05, 0.025, 0.0125}) {
    IntegrationOptions opt;
    opt.t_end = 2.0;
    opt.dt = h;
    std::vector<double> x = {1.0};
    REQUIRE(integrate(Method::kRk4, decay, 0.0, x.data(), 1, opt, nullptr).ok());
    errors.push_back(std::abs(x[0] - std::exp(-2.0)));
  }
  for (size_t i = 1; i < errors.size(); ++i) {
    const double order = std::log2(errors[i - 1] / errors[i]);
    INFO("h = " << 0.1 / (1 << (i - 1)) << " error " << errors[i - 1] << ", observed order " << order);
    CHECK(order == Approx(4.0).margin(0.1));
  }
  CHECK(errors[0] < 1e-6);
}

TEST_CASE("Fixed-size RK4 step converges with order 4 on the harmonic oscillator", "[rk4]") {
  std::vector<double> errors;
  const double t_end = 2 * kPi;
  for (int steps : {50, 100, 200, 400}) {
    double x[2] = {1.0, 0.0};
    const double h = t_end / steps;
    for (int k = 0; k < steps; ++k) rk4_step<2>(oscillator, k * h, h, x);
    errors.push_back(std::hypot(x[0] - 1.0, x[1]));
  }
  for (size_t i = 1; i < errors.size(); ++i) {
    const double order = std::log2(errors[i - 1] / errors[i]);
    INFO("error " << errors[i - 1] << " -> " << errors[i] << ", observed order " << order);
    CHECK(order == Approx(4.0).margin(0.1));
  }
}

TEST_CASE("RK4 step built without exceptions or the C++ library", "[rk4]") {
  double q = 0, v = 0;
  embedded_oscillator(2 * kPi / 100, 100, &q, &v);
  CHECK(std::hypot(q - 1.0, v) < 1e-6);  // one period of cos t
  CHECK(std::hypot(q - 1.0, v) > 0.0);
}

TEST_CASE("RK4 driver equals repeated fixed-size steps and ends exactly at t_end", "[rk4]") {
  IntegrationOptions opt;
  opt.t_end = 1.0;
  opt.dt = 0.3;  // not a divisor: the last step is 0.1
  std::vector<double> x = {1.0, 0.0};
  Recorded rec;
  const IntegrationResult r = record(Method::kRk4, oscillator, 0.0, x, opt, rec);
  REQUIRE(r.ok());
  REQUIRE(rec.t.size() == 5);
  CHECK(rec.t.back() == 1.0);
  CHECK(r.t == 1.0);
  CHECK(r.stats.accepted == 4);
  CHECK(r.stats.rhs_evals == 16);
  double y[2] = {1.0, 0.0};
  for (size_t k = 1; k < rec.t.size(); ++k) {
    rk4_step<2>(oscillator, rec.t[k - 1], rec.t[k] - rec.t[k - 1], y);
    CHECK(rec.x[k][0] == y[0]);
    CHECK(rec.x[k][1] == y[1]);
    CHECK(rec.x[k][0] == Approx(std::cos(rec.t[k])).margin(1e-4));
  }
}

TEST_CASE("DOPRI5 on the harmonic oscillator: accuracy, exact output grid, statistics", "[dopri5]") {
  IntegrationOptions opt;
  opt.t_end = 20.0;
  opt.dt = 0.1;
  opt.rtol = 1e-10;
  opt.atol = 1e-10;
  std::vector<double> x = {1.0, 0.0};
  Recorded rec;
  const IntegrationResult r = record(Method::kDopri5, oscillator, 0.0, x, opt, rec);
  REQUIRE(r.status == Status::kSuccess);
  REQUIRE(r.message.empty());
  REQUIRE(rec.t.size() == 201);
  double max_err = 0;
  for (size_t k = 0; k < rec.t.size(); ++k) {
    const double t_expected = k == 200 ? 20.0 : 0.1 * static_cast<double>(k);
    CHECK(rec.t[k] == t_expected);  // exactly the grid, no accumulated drift
    max_err =
        std::max(max_err, std::hypot(rec.x[k][0] - std::cos(rec.t[k]), rec.x[k][1] + std::sin(rec.t[k])));
  }
  INFO("max error " << max_err << " over " << r.stats.accepted << " accepted steps");
  CHECK(max_err < 20 * opt.rtol);
  CHECK(r.t == 20.0);
  CHECK(x[0] == rec.x.back()[0]);
  // FSAL: 6 evaluations per attempted step, plus the first and the one of the initial-step estimate.
  CHECK(r.stats.rhs_evals == 6 * (r.stats.accepted + r.stats.rejected) + 2);
  CHECK(r.stats.accepted > 20);
  CHECK(r.stats.rejected <= r.stats.accepted / 10 + 2);
}

TEST_CASE("DOPRI5 dense output: steps are not clipped to the output grid", "[dopri5]") {
  IntegrationOptions opt;
  opt.t_end = 10.0;
  opt.dt = 0.01;
  opt.rtol = 1e-6;
  opt.atol = 1e-6;
  std::vector<double> x = {1.0, 0.0};
  Recorded rec;
  const IntegrationResult r = record(Method::kDopri5, oscillator, 0.0, x, opt, rec);
  REQUIRE(r.ok());
  REQUIRE(rec.t.size() == 1001);
  double max_err = 0;
  for (size_t k = 0; k < rec.t.size(); ++k) {
    max_err = std::max(max_err, std::abs(rec.x[k][0] - std::cos(rec.t[k])));
  }
  INFO("max dense-output error " << max_err << " with " << r.stats.accepted << " steps for 1000 outputs");
  CHECK(r.stats.accepted < 200);  // far fewer steps than output intervals
  CHECK(max_err < 20 * opt.rtol);
}

TEST_CASE("DOPRI5 on an eccentric Kepler orbit: energy, period and dense output", "[dopri5]") {
  // The global error of an orbit is mostly phase error, growing with every
  // revolution; over one period it stays within ~100 rtol.
  const double e = 0.5;
  IntegrationOptions opt;
  opt.t_end = 2 * kPi;  // one period
  opt.dt = 0.05;
  opt.rtol = 1e-10;
  opt.atol = 1e-10;
  for (double beta : {0.04, 0.0}) {  // with and without PI control
    opt.pi_beta = beta;
    std::vector<double> s(4);
    kepler_exact(e, 0.0, s.data());
    const double energy0 = kepler_energy(s.data());
    REQUIRE(energy0 == Approx(-0.5).margin(1e-15));
    Recorded rec;
    const IntegrationResult r = record(Method::kDopri5, kepler, 0.0, s, opt, rec);
    REQUIRE(r.status == Status::kSuccess);
    double max_err = 0, max_energy_err = 0;
    for (size_t k = 0; k < rec.t.size(); ++k) {
      double exact[4];
      kepler_exact(e, rec.t[k], exact);
      max_err = std::max(max_err, std::hypot(rec.x[k][0] - exact[0], rec.x[k][1] - exact[1]));
      max_energy_err = std::max(max_energy_err, std::abs(kepler_energy(rec.x[k].data()) - energy0));
    }
    // After one period the orbit is back at periapsis (1 - e, 0).
    const double period_err = std::hypot(s[0] - (1 - e), s[1]);
    INFO("beta " << beta << ": max position error " << max_err << ", energy error " << max_energy_err
                 << ", periapsis error " << period_err << ", steps " << r.stats.accepted << "+"
                 << r.stats.rejected);
    CHECK(rec.t.size() == 127);
    CHECK(rec.t.back() == opt.t_end);
    CHECK(max_err < 200 * opt.rtol);
    CHECK(max_energy_err < 20 * opt.rtol);
    CHECK(period_err < 200 * opt.rtol);
    CHECK(r.stats.rhs_evals == 6 * (r.stats.accepted + r.stats.rejected) + 2);
  }
}

TEST_CASE("DOPRI5 local orders: step error ~h^6, dense output error ~h^5 or better", "[dopri5]") {
  // One accepted step of size h (loose tolerance) on the oscillator; the
  // dense output is sampled at 0.3 h, 0.6 h and 0.9 h.
  std::vector<double> step_err, dense_err;
  for (double h : {0.4, 0.2, 0.1, 0.05}) {
    IntegrationOptions opt;
    opt.t_end = h;
    opt.dt = 0.3 * h;
    opt.h0 = h;
    opt.rtol = opt.atol = 1.0;
    std::vector<double> x = {1.0, 0.0};
    double dense = 0;
    const IntegrationResult r =
        integrate(Method::kDopri5, oscillator, 0.0, x.data(), 2, opt, [&](double t, const double* xs) {
          if (t > 0 && t < h) dense = std::max(dense, std::abs(xs[0] - std::cos(t)));
          return true;
        });
    REQUIRE(r.stats.accepted == 1);
    step_err.push_back(std::abs(x[0] - std::cos(h)));
    dense_err.push_back(dense);
  }
  for (size_t i = 1; i < step_err.size(); ++i) {
    const double step_order = std::log2(step_err[i - 1] / step_err[i]);
    const double dense_order = std::log2(dense_err[i - 1] / dense_err[i]);
    INFO("step error " << step_err[i] << " order " << step_order << ", dense error " << dense_err[i]
                       << " order " << dense_order);
    CHECK(step_order == Approx(6.0).margin(0.15));
    CHECK(dense_order > 4.85);
  }
}

TEST_CASE("DOPRI5 error follows the tolerance", "[dopri5]") {
  std::vector<double> errors;
  for (double tol : {1e-6, 1e-8, 1e-10}) {
    IntegrationOptions opt;
    opt.t_end = 2 * kPi;
    opt.dt = 0.1;
    opt.rtol = opt.atol = tol;
    std::vector<double> s(4);
    kepler_exact(0.3, 0.0, s.data());
    REQUIRE(integrate(Method::kDopri5, kepler, 0.0, s.data(), 4, opt, nullptr).ok());
    double exact[4];
    kepler_exact(0.3, opt.t_end, exact);
    errors.push_back(std::hypot(s[0] - exact[0], s[1] - exact[1]));
    INFO("tol " << tol << " error " << errors.back());
    CHECK(errors.back() < 200 * tol);
  }
  CHECK(errors[1] < errors[0] / 10);
  CHECK(errors[2] < errors[1] / 10);
}

TEST_CASE("Observer can stop the run, trivial runs", "[integrate]") {
  IntegrationOptions opt;
  opt.t_end = 1.0;
  opt.dt = 0.1;
  for (Method m : {Method::kRk4, Method::kDopri5}) {
    std::vector<double> x = {1.0};
    int calls = 0;
    const IntegrationResult r = integrate(m, decay, 0.0, x.data(), 1, opt, [&](double t, const double*) {
      ++calls;
      return t < 0.25;
    });
    CHECK(r.status == Status::kStoppedByObserver);
    CHECK(r.ok());
    CHECK(calls == 4);  // 0, 0.1, 0.2, 0.3
    CHECK(x[0] == Approx(std::exp(-r.t)).epsilon(1e-6));
  }
  SECTION("t_end == t0: one output, no steps") {
    opt.t_end = 0.0;
    std::vector<double> x = {1.0};
    Recorded rec;
    const IntegrationResult r = record(Method::kDopri5, decay, 0.0, x, opt, rec);
    CHECK(r.status == Status::kSuccess);
    CHECK(rec.t == std::vector<double>{0.0});
    CHECK(r.stats.accepted == 0);
  }
  SECTION("empty state") {
    Recorded rec;
    std::vector<double> x;
    const Rhs nothing = [](double, const double*, double*) { return true; };
    const IntegrationResult r = record(Method::kDopri5, nothing, 0.0, x, opt, rec);
    CHECK(r.status == Status::kSuccess);
    CHECK(rec.t.size() == 11);
  }
}

TEST_CASE("A NaN from the right-hand side stops the run with the time and state", "[failure]") {
  const Rhs nan_late = [](double t, const double* x, double* xdot) {
    xdot[0] = t >= 0.55 ? std::nan("") : -x[0];
    return true;
  };
  IntegrationOptions opt;
  opt.t_end = 2.0;
  opt.dt = 0.1;
  opt.state_names = {"y"};
  SECTION("RK4: the failing stage is at t = 0.55, x keeps the state at 0.5") {
    std::vector<double> x = {1.0};
    Recorded rec;
    const IntegrationResult r = record(Method::kRk4, nan_late, 0.0, x, opt, rec);
    CHECK(r.status == Status::kNonFinite);
    CHECK_FALSE(r.ok());
    CHECK(r.message.find("d(y)/dt = nan") != std::string::npos);
    CHECK(time_in_message(r.message) == 0.55);
    CHECK(r.message.find("y=0.5") != std::string::npos);  // stage state, about exp(-0.55)
    CHECK(r.t == 0.5);
    CHECK(rec.t.size() == 6);
    CHECK(x[0] == rec.x.back()[0]);
  }
  SECTION("DOPRI5") {
    std::vector<double> x = {1.0};
    Recorded rec;
    const IntegrationResult r = record(Method::kDopri5, nan_late, 0.0, x, opt, rec);
    INFO(r.message);
    CHECK(r.status == Status::kNonFinite);
    CHECK(time_in_message(r.message) >= 0.55);
    CHECK(r.t < 0.55);
    CHECK(x[0] == Approx(std::exp(-r.t)).epsilon(1e-7));
    CHECK(rec.t.back() <= r.t);
  }
}

TEST_CASE("A right-hand side that fails or throws stops the run", "[failure]") {
  IntegrationOptions opt;
  opt.t_end = 1.0;
  const Rhs refuses = [](double t, const double* x, double* xdot) {
    xdot[0] = -x[0];
    return t < 0.5;
  };
  const Rhs throws = [](double t, const double* x, double* xdot) {
    if (t > 0.5) throw std::runtime_error("domain error");
    xdot[0] = -x[0];
    return true;
  };
  for (Method m : {Method::kRk4, Method::kDopri5}) {
    std::vector<double> x = {1.0};
    IntegrationResult r = integrate(m, refuses, 0.0, x.data(), 1, opt, nullptr);
    CHECK(r.status == Status::kRhsFailed);
    CHECK(r.message.find("right-hand side failed at t=") != std::string::npos);
    CHECK(time_in_message(r.message) >= 0.5);
    x = {1.0};
    r = integrate(m, throws, 0.0, x.data(), 1, opt, nullptr);
    CHECK(r.status == Status::kRhsFailed);
    CHECK(r.message.find("domain error") != std::string::npos);
  }
}

TEST_CASE("Finite-time blow-up ends in step-size underflow near the singularity", "[failure]") {
  // x' = x^2, x(0) = 1: x = 1 / (1 - t), infinite at t = 1.
  const Rhs blowup = [](double, const double* x, double* xdot) {
    xdot[0] = x[0] * x[0];
    return true;
  };
  IntegrationOptions opt;
  opt.t_end = 2.0;
  opt.dt = 0.25;
  std::vector<double> x = {1.0};
  Recorded rec;
  const IntegrationResult r = record(Method::kDopri5, blowup, 0.0, x, opt, rec);
  INFO(r.message);
  CHECK(r.status == Status::kStepSizeTooSmall);
  // The numerical singularity lags the exact one by the accumulated error.
  CHECK(r.t == Approx(1.0).margin(1e-6));
  CHECK(time_in_message(r.message) == Approx(r.t));
  CHECK(x[0] > 1e10);
  CHECK(rec.t.size() >= 4);  // 0, 0.25, 0.5, 0.75 and perhaps 1
  CHECK(rec.t.back() <= r.t);
}

TEST_CASE("Impossible tolerance and stiff problems fail cleanly", "[failure]") {
  SECTION("tolerance below round-off: step-size underflow") {
    IntegrationOptions opt;
    opt.t_end = 2.0;
    opt.rtol = 1e-300;
    opt.atol = 1e-300;
    std::vector<double> x = {1.0};
    const IntegrationResult r = integrate(Method::kDopri5, decay, 1.0, x.data(), 1, opt, nullptr);
    INFO(r.message);
    CHECK(r.status == Status::kStepSizeTooSmall);
    CHECK(r.message.find("cannot meet the tolerance") != std::string::npos);
    CHECK(r.t < 1.001);  // a few steps may pass where the error estimate rounds to zero
    CHECK(r.stats.rejected < 1000);
  }
  SECTION("stiff problem: max_steps") {
    // x' = -1e6 (x - cos t): explicit steps are limited by stability, not accuracy.
    const Rhs stiff = [](double t, const double* x, double* xdot) {
      xdot[0] = -1e6 * (x[0] - std::cos(t));
      return true;
    };
    IntegrationOptions opt;
    opt.t_end = 10.0;
    opt.max_steps = 2000;
    std::vector<double> x = {1.0};
    const IntegrationResult r = integrate(Method::kDopri5, stiff, 0.0, x.data(), 1, opt, nullptr);
    INFO(r.message);
    CHECK(r.status == Status::kMaxSteps);
    CHECK(r.message.find("max_steps = 2000") != std::string::npos);
    CHECK(r.stats.accepted + r.stats.rejected == 2000);
    CHECK(r.t < 0.1);
    CHECK(x[0] == Approx(std::cos(r.t)).margin(1e-5));  // it was tracking the slow solution
  }
  SECTION("RK4 counts steps too") {
    IntegrationOptions opt;
    opt.t_end = 1.0;
    opt.dt = 1e-3;
    opt.max_steps = 100;
    std::vector<double> x = {1.0};
    const IntegrationResult r = integrate(Method::kRk4, decay, 0.0, x.data(), 1, opt, nullptr);
    CHECK(r.status == Status::kMaxSteps);
    CHECK(r.t == Approx(0.1));
  }
}

TEST_CASE("Invalid arguments are reported, not thrown", "[failure]") {
  std::vector<double> x = {1.0};
  const auto status = [&](const IntegrationOptions& opt) {
    return integrate(Method::kDopri5, decay, 0.0, x.data(), 1, opt, nullptr).status;
  };
  IntegrationOptions opt;
  opt.dt = 0;
  CHECK(status(opt) == Status::kInvalidArgument);
  opt = {};
  opt.t_end = -1;
  CHECK(status(opt) == Status::kInvalidArgument);
  opt = {};
  opt.rtol = opt.atol = 0;
  CHECK(status(opt) == Status::kInvalidArgument);
  opt = {};
  opt.atol_per_component = {1e-8, 1e-8};
  CHECK(status(opt) == Status::kInvalidArgument);
  opt = {};
  x = {std::nan("")};
  CHECK(status(opt) == Status::kNonFinite);
}

TEST_CASE("Method names", "[integrate]") {
  Method m = Method::kRk4;
  CHECK(parse_method("dopri5", &m));
  CHECK(m == Method::kDopri5);
  CHECK(parse_method("rk4", &m));
  CHECK(m == Method::kRk4);
  CHECK_FALSE(parse_method("euler", &m));
  CHECK(std::string(method_name(Method::kDopri5)) == "dopri5");
}
