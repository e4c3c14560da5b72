// SPDX-License-Identifier: GPL-2.0-or-later
// The numeric derivation of flexible bodies and prescribed motions on its
// own: Gauss rules, the textbook element matrices of a cantilever (stiffness,
// consistent mass), the geometric stiffness of a spinning beam against the
// finite-element layer's (an independent implementation), the prescribed
// acceleration, and the path's own consistency: M is the Hessian of T, and
// d(T + V)/dt = P_nc along its own dynamics (gyroscopic and elastic terms
// included), the cheap power equal to the full evaluation's.
#include <catch2/catch.hpp>
#include <cmath>
#include <random>

#include "fem/elastic_model.hpp"
#include "fem/rotating.hpp"
#include "model/expression_eval.hpp"
#include "model/load.hpp"
#include "numeric/beam.hpp"
#include "numeric/dynamics.hpp"
#include "numeric/instance.hpp"
#include "numeric/shape_function.hpp"
#include "numeric/time_function.hpp"

namespace {

using kanegen::model::Model;
using kanegen::model::Scalar;
using kanegen::numeric::Evaluation;
using kanegen::numeric::State;

Model load(const std::string& relative) {
  return kanegen::model::load_model(std::string(KANEGEN_SOURCE_DIR) + "/" + relative);
}

constexpr double E = 7e10, A = 1e-4, Iz = 1e-10, rho = 2700, L = 0.6;

/// One clamped planar beam of length L on a fixed joint (or on a joint
/// turning about `axis` when `spin`), no gravity; in its first `modes` modes
/// when `modes` > 0, with geometric stiffening when `stiffening`.
Model cantilever(int elements, bool spin = false, std::array<double, 3> axis = {0, 1, 0}, int modes = 0,
                 bool stiffening = true) {
  Model m;
  m.name = "cantilever";
  m.gravity = {Scalar::number(0), Scalar::number(0), Scalar::number(0)};
  kanegen::model::Body b;
  b.name = "beam";
  b.mass = Scalar::number(0);
  b.com = {Scalar::number(0), Scalar::number(0), Scalar::number(0)};
  for (Scalar& i : b.inertia) i = Scalar::number(0);
  b.flexible = true;
  b.elastic.segments.push_back({{L, 0, 0}, elements, ""});
  b.elastic.A = A;
  b.elastic.Iz = Iz;
  b.elastic.E = E;
  b.elastic.density = rho;
  b.elastic.geometric_stiffening = stiffening;
  b.elastic.modes = modes;
  m.bodies.push_back(b);
  kanegen::model::Joint j;
  j.name = "hub";
  j.type = spin ? kanegen::model::JointType::continuous : kanegen::model::JointType::fixed;
  j.parent = "ground";
  j.child = "beam";
  for (Scalar& x : j.origin_xyz) x = Scalar::number(0);
  for (Scalar& x : j.origin_rpy) x = Scalar::number(0);
  j.axis = axis;
  j.spring_stiffness = j.spring_rest = j.damping = Scalar::number(0);
  m.joints.push_back(j);
  return m;
}

State at(std::vector<double> q, std::vector<double> u, double t = 0) {
  State s;
  s.t = t;
  s.tau.assign(q.size(), 0.0);
  s.q = std::move(q);
  s.u = std::move(u);
  return s;
}

}  // namespace

TEST_CASE("Gauss-Legendre rules on [0, 1] are exact to degree 2n - 1", "[numeric][flexible]") {
  for (int n = 1; n <= 6; ++n) {
    const kanegen::numeric::GaussRule rule = kanegen::numeric::gauss_rule(n);
    REQUIRE(rule.points.size() == static_cast<std::size_t>(n));
    for (int k = 0; k <= 2 * n - 1; ++k) {
      double sum = 0;
      for (int i = 0; i < n; ++i) sum += rule.weights[i] * std::pow(rule.points[i], k);
      CHECK(sum == Approx(1.0 / (k + 1)).epsilon(1e-14));
    }
  }
}

