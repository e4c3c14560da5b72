// SPDX-License-Identifier: GPL-2.0-or-later
// The numeric derivation (generator/numeric) on its own, against closed
// forms: the simple pendulum, the forced cart pendulum of
// tests/regression/test_forced_cart_pendulum.cpp, joint frames turned by rpy,
// a prismatic joint in a rotated frame; and its own consistency (M is the
// Hessian of its kinetic energy in u).
#include <catch2/catch.hpp>
#include <cmath>
#include <random>

#include "model/expression_eval.hpp"
#include "model/load.hpp"
#include "numeric/dual.hpp"
#include "numeric/dynamics.hpp"
#include "numeric/finite_difference.hpp"
#include "numeric/instance.hpp"
#include "numeric/loops.hpp"

namespace {

using kanegen::model::Model;
using kanegen::numeric::Evaluation;
using kanegen::numeric::State;

constexpr double kPi = 3.14159265358979323846;

Model load(const std::string& relative) {
  return kanegen::model::load_model(std::string(KANEGEN_SOURCE_DIR) + "/" + relative);
}

State state(std::vector<double> q, std::vector<double> u, std::vector<double> tau) {
  State s;
  s.q = std::move(q);
  s.u = std::move(u);
  s.tau = std::move(tau);
  return s;
}

/// A body with one joint, built in code: rpy-turned joint frame, given axis and type.
Model one_joint(const std::string& type, std::array<double, 3> axis, std::array<double, 3> rpy) {
  using kanegen::model::Scalar;
  Model m;
  m.name = "one";
  m.gravity = {Scalar::number(0), Scalar::number(0), Scalar::number(0)};
  kanegen::model::Body b;
  b.name = "b";
  b.mass = Scalar::number(2.0);
  b.com = {Scalar::number(0.3), Scalar::number(0), Scalar::number(0)};
  b.inertia = {Scalar::number(0.1), Scalar::number(0.2), Scalar::number(0.4),
               Scalar::number(0),   Scalar::number(0),   Scalar::number(0)};
  m.bodies.push_back(b);
  kanegen::model::Joint j;
  j.name = "j";
  j.type = type == "prismatic" ? kanegen::model::JointType::prismatic : kanegen::model::JointType::revolute;
  j.parent = "ground";
  j.child = "b";
  j.origin_xyz = {Scalar::number(1), Scalar::number(2), Scalar::number(3)};
  j.origin_rpy = {Scalar::number(rpy[0]), Scalar::number(rpy[1]), Scalar::number(rpy[2])};
  j.axis = axis;
  j.spring_stiffness = j.spring_rest = j.damping = Scalar::number(0);
  m.joints.push_back(j);
  kanegen::model::Output o;
  o.name = "com";
  o.body = "b";
  o.point = b.com;
  m.outputs.push_back(o);
  return m;
}

}  // namespace

TEST_CASE("dual numbers differentiate products, quotients, sin and cos, nested ones twice", "[numeric]") {
  using D1 = kanegen::numeric::Dual<double>;
  using D2 = kanegen::numeric::Dual<D1>;
  const double x = 0.7;
  // f(x) = sin(x) x^2 / (1 + x), f'(x) by the quotient rule.
  const D1 xd(x, 1.0);
  const D1 f = sin(xd) * xd * xd / (1.0 + xd);
  const double g = std::sin(x) * x * x, dg = std::cos(x) * x * x + 2 * x * std::sin(x);
  CHECK(f.v == Approx(g / (1 + x)));
  CHECK(f.d == Approx((dg * (1 + x) - g) / ((1 + x) * (1 + x))));
  // Second derivative of cos(x) * x: -cos(x) x - 2 sin(x).
  const D2 y(D1(x, 1.0), D1(1.0, 0.0));
  const D2 h = cos(y) * y;
  CHECK(h.d.d == Approx(-std::cos(x) * x - 2 * std::sin(x)));
  CHECK(h.v.d == Approx(h.d.v));
}

TEST_CASE("model expressions evaluate as GiNaC reads them", "[numeric][expression]") {
  const kanegen::model::ParameterValues p{{"m1", 2.0}, {"l1", 3.0}, {"a", 1.5}, {"b", 4.0}};
  using kanegen::model::evaluate_expression;
  CHECK(evaluate_expression("m1*l1^2/12", p) == Approx(1.5));
  CHECK(evaluate_expression("-a^2", p) == Approx(-2.25));
  CHECK(evaluate_expression("-a*b + m1", p) == Approx(-4.0));
  CHECK(evaluate_expression("b/m1/2", p) == Approx(1.0));
  CHECK(evaluate_expression("a - b - m1", p) == Approx(-4.5));
  CHECK(evaluate_expression("(a^b)^0.5", p) == Approx(std::pow(1.5, 2.0)));
  CHECK(evaluate_expression("sqrt(b) + sin(pi/2) + cos(0) + tan(0) + exp(0) + log(1)", p) == Approx(5.0));
  CHECK(evaluate_expression(" .5 + 1e-3 + 2E+1 ", p) == Approx(20.501));
  CHECK(evaluate_expression("a*(-b)", p) == Approx(-6.0));
  CHECK_THROWS_WITH(evaluate_expression("m1 + m2", p), Catch::Contains("unknown name 'm2'"));
  CHECK_THROWS_AS(evaluate_expression("m1 +", p), std::invalid_argument);
  CHECK(kanegen::model::evaluate(kanegen::model::Scalar::number(4.5), p) == 4.5);
}

