// SPDX-License-Identifier: GPL-2.0-or-later
// The adaptive implicit method (CVODE BDF) and the state Jacobian it uses,
// on hand-written models with exact Jacobians: a stiff scalar ODE and a
// stiff two-mass chain against their analytic solutions, a cart pendulum
// (M(q), velocity terms, a prescribed coordinate) against finite
// differences, and the runner's command line (--integrator implicit,
// --stats, a model without Jacobians).
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <string>
#include <vector>

#include "kanegen/runtime/driver.hpp"
#include "kanegen/runtime/integrators.hpp"
#include "kanegen/runtime/model.hpp"
#include "kanegen/runtime/state_jacobian.hpp"
#include "kanegen/runtime/text.hpp"

namespace {

using namespace kanegen::runtime;

// ------------------------------------------------------------ models

const char* const kNames2[] = {"a", "b"};
const char* const kSpeeds2[] = {"a_dot", "b_dot"};
const char* const kNoNames[] = {""};

// A table with the bookkeeping every hand-written model shares; the kernels
// are filled in by the model. Params: none (one unused double).
ModelTable base_table(const char* name) {
  ModelTable t{};
  t.name = name;
  t.nq = t.nu = 2;
  t.ntau = 0;
  t.ny = 0;
  t.np = 0;
  t.coordinate_names = kNames2;
  t.speed_names = kSpeeds2;
  t.input_names = kNoNames;
  t.output_names = kNoNames;
  t.parameter_names = kNoNames;
  t.parameters_size = sizeof(double);
  t.default_parameters = [](void*) {};
  t.set_parameter = [](void*, const char*, double) { return false; };
  t.get_parameter = [](const void*, int) { return 0.0; };
  t.coordinate_rates = [](const double*, const double* u, double* qdot) {
    qdot[0] = u[0];
    qdot[1] = u[1];
  };
  t.outputs = [](const void*, double, const double*, const double*, double*) {};
  return t;
}

// Two unit masses on a line: a soft spring (k1) from the wall to mass a, a
// stiff one (k2) between a and b. M = I, f = -K q, K = [[k1 + k2, -k2], [-k2, k2]].
constexpr double kSoft = 1.0, kStiff = 1e6;
constexpr double kK[2][2] = {{kSoft + kStiff, -kStiff}, {-kStiff, kStiff}};

// The slow mode of K (the smaller eigenvalue of a symmetric 2x2), to start on.
struct Mode {
  double omega, v[2];
};
Mode slow_mode() {
  const double tr = kK[0][0] + kK[1][1], det = kK[0][0] * kK[1][1] - kK[0][1] * kK[1][0];
  const double lambda = 0.5 * tr - std::sqrt(0.25 * tr * tr - det);
  Mode m{std::sqrt(lambda), {-kK[0][1], kK[0][0] - lambda}};
  const double norm = std::hypot(m.v[0], m.v[1]);
  m.v[0] /= norm;
  m.v[1] /= norm;
  return m;
}

const double* chain_q0() {
  static const Mode m = slow_mode();
  static const double q[2] = {0.1 * m.v[0], 0.1 * m.v[1]};
  return q;
}
const double kZero2[2] = {0.0, 0.0};

ModelTable chain_table(bool with_jacobians) {
  ModelTable t = base_table("stiff_chain");
  t.q0 = chain_q0();
  t.u0 = kZero2;
  t.initial_state = [](const void*, double* q, double* u) {
    q[0] = chain_q0()[0], q[1] = chain_q0()[1];
    u[0] = u[1] = 0.0;
  };
  t.mass_matrix = [](const void*, const double*, double* M) { M[0] = M[3] = 1.0, M[1] = M[2] = 0.0; };
  t.forcing = [](const void*, double, const double* q, const double*, const double*, double* f) {
    for (int i = 0; i < 2; ++i) f[i] = -kK[i][0] * q[0] - kK[i][1] * q[1];
  };
  t.forward_dynamics = [](const void*, double, const double* q, const double*, const double*, double* udot) {
    for (int i = 0; i < 2; ++i) udot[i] = -kK[i][0] * q[0] - kK[i][1] * q[1];
    return 0;
  };
  t.kinetic_energy = [](const void*, const double*, const double* u) {
    return 0.5 * (u[0] * u[0] + u[1] * u[1]);
  };
  t.potential_energy = [](const void*, const double* q) {
    return 0.5 * (kSoft * q[0] * q[0] + kStiff * (q[1] - q[0]) * (q[1] - q[0]));
  };
  if (with_jacobians) {
    t.forcing_jacobian = [](const void*, double, const double*, const double*, const double*, double* dfdq,
                            double* dfdu) {
      for (int i = 0; i < 4; ++i) dfdq[i] = -kK[i / 2][i % 2], dfdu[i] = 0.0;
    };
    t.mass_matrix_product_jacobian = [](const void*, const double*, const double*, double* dMa) {
      for (int i = 0; i < 4; ++i) dMa[i] = 0.0;
    };
  }
  return t;
}

// A cart (x, spring k to the wall) carrying a pendulum (theta), both
// nonlinear in M(q) and f(q, u):
//   M = [[mc + mp, mp l c], [mp l c, mp l^2]],
//   f = [mp l s w^2 - k x, -mp g l s]   (c = cos theta, s = sin theta, w = theta').
// With the cart prescribed (role 2) to x = A sin(W t).
constexpr double mc = 2.0, mp = 0.5, l = 0.7, g = 9.81, k = 400.0, A = 0.05, W = 3.0;
const int kFreeRoles[] = {0, 0};
const int kPrescribedRoles[] = {2, 0};
const double kCartQ0[2] = {0.0, 0.8};
const double kCartU0[2] = {0.0, 0.3};

void cart_mass(const double* q, double* M) {
  M[0] = mc + mp;
  M[1] = M[2] = mp * l * std::cos(q[1]);
  M[3] = mp * l * l;
}
void cart_forcing(const double* q, const double* u, double* f) {
  f[0] = mp * l * std::sin(q[1]) * u[1] * u[1] - k * q[0];
  f[1] = -mp * g * l * std::sin(q[1]);
}

ModelTable cart_table(bool prescribed) {
  ModelTable t = base_table(prescribed ? "driven_cart_pendulum" : "cart_pendulum");
  t.q0 = kCartQ0;
  t.u0 = kCartU0;
  t.coordinate_roles = prescribed ? kPrescribedRoles : kFreeRoles;
  t.initial_state = [](const void*, double* q, double* u) {
    q[0] = kCartQ0[0], q[1] = kCartQ0[1], u[0] = kCartU0[0], u[1] = kCartU0[1];
  };
  t.mass_matrix = [](const void*, const double* q, double* M) { cart_mass(q, M); };
  t.forcing = [](const void*, double, const double* q, const double* u, const double*, double* f) {
    cart_forcing(q, u, f);
  };
  if (prescribed) {
    t.initial_state = [](const void*, double* q, double* u) {
      q[0] = 0.0, q[1] = kCartQ0[1], u[0] = A * W, u[1] = kCartU0[1];
    };
    t.forward_dynamics = [](const void*, double tt, const double* q, const double* u, const double*,
                            double* udot) {
      double M[4], f[2];
      cart_mass(q, M);
      cart_forcing(q, u, f);
      udot[0] = -A * W * W * std::sin(W * tt);
      udot[1] = (f[1] - M[2] * udot[0]) / M[3];
      return 0;
    };
  } else {
    t.forward_dynamics = [](const void*, double, const double* q, const double* u, const double*,
                            double* udot) {
      double M[4], f[2];
      cart_mass(q, M);
      cart_forcing(q, u, f);
      const double det = M[0] * M[3] - M[1] * M[2];
      udot[0] = (M[3] * f[0] - M[1] * f[1]) / det;
      udot[1] = (M[0] * f[1] - M[2] * f[0]) / det;
      return 0;
    };
  }
  t.kinetic_energy = [](const void*, const double* q, const double* u) {
    double M[4];
    cart_mass(q, M);
    return 0.5 * (M[0] * u[0] * u[0] + 2 * M[1] * u[0] * u[1] + M[3] * u[1] * u[1]);
  };
  t.potential_energy = [](const void*, const double* q) {
    return 0.5 * k * q[0] * q[0] - mp * g * l * std::cos(q[1]);
  };
  t.forcing_jacobian = [](const void*, double, const double* q, const double* u, const double*, double* dfdq,
                          double* dfdu) {
    const double c = std::cos(q[1]), s = std::sin(q[1]);
    dfdq[0] = -k, dfdq[1] = mp * l * c * u[1] * u[1];
    dfdq[2] = 0.0, dfdq[3] = -mp * g * l * c;
    dfdu[0] = 0.0, dfdu[1] = 2 * mp * l * s * u[1];
    dfdu[2] = dfdu[3] = 0.0;
  };
  t.mass_matrix_product_jacobian = [](const void*, const double* q, const double* a, double* dMa) {
    const double s = std::sin(q[1]);
    dMa[0] = 0.0, dMa[1] = -mp * l * s * a[1];
    dMa[2] = 0.0, dMa[3] = -mp * l * s * a[0];
  };
  return t;
}

// ------------------------------------------------------------ helpers

// d(x')/dx by central differences of forward_dynamics: the reference for StateJacobian.
std::vector<double> finite_difference_jacobian(const Model& model, double t, std::vector<double> x) {
  const int m = model.info().nu, n = 2 * m;
  std::vector<double> J(static_cast<size_t>(n) * n, 0.0), ap(m), am(m);
  for (int i = 0; i < m; ++i) J[i * n + m + i] = 1.0;
  for (int j = 0; j < n; ++j) {
    const double h = 1e-6 * std::max(1.0, std::abs(x[j])), keep = x[j];
    x[j] = keep + h;
    model.forward_dynamics(t, x.data(), x.data() + m, nullptr, ap.data());
    x[j] = keep - h;
    model.forward_dynamics(t, x.data(), x.data() + m, nullptr, am.data());
    x[j] = keep;
    for (int i = 0; i < m; ++i) J[(m + i) * n + j] = (ap[i] - am[i]) / (2 * h);
  }
  return J;
}

struct Outcome {
  int code;
  std::string out, err;
};

std::string read_all(std::FILE* f) {
  std::string s;
  std::rewind(f);
  char buf[4096];
  for (size_t got; (got = std::fread(buf, 1, sizeof buf, f)) > 0;) s.append(buf, got);
  std::fclose(f);
  return s;
}

Outcome run(Model& model, std::vector<std::string> args) {
  args.insert(args.begin(), "runner");
  std::FILE* out = std::tmpfile();
  std::FILE* err = std::tmpfile();
  REQUIRE(out);
  REQUIRE(err);
  const int code = run_model(model, args, out, err);
  return {code, read_all(out), read_all(err)};
}

// The CSV's rows as numbers (header skipped).
std::vector<std::vector<double>> rows(const std::string& csv) {
  std::vector<std::vector<double>> table;
  std::istringstream in(csv);
  std::string line;
  std::getline(in, line);
  while (std::getline(in, line)) {
    std::vector<double> v;
    REQUIRE(parse_number_list(line, &v));
    table.push_back(v);
  }
  return table;
}

// The value of "key=N" in a stats line.
long stat(const std::string& text, const std::string& key) {
  const size_t at = text.find(" " + key + "=");
  REQUIRE(at != std::string::npos);
  return std::stol(text.substr(at + key.size() + 2));
}

}  // namespace