TEST_CASE("cantilever element: -K eta and the consistent mass are the textbook matrices",
          "[numeric][flexible]") {
  const Model model = cantilever(1, false, {0, 1, 0}, 0, false);  // the linear model
  const auto instance = kanegen::numeric::instantiate(model, {});
  REQUIRE(instance.coordinate_names == std::vector<std::string>{"beam.n1.u", "beam.n1.v", "beam.n1.theta_z"});
  // The free end's (u, v, theta_z): K = [EA/L; EI/L^3 (12, -6L... with the clamped end removed)].
  const double ea = E * A / L, ei = E * Iz;
  const double K[3][3] = {
      {ea, 0, 0}, {0, 12 * ei / (L * L * L), -6 * ei / (L * L)}, {0, -6 * ei / (L * L), 4 * ei / L}};
  const double m = rho * A * L;
  const double M[3][3] = {
      {m / 3, 0, 0}, {0, 156 * m / 420, -22 * L * m / 420}, {0, -22 * L * m / 420, 4 * L * L * m / 420}};
  for (int k = 0; k < 3; ++k) {
    std::vector<double> q(3, 0.0);
    q[k] = 1e-3;
    const Evaluation e = kanegen::numeric::evaluate(instance, at(q, {0, 0, 0}));
    for (int r = 0; r < 3; ++r) {
      CHECK(e.forcing[r] == Approx(-K[r][k] * 1e-3).epsilon(1e-12).margin(1e-12 * ea * 1e-3));
      CHECK(e.mass_matrix[r * 3 + k] == Approx(M[r][k]).epsilon(1e-12).margin(1e-15));
    }
    CHECK(e.potential_energy == Approx(0.5 * K[k][k] * 1e-6).epsilon(1e-12));
  }
}

TEST_CASE(
    "spinning modal beam: the foreshortening gives the FEM layer's geometric stiffness of the centrifugal "
    "load",
    "[numeric][flexible]") {
  // Spin about y: omega_y^2 = Omega^2 loads the planar beam (hub at the axis, no gravity).
  const Model model = cantilever(6, true, {0, 1, 0}, 3);
  const auto instance = kanegen::numeric::instantiate(model, {});
  const int n = instance.coordinates();
  REQUIRE(n == 4);
  const double omega = 3.0;
  const kanegen::fem::ElasticModel beam =
      kanegen::fem::build_elastic_model(model.bodies[0], "", kanegen::numeric::sample_shape);
  const Eigen::MatrixXd kl = beam.reduced.geometric->linear;  // K_G for a = x, in the modes
  // f(eta) - f(0) at u = (Omega, 0...): -K eta - Omega^2 Kl eta + the centrifugal force on N eta.
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> any(-1e-3, 1e-3);
  std::vector<double> q(n, 0.0), u(n, 0.0);
  u[0] = omega;
  for (int k = 1; k < n; ++k) q[k] = any(rng);
  const Evaluation deformed = kanegen::numeric::evaluate(instance, at(q, u));
  const Evaluation straight = kanegen::numeric::evaluate(instance, at(std::vector<double>(n, 0.0), u));
  // The spin-softening term, int rho N^T W^2 N eta, from the FEM invariants; K_e from the FEM stiffness.
  const Eigen::MatrixXd k = beam.reduced.stiffness;
  const Eigen::MatrixXd softening =
      kanegen::fem::spin_softening(beam.reduced.invariants, Eigen::Vector3d(0, omega, 0));
  Eigen::VectorXd eta(n - 1);
  for (int i = 1; i < n; ++i) eta[i - 1] = q[i];
  const Eigen::VectorXd expected = -(k + omega * omega * kl + softening) * eta;
  double largest = 0;
  for (int i = 0; i < n - 1; ++i) largest = std::max(largest, std::abs(expected[i]));
  for (int i = 1; i < n; ++i)
    CHECK(deformed.forcing[i] - straight.forcing[i] == Approx(expected[i - 1]).margin(1e-11 * largest));
}