TEST_CASE("simple pendulum: M = m l^2, f = -m g l sin q + tau, the energies", "[numeric]") {
  const Model model = load("models/simple_pendulum.json");
  const kanegen::model::ParameterValues p{{"m", 1.3}, {"l", 0.7}, {"g", 9.5}};
  const auto instance = kanegen::numeric::instantiate(model, p);
  REQUIRE(instance.coordinates() == 1);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> any(-3, 3);
  for (int k = 0; k < 20; ++k) {
    const double q = any(rng), u = any(rng), tau = any(rng);
    const Evaluation e = kanegen::numeric::evaluate(instance, state({q}, {u}, {tau}));
    const double m = 1.3, l = 0.7, g = 9.5;
    CHECK(e.mass_matrix[0] == Approx(m * l * l).epsilon(1e-14));
    CHECK(e.forcing[0] == Approx(-m * g * l * std::sin(q) + tau).margin(1e-13));
    CHECK(e.udot[0] == Approx((-m * g * l * std::sin(q) + tau) / (m * l * l)).margin(1e-13));
    CHECK(e.kinetic_energy == Approx(0.5 * m * l * l * u * u).epsilon(1e-14));
    CHECK(e.potential_energy == Approx(-m * g * l * std::cos(q)).margin(1e-13));
    CHECK(e.nonconservative_power == Approx(tau * u).margin(1e-13));
    REQUIRE(e.outputs.size() == 4);
    CHECK(e.outputs[0] == Approx(-l * std::sin(q)).margin(1e-15));
    CHECK(e.outputs[1] == Approx(0).margin(1e-15));
    CHECK(e.outputs[2] == Approx(-l * std::cos(q)).margin(1e-15));
    CHECK(e.outputs[3] == q);
  }
}

TEST_CASE("forced cart pendulum: prismatic + revolute, spring, damper, world and body forces", "[numeric]") {
  // Closed form (tests/regression/test_forced_cart_pendulum.cpp): cart x, angle q about +y, bob at
  // (x - l sin q, 0, -l cos q); world force (fx, 0, fz) and body force (b, 0, 0) at the bob.
  const Model model = load("tests/data/models/forced_cart_pendulum.json");
  const auto p = kanegen::model::default_parameter_values(model);
  const auto instance = kanegen::numeric::instantiate(model, p);
  const double mc = p.at("m_cart"), m = p.at("m"), l = p.at("l"), g = p.at("g"), k = p.at("k"), c = p.at("c"),
               rest = p.at("rest"), fx = p.at("fx"), fz = p.at("fz"), b = p.at("b");
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> any(-3, 3);
  for (int sample = 0; sample < 20; ++sample) {
    const std::vector<double> q{any(rng), any(rng)}, u{any(rng), any(rng)}, tau{any(rng), any(rng)};
    const double s = std::sin(q[1]), co = std::cos(q[1]), qd = u[1];
    const Evaluation e = kanegen::numeric::evaluate(instance, state(q, u, tau));
    INFO("sample " << sample);
    CHECK(e.mass_matrix[0] == Approx(mc + m).epsilon(1e-14));
    CHECK(e.mass_matrix[1] == Approx(-m * l * co).margin(1e-14));
    CHECK(e.mass_matrix[2] == Approx(-m * l * co).margin(1e-14));
    CHECK(e.mass_matrix[3] == Approx(m * l * l).epsilon(1e-14));
    CHECK(e.forcing[0] == Approx(-m * l * s * qd * qd + fx + b * co + tau[0]).margin(1e-13));
    CHECK(e.forcing[1] ==
          Approx(-m * g * l * s - fx * l * co + fz * l * s - b * l - k * (q[1] - rest) - c * qd + tau[1])
              .margin(1e-13));
    CHECK(e.potential_energy == Approx(-m * g * l * co + 0.5 * k * (q[1] - rest) * (q[1] - rest) +
                                       fx * l * s + fz * l * co - fx * q[0])
                                    .margin(1e-13));
    const double vx = u[0] - l * co * qd, vz = l * s * qd;
    CHECK(e.kinetic_energy == Approx(0.5 * mc * u[0] * u[0] + 0.5 * m * (vx * vx + vz * vz)).margin(1e-13));
    // Dampers, inputs and the body-frame thrust (b cos q, 0, -b sin q) at the bob.
    const double power = -c * qd * qd + tau[0] * u[0] + tau[1] * qd + b * co * u[0] - b * l * qd;
    CHECK(e.nonconservative_power == Approx(power).margin(1e-13));
    CHECK(kanegen::numeric::nonconservative_power(instance, state(q, u, tau)) == Approx(power).margin(1e-13));
    CHECK(e.outputs[0] == Approx(q[0] - l * s).margin(1e-14));
    CHECK(e.outputs[2] == Approx(-l * co).margin(1e-14));
  }
}