// ------------------------------------------------------------ tests

TEST_CASE("implicit: stiff scalar ODE against its exact solution, in few steps", "[implicit]") {
  const Method method = GENERATE(Method::kRadau, Method::kBdf);
  INFO(method_name(method));
  // x' = -K (x - cos t), x(0) = 1: x = (K^2 cos t + K sin t) / (K^2 + 1) + e^{-K t} / (K^2 + 1).
  constexpr double K = 1e6;
  const Rhs rhs = [](double t, const double* x, double* xdot) {
    xdot[0] = -K * (x[0] - std::cos(t));
    return true;
  };
  const Jacobian jac = [](double, const double*, double* J) {
    J[0] = -K;
    return true;
  };
  const auto exact = [](double t) {
    return (K * K * std::cos(t) + K * std::sin(t) + std::exp(-K * t)) / (K * K + 1);
  };
  IntegrationOptions opt;
  opt.t_end = 10.0;
  opt.dt = 0.5;
  opt.rtol = 1e-8;
  opt.atol = 1e-10;
  opt.max_order = 5;  // smooth and non-oscillatory: the high orders pay
  std::vector<double> x = {1.0};
  double worst = 0.0;
  int outputs = 0;
  const Observer observer = [&](double t, const double* xs) {
    worst = std::max(worst, std::abs(xs[0] - exact(t)));
    ++outputs;
    return true;
  };
  const IntegrationResult r = integrate(method, rhs, 0.0, x.data(), 1, opt, observer, jac);
  INFO(r.message);
  REQUIRE(r.status == Status::kSuccess);
  CHECK(r.t == 10.0);
  CHECK(outputs == 21);
  // Radau's step ends are of order 5 (here 3e-11 after steps of 0.5), its
  // rows between them come from the collocation polynomial, of order 3
  // (5e-4 here): docs/runtime.md.
  CHECK(std::abs(x[0] - exact(10.0)) < 1e-9);
  CHECK(worst < (method == Method::kRadau ? 1e-3 : 1e-6));
  // DOPRI5 needs ~ K t / 3.3 = 3e6 steps here (tests/runtime/integrators_test.cpp).
  CHECK(r.stats.accepted < 2000);
  CHECK(r.stats.newton_iterations >= r.stats.accepted);
  CHECK(r.stats.jacobian_evaluations > 0);
  CHECK(r.stats.factorizations >= r.stats.jacobian_evaluations);
}