TEST_CASE("nodal beam under tension: the nonlinear axial strain gives the FEM layer's geometric stiffness",
          "[numeric][flexible]") {
  // A uniform stretch u = x N / EA (tension N everywhere), no bending: the
  // bending rows' forcing is then -(K_e + N K_tip) v for a small bending v,
  // K_tip the FEM layer's geometric stiffness of a unit axial tip force.
  const Model model = cantilever(4);
  const auto instance = kanegen::numeric::instantiate(model, {});
  const int n = instance.coordinates();
  REQUIRE(n == 12);
  const kanegen::fem::ElasticModel beam =
      kanegen::fem::build_elastic_model(model.bodies[0], "", kanegen::numeric::sample_shape);
  const Eigen::MatrixXd& B = beam.reduced.basis;
  const int tip = beam.body.num_nodes() - 1;
  const Eigen::MatrixXd k_tip =
      B.transpose() * kanegen::fem::node_force_geometric_stiffness(beam.body, tip) * B;
  const double tension = 250.0;
  std::vector<double> stretched(n, 0.0);
  for (int i = 0; i < n; ++i)
    if (instance.coordinate_names[i].size() > 2 &&
        instance.coordinate_names[i].compare(instance.coordinate_names[i].size() - 2, 2, ".u") == 0)
      stretched[i] = (i / 3 + 1) * (L / 4) * tension / (E * A);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> any(-1e-7, 1e-7);
  std::vector<double> bent = stretched;
  Eigen::VectorXd v = Eigen::VectorXd::Zero(n);
  for (int i = 0; i < n; ++i)
    if (stretched[i] == 0.0) bent[i] += v[i] = any(rng);
  const std::vector<double> rest(n, 0.0);
  const Evaluation at_bent = kanegen::numeric::evaluate(instance, at(bent, rest));
  const Evaluation at_stretched = kanegen::numeric::evaluate(instance, at(stretched, rest));
  const Eigen::VectorXd expected = -(beam.reduced.stiffness + tension * k_tip) * v;
  double largest = 0;
  for (int i = 0; i < n; ++i)
    if (v[i] != 0.0) largest = std::max(largest, std::abs(expected[i]));
  for (int i = 0; i < n; ++i) {
    if (v[i] == 0.0) continue;  // the axial rows: second order in v
    INFO(instance.coordinate_names[i]);
    CHECK(at_bent.forcing[i] - at_stretched.forcing[i] == Approx(expected[i]).margin(1e-7 * largest));
  }
}

TEST_CASE("prescribed motions: q, q' and q'' exactly, piece by piece", "[numeric][flexible]") {
  const kanegen::model::ParameterValues p{{"Ws", 4.0}};
  const kanegen::numeric::TimeFunction spin("(Ws/5)*(t^2/2 + (5/(2*pi))^2*(cos(2*pi*t/5) - 1))", p);
  const kanegen::numeric::TimeFunction steady("Ws*(t - 2.5)", p);
  kanegen::numeric::JointData joint;
  joint.prescribed = {{spin, true, 5.0}, {steady, false, 0.0}};
  const double pi = 3.14159265358979323846;
  for (double t : {0.0, 1.3, 4.9}) {
    const auto m = kanegen::numeric::prescribed_motion(joint, t);
    const double w = 2 * pi / 5;
    CHECK(m[0] == Approx(0.8 * (t * t / 2 + (std::cos(w * t) - 1) / (w * w))).margin(1e-14));
    CHECK(m[1] == Approx(0.8 * (t - std::sin(w * t) / w)).margin(1e-14));
    CHECK(m[2] == Approx(0.8 * (1 - std::cos(w * t))).margin(1e-14));
  }
  const auto after = kanegen::numeric::prescribed_motion(joint, 7.0);
  CHECK(after[0] == Approx(18.0));
  CHECK(after[1] == Approx(4.0));
  CHECK(after[2] == 0.0);
  // Powers, quotients and functions of t, and of parameters only.
  const kanegen::numeric::TimeFunction f("-t^2/exp(0) + sqrt(t)*log(t) + tan(t) + 2^t", {});
  using D1 = kanegen::numeric::Dual<double>;
  const D1 x = f(D1(1.5, 1.0));
  CHECK(x.v == Approx(-2.25 + std::sqrt(1.5) * std::log(1.5) + std::tan(1.5) + std::pow(2, 1.5)));
  CHECK(x.d == Approx(-3.0 + std::log(1.5) / (2 * std::sqrt(1.5)) + std::sqrt(1.5) / 1.5 +
                      1 / (std::cos(1.5) * std::cos(1.5)) + std::log(2.0) * std::pow(2, 1.5)));
  CHECK_THROWS_AS(kanegen::numeric::TimeFunction("t + nope", {}), std::invalid_argument);
}