TEST_CASE("joint frames: rpy turns the axis, inertia about it, prismatic slides in the turned frame",
          "[numeric]") {
  // roll = pi/2 takes the joint's z axis to world -y; the body turns about it.
  const auto revolute = kanegen::numeric::instantiate(one_joint("revolute", {0, 0, 1}, {kPi / 2, 0, 0}), {});
  const double q = 0.4;
  const Evaluation e = kanegen::numeric::evaluate(revolute, state({q}, {1.5}, {0}));
  // M = m a^2 + izz; T = M u^2 / 2.
  CHECK(e.mass_matrix[0] == Approx(2.0 * 0.09 + 0.4).epsilon(1e-14));
  CHECK(e.kinetic_energy == Approx(0.5 * (2.0 * 0.09 + 0.4) * 1.5 * 1.5).epsilon(1e-14));
  // The COM starts along world x (roll keeps x) and turns about -y: (a cos q, 0, a sin q) + origin.
  CHECK(e.outputs[0] == Approx(1 + 0.3 * std::cos(q)).epsilon(1e-14));
  CHECK(e.outputs[1] == Approx(2).epsilon(1e-14));
  CHECK(e.outputs[2] == Approx(3 + 0.3 * std::sin(q)).epsilon(1e-14));
  // Centripetal force on the spinning body does no work along the joint: f = 0.
  CHECK(e.forcing[0] == Approx(0).margin(1e-14));

  // yaw = pi/2 takes the joint's x axis to world y: the body slides along y.
  const auto slider = kanegen::numeric::instantiate(one_joint("prismatic", {1, 0, 0}, {0, 0, kPi / 2}), {});
  const Evaluation s = kanegen::numeric::evaluate(slider, state({0.25}, {2.0}, {0}));
  CHECK(s.mass_matrix[0] == Approx(2.0).epsilon(1e-14));
  CHECK(s.outputs[0] == Approx(1).epsilon(1e-14));  // com (0.3, 0, 0) turned to (0, 0.3, 0)
  CHECK(s.outputs[1] == Approx(2 + 0.3 + 0.25).epsilon(1e-14));
  CHECK(s.outputs[2] == Approx(3).epsilon(1e-14));
  CHECK(s.kinetic_energy == Approx(0.5 * 2.0 * 4.0).epsilon(1e-14));
}

TEST_CASE("numeric M is the Hessian of the numeric kinetic energy in u (7-DOF arm)", "[numeric]") {
  const Model model = load("models/arm7.urdf");
  const auto instance = kanegen::numeric::instantiate(model, {});
  const int n = instance.coordinates();
  REQUIRE(n == 7);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> any(-3, 3);
  std::vector<double> q(n);
  for (double& x : q) x = any(rng);
  const auto kinetic = [&](const std::vector<double>& u) {
    return kanegen::numeric::evaluate(instance, state(q, u, std::vector<double>(n, 0.0))).kinetic_energy;
  };
  const Evaluation e = kanegen::numeric::evaluate(
      instance, state(q, std::vector<double>(n, 0.0), std::vector<double>(n, 0.0)));
  double largest = 0;
  for (double x : e.mass_matrix) largest = std::max(largest, std::abs(x));
  for (int r = 0; r < n; ++r) {
    for (int s = 0; s < n; ++s) {
      std::vector<double> ur(n, 0.0), us(n, 0.0), both(n, 0.0);
      ur[r] = us[s] = 1;
      both[r] += 1;
      both[s] += 1;
      const double h = kinetic(both) - kinetic(ur) - kinetic(us);
      CHECK(std::abs(h - e.mass_matrix[r * n + s]) < 1e-13 * largest);
    }
  }
  // With u = 0 and no inputs, f is the generalized gravity force: minus the gradient of V.
  for (int r = 0; r < n; ++r) {
    std::vector<double> plus = q, minus = q;
    const double h = 1e-6;
    plus[r] += h;
    minus[r] -= h;
    const auto V = [&](const std::vector<double>& x) {
      return kanegen::numeric::evaluate(instance,
                                        state(x, std::vector<double>(n, 0.0), std::vector<double>(n, 0.0)))
          .potential_energy;
    };
    CHECK(e.forcing[r] == Approx(-(V(plus) - V(minus)) / (2 * h)).margin(1e-7));
  }
}