TEST_CASE("implicit: needs a Jacobian, and genalpha is not an ODE method", "[implicit]") {
  const Rhs rhs = [](double, const double* x, double* xdot) {
    xdot[0] = -x[0];
    return true;
  };
  IntegrationOptions opt;
  std::vector<double> x = {1.0};
  for (const Method method : {Method::kImplicit, Method::kRadau, Method::kBdf}) {
    const IntegrationResult r = integrate(method, rhs, 0.0, x.data(), 1, opt, nullptr);
    CHECK(r.status == Status::kInvalidArgument);
    CHECK(r.message.find("Jacobian") != std::string::npos);
  }
  IntegrationResult r = integrate(Method::kImplicit, rhs, 0.0, x.data(), 1, opt, nullptr);
  r = integrate(Method::kGenAlpha, rhs, 0.0, x.data(), 1, opt, nullptr);
  CHECK(r.status == Status::kInvalidArgument);
  Method m = Method::kRk4;
  CHECK(parse_method("implicit", &m));
  CHECK(m == Method::kImplicit);
  CHECK(parse_method("genalpha", &m));
  CHECK(m == Method::kGenAlpha);
  CHECK(std::string(method_name(Method::kImplicit)) == "implicit");
  CHECK(parse_method("radau", &m));
  CHECK(m == Method::kRadau);
  CHECK(parse_method("bdf", &m));
  CHECK(m == Method::kBdf);
  // bench/implicit.py: Radau is the faster on the stiff models.
  CHECK(implicit_method() == Method::kRadau);
}