TEST_CASE("flexible models: M is the Hessian of T, d(T + V)/dt = P_nc along the numeric dynamics",
          "[numeric][flexible]") {
  for (const char* file : {"tests/data/models/flex_spatial_hub.json", "tests/data/models/flex_hub_modal.json",
                           "tests/data/models/flex_prescribed_hub.json"}) {
    INFO(file);
    const Model model = load(file);
    const auto instance =
        kanegen::numeric::instantiate(model, kanegen::model::default_parameter_values(model));
    const int n = instance.coordinates(), joints = instance.joint_coordinates();
    std::mt19937 rng(17);
    std::uniform_real_distribution<double> any(-1, 1);
    for (int sample = 0; sample < 3; ++sample) {
      State s = at(std::vector<double>(n), std::vector<double>(n), 1.0 + sample);
      for (int r = 0; r < n; ++r) {
        const double size = r < joints ? 1.0 : 1e-3;
        s.q[r] = size * any(rng);
        s.u[r] = 2 * size * any(rng);
        if (r < joints) s.tau[r] = any(rng);
      }
      const Evaluation e = kanegen::numeric::evaluate(instance, s);
      REQUIRE(e.udot.size() == static_cast<std::size_t>(n));
      // T is quadratic in u: its second differences are M.
      const auto kinetic = [&](const std::vector<double>& u) {
        State x = s;
        x.u = u;
        return kanegen::numeric::evaluate(instance, x).kinetic_energy;
      };
      double largest = 0;
      for (double x : e.mass_matrix) largest = std::max(largest, std::abs(x));
      for (int r = 0; r < n; r += 3)
        for (int c = 0; c < n; c += 2) {
          std::vector<double> ur(n, 0.0), uc(n, 0.0), both(n, 0.0), zero(n, 0.0);
          ur[r] = uc[c] = 1;
          both[r] += 1;
          both[c] += 1;
          CHECK(kinetic(both) - kinetic(ur) - kinetic(uc) + kinetic(zero) ==
                Approx(e.mass_matrix[r * n + c]).margin(1e-12 * largest));
        }
      // Along q' = u, u' = udot: central differences of T + V against the power.
      const double h = 1e-6;
      const auto energy = [&](double sign) {
        State x = s;
        for (int r = 0; r < n; ++r) {
          x.q[r] += sign * h * s.u[r];
          x.u[r] += sign * h * e.udot[r];
        }
        x.t += sign * h;
        const Evaluation y = kanegen::numeric::evaluate(instance, x);
        return y.kinetic_energy + y.potential_energy;
      };
      const double rate = (energy(1) - energy(-1)) / (2 * h);
      const double scale = std::abs(e.kinetic_energy) + std::abs(e.potential_energy);
      CHECK(rate == Approx(e.nonconservative_power).margin(1e-6 * scale));
      // The cheap power path, with the numeric udot, equals the full evaluation's.
      CHECK(kanegen::numeric::nonconservative_power(instance, s, &e.udot) ==
            Approx(e.nonconservative_power).epsilon(1e-10).margin(1e-12 * scale));
      CHECK(kanegen::numeric::nonconservative_power(instance, s) ==
            Approx(e.nonconservative_power).epsilon(1e-10).margin(1e-12 * scale));
    }
  }
}

TEST_CASE("an assumed-mode slope the chain rule cannot give at an end is its one-sided limit", "[numeric]") {
  std::vector<double> value, slope;
  kanegen::numeric::sample_shape("(x/L)*sqrt(x/L)", {{"L", 2.0}}, {0.0, 1.0, 2.0}, value, slope);
  CHECK(value[0] == 0.0);
  CHECK(std::abs(slope[0]) < 1e-100);  // d/dx (x/L)^1.5 = 1.5 sqrt(x/L)/L -> 0
  CHECK(slope[1] == Approx(1.5 * std::sqrt(0.5) / 2.0));
  CHECK(slope[2] == Approx(0.75));
}