TEST_CASE("finite-difference Jacobians (for emitted Jacobians) are accurate to about 1e-10", "[numeric]") {
  // g(x) = (sin(x0) x1, x0^2 + cos(x1), exp(x0 x1)), J by hand.
  const auto g = [](const std::vector<double>& x) {
    return std::vector<double>{std::sin(x[0]) * x[1], x[0] * x[0] + std::cos(x[1]), std::exp(x[0] * x[1])};
  };
  const std::vector<double> x{0.7, -1.3};
  const std::vector<double> J = kanegen::numeric::finite_difference_jacobian(g, x);
  const double e = std::exp(x[0] * x[1]);
  const double exact[6] = {std::cos(x[0]) * x[1], std::sin(x[0]), 2 * x[0],
                           -std::sin(x[1]),       x[1] * e,       x[0] * e};
  REQUIRE(J.size() == 6);
  for (int i = 0; i < 6; ++i) CHECK(J[i] == Approx(exact[i]).margin(1e-10));
}

TEST_CASE("loops: four-bar Phi in closed form, C and gamma against finite differences, the saddle point",
          "[numeric][loops]") {
  const Model model = load("models/four_bar.json");
  const auto m = kanegen::numeric::instantiate(model, kanegen::model::default_parameter_values(model));
  const std::vector<double> q{0.3, 1.1, 1.9}, u{2.0, -1.5, 0.7};
  const double a = 0.2, b = 0.6, c = 0.5, d = 0.6;
  const kanegen::numeric::LoopKinematics k = kanegen::numeric::loop_kinematics(m, q, u);
  REQUIRE(k.phi.size() == 2);
  CHECK(k.phi[0] ==
        Approx(a * std::cos(q[0]) + b * std::cos(q[0] + q[1]) - d - c * std::cos(q[2])).margin(1e-15));
  CHECK(k.phi[1] ==
        Approx(a * std::sin(q[0]) + b * std::sin(q[0] + q[1]) - c * std::sin(q[2])).margin(1e-15));
  const auto phi = [&](const std::vector<double>& x) {
    return kanegen::numeric::loop_residuals(m, x.data());
  };
  const std::vector<double> C = kanegen::numeric::finite_difference_jacobian(phi, q);
  for (std::size_t i = 0; i < C.size(); ++i) CHECK(k.jacobian[i] == Approx(C[i]).margin(1e-10));
  // gamma = -d/ds (C(q + s u) u) at s = 0.
  const auto velocity = [&](const std::vector<double>& s) {
    std::vector<double> x = q;
    for (std::size_t r = 0; r < x.size(); ++r) x[r] += s[0] * u[r];
    const std::vector<double> J = kanegen::numeric::loop_kinematics(m, x, u).jacobian;
    return std::vector<double>{J[0] * u[0] + J[1] * u[1] + J[2] * u[2],
                               J[3] * u[0] + J[4] * u[1] + J[5] * u[2]};
  };
  const std::vector<double> rate = kanegen::numeric::finite_difference_jacobian(velocity, {0.0});
  CHECK(k.bias[0] == Approx(-rate[0]).margin(1e-9));
  CHECK(k.bias[1] == Approx(-rate[1]).margin(1e-9));
  // The evaluation's udot and lambda solve M udot = f + C^T lambda, C udot = gamma.
  const Evaluation e = kanegen::numeric::evaluate(m, state(q, u, {0, 0, 0}));
  REQUIRE(e.udot.size() == 3);
  REQUIRE(e.lambda.size() == 2);
  for (int r = 0; r < 3; ++r) {
    double residual = -e.forcing[r];
    for (int s = 0; s < 3; ++s) residual += e.mass_matrix[r * 3 + s] * e.udot[s];
    for (int i = 0; i < 2; ++i) residual -= k.jacobian[i * 3 + r] * e.lambda[i];
    CHECK(residual == Approx(0).margin(1e-12));
  }
  for (int i = 0; i < 2; ++i) {
    double residual = -k.bias[i];
    for (int s = 0; s < 3; ++s) residual += k.jacobian[i * 3 + s] * e.udot[s];
    CHECK(residual == Approx(0).margin(1e-12));
  }
  CHECK(e.outputs.size() == 14);  // the reaction at tau = 0: this lambda
  CHECK(e.outputs[12] == Approx(e.lambda[0]).margin(1e-12));
}