TEST_CASE("implicit: a failing step names the time and state, and the rows before it stay", "[implicit]") {
  const Method method = GENERATE(Method::kRadau, Method::kBdf);
  INFO(method_name(method));
  // x' = x^2 blows up at t = 1: the step size falls to its minimum there.
  const Rhs rhs = [](double, const double* x, double* xdot) {
    xdot[0] = x[0] * x[0];
    return true;
  };
  const Jacobian jac = [](double, const double* x, double* J) {
    J[0] = 2 * x[0];
    return true;
  };
  IntegrationOptions opt;
  opt.t_end = 2.0;
  opt.dt = 0.25;
  opt.state_names = {"y"};
  std::vector<double> x = {1.0};
  std::vector<double> times;
  const IntegrationResult r = integrate(
      method, rhs, 0.0, x.data(), 1, opt,
      [&](double t, const double*) {
        times.push_back(t);
        return true;
      },
      jac);
  INFO(r.message);
  CHECK_FALSE(r.ok());
  // CVODE stops short of t = 1; Radau's implicit stages have solutions a
  // little past the pole, and it stops within 1e-10 after it.
  CHECK(r.t < (method == Method::kRadau ? 1.0 + 1e-10 : 1.0));
  CHECK(r.t > 0.99);
  CHECK(r.message.find(" at t=") != std::string::npos);
  CHECK(r.message.find("y=") != std::string::npos);
  CHECK(times.size() == (method == Method::kRadau ? 5u : 4u));  // 0, 0.25, 0.5, 0.75 (and 1)
}

TEST_CASE("state Jacobian: exact kernels against finite differences of the accelerations", "[implicit]") {
  for (const bool prescribed : {false, true}) {
    const Model model(cart_table(prescribed));
    StateJacobian jacobian(model);
    const std::vector<double> x = {0.03, 1.1, -0.4, 2.3};
    std::vector<double> J(16);
    REQUIRE(jacobian.evaluate(0.37, x.data(), nullptr, J.data()));
    const std::vector<double> reference = finite_difference_jacobian(model, 0.37, x);
    for (int i = 0; i < 16; ++i) {
      INFO("prescribed " << prescribed << ", entry " << i);
      CHECK(J[i] == Approx(reference[i]).epsilon(1e-6).margin(1e-6));
    }
    if (prescribed)  // the prescribed acceleration depends on t only
      for (int j = 0; j < 4; ++j) CHECK(J[2 * 4 + j] == 0.0);
  }
}

TEST_CASE("implicit: the stiff chain on its slow mode, against the analytic solution", "[implicit]") {
  // implicit selects radau, which ignores --max-order.
  const std::string method = GENERATE(std::string("implicit"), std::string("bdf"));
  INFO(method);
  Model model(chain_table(true));
  const Mode mode = slow_mode();
  // The stiff mode is not excited: the high orders pay (--max-order 5).
  const Outcome o = run(model, {"simulate", "--t-end", "10", "--dt", "0.5", "--integrator", method,
                                "--max-order", "5", "--rtol", "1e-9", "--atol", "1e-12", "--stats"});
  INFO(o.err);
  REQUIRE(o.code == 0);
  const auto table = rows(o.out);
  REQUIRE(table.size() == 21);
  double worst = 0.0;
  for (const auto& row : table) {
    const double amplitude = 0.1 * std::cos(mode.omega * row[0]);
    worst =
        std::max({worst, std::abs(row[1] - amplitude * mode.v[0]), std::abs(row[2] - amplitude * mode.v[1])});
  }
  CHECK(worst < 1e-5);
  CHECK(table.back()[0] == 10.0);
  // The stiff mode (omega = 1414 rad/s) limits an explicit step to ~2e-3 s:
  // 5000 steps for 10 s. The implicit method follows the slow one.
  CHECK(o.err.find(method == "bdf" ? "stats: integrator=bdf " : "stats: integrator=radau ") !=
        std::string::npos);
  CHECK(stat(o.err, "accepted") < 1500);
  CHECK(stat(o.err, "newton_iterations") > 0);
  CHECK(stat(o.err, "jacobian_evals") > 0);
  CHECK(stat(o.err, "lu_factorizations") > 0);
}

TEST_CASE("implicit: the driven cart pendulum follows DOPRI5", "[implicit]") {
  Model model(cart_table(true));
  const std::vector<std::string> common = {"simulate", "--t-end", "3",      "--dt", "0.1",
                                           "--rtol",   "1e-10",   "--atol", "1e-12"};
  std::vector<std::string> implicit = common, explicit_ = common;
  implicit.insert(implicit.end(), {"--integrator", GENERATE("radau", "bdf")});
  const Outcome a = run(model, implicit), b = run(model, explicit_);
  INFO(a.err << b.err);
  REQUIRE(a.code == 0);
  REQUIRE(b.code == 0);
  const auto ra = rows(a.out), rb = rows(b.out);
  REQUIRE(ra.size() == rb.size());
  for (size_t i = 0; i < ra.size(); ++i) {
    CHECK(ra[i][1] == Approx(A * std::sin(W * ra[i][0])).margin(1e-6));  // the prescribed cart
    for (int j = 1; j <= 4; ++j) CHECK(ra[i][j] == Approx(rb[i][j]).margin(2e-6));
  }
}

TEST_CASE("implicit: a model without Jacobian kernels is refused, saying how to get them", "[implicit]") {
  Model model(chain_table(false));
  for (const char* method : {"implicit", "genalpha"}) {
    const Outcome o = run(model, {"simulate", "--t-end", "1", "--integrator", method});
    INFO(o.err);
    CHECK(o.code == 2);
    CHECK(o.out.empty());
    CHECK(o.err.find("no Jacobian kernels") != std::string::npos);
    CHECK(o.err.find("--jacobians") != std::string::npos);
  }
  CHECK_THROWS_WITH(StateJacobian(model), Catch::Contains("--jacobians"));
}

TEST_CASE("genalpha through the runner: a row per step, the slow mode, its statistics",
          "[implicit][genalpha]") {
  Model model(chain_table(true));
  const Mode mode = slow_mode();
  const Outcome o = run(model, {"simulate", "--t-end", "2", "--dt", "0.001", "--integrator", "genalpha",
                                "--rho-inf", "0.8", "--stats"});
  INFO(o.err);
  REQUIRE(o.code == 0);
  const auto table = rows(o.out);
  REQUIRE(table.size() == 2001);
  CHECK(table.back()[0] == Approx(2.0));
  // Second order: the phase error after 2 s at omega h = 7e-4 is ~1e-7 of the amplitude.
  for (const auto& row : table)
    CHECK(row[1] == Approx(0.1 * std::cos(mode.omega * row[0]) * mode.v[0]).margin(1e-5));
  CHECK(o.err.find("stats: integrator=genalpha accepted=2000 rejected=0") != std::string::npos);
  CHECK(stat(o.err, "newton_iterations") >= 2000);
  CHECK(stat(o.err, "lu_factorizations") > 0);
}

TEST_CASE("genalpha: t_end must be a whole number of steps, and rho_inf at most 1", "[implicit][genalpha]") {
  Model model(chain_table(true));
  Outcome o = run(model, {"simulate", "--t-end", "1.0005", "--dt", "0.001", "--integrator", "genalpha"});
  CHECK(o.code == 2);
  CHECK(o.out.empty());
  CHECK(o.err.find("whole number of steps") != std::string::npos);
  o = run(model, {"simulate", "--t-end", "1", "--integrator", "genalpha", "--rho-inf", "1.5"});
  CHECK(o.code == 2);
  CHECK(o.err.find("--rho-inf") != std::string::npos);
}

// Every row of the registry (methods.hpp) through the runner, so that a new
// method is run here without a line of its own: a row per output time and
// its --stats line under the name of the method that ran (an alias's target).
TEST_CASE("every registered method simulates the chain through the runner", "[implicit][methods]") {
  Model model(chain_table(true));
  for (const MethodSpec& m : kMethods) {
    INFO(m.name);
    // dt below the stiff mode's stability limit (omega = 1414 rad/s) for rk4.
    const Outcome o = run(model, {"simulate", "--t-end", "0.01", "--dt", "0.001", "--integrator", m.name,
                                  "--rtol", "1e-6", "--atol", "1e-9", "--stats"});
    INFO(o.err);
    REQUIRE(o.code == 0);
    const auto table = rows(o.out);
    REQUIRE(table.size() == 11);
    CHECK(table.back()[0] == 0.01);
    CHECK(o.err.find(std::string("stats: integrator=") + resolved_spec(m.method).name + " ") !=
          std::string::npos);
  }
}
