// SPDX-License-Identifier: GPL-2.0-or-later
// Forces, outputs and loops on a mesh body's node sets (issue 18), through
// the generated kernels, against closed forms: the static deflection of a
// cantilever plate under a force on its tip edge, and the prop force of a
// propped cantilever under its weight. The bar is the slender CPS8 bar of
// tests/fem (its frequencies are the Euler-Bernoulli beam's within 0.7 %),
// reduced by Craig-Bampton with the tip edge as the interface, so the
// statics at the tip are the mesh's own; shear adds 5e-4 of the bending
// deflection at L / h = 40.
#include <Eigen/Dense>
#include <catch2/catch.hpp>
#include <cmath>
#include <kanegen/runtime/model.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "slender_propped.hpp"
#include "slender_tip_force.hpp"

namespace {

constexpr double kLength = 0.4, kHeight = 0.01, kThickness = 0.002, kE = 2.1e11, kRho = 7800;
constexpr double kIz = kThickness * kHeight * kHeight * kHeight / 12;

int output_column(const kanegen::runtime::Model& model, const std::string& name) {
  for (int i = 0; i < model.info().ny; ++i)
    if (model.info().output_names[i] == name) return i;
  throw std::invalid_argument("no output " + name);
}

/// The state at rest: u = 0 and f(q, 0) + C(q)^T lambda = 0, Phi(q) = 0,
/// by Newton's method with a central-difference Jacobian of f (the models
/// are linear at rest: their bodies do not turn, so one step is exact and
/// the second checks it).
std::vector<double> rest_state(const kanegen::runtime::Model& model) {
  const int n = model.info().nq, m = model.info().nc;  // the models have as many speeds as coordinates
  std::vector<double> q(n, 0.0), u(n, 0.0), tau(model.info().ntau + 1, 0.0);
  Eigen::VectorXd lambda = Eigen::VectorXd::Zero(m);
  const auto residual = [&](const std::vector<double>& at, const Eigen::VectorXd& l) {
    Eigen::VectorXd r(n + m), f(n), phi(m);
    model.forcing(0.0, at.data(), u.data(), tau.data(), f.data());
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> C(m,
                                                                             n);  // as the kernel writes it
    if (m > 0) {
      model.constraint_jacobian(at.data(), C.data());
      model.constraints(at.data(), phi.data());
    }
    r << f + C.transpose() * l, phi;
    return r;
  };
  for (int iteration = 0; iteration < 2; ++iteration) {
    const Eigen::VectorXd r0 = residual(q, lambda);
    Eigen::MatrixXd J(n + m, n + m);
    for (int k = 0; k < n + m; ++k) {
      const double h = 1e-7;
      std::vector<double> qp = q, qm = q;
      Eigen::VectorXd lp = lambda, lm = lambda;
      if (k < n) {
        qp[k] += h;
        qm[k] -= h;
      } else {
        lp[k - n] += h;
        lm[k - n] -= h;
      }
      J.col(k) = (residual(qp, lp) - residual(qm, lm)) / (2 * h);
    }
    const Eigen::VectorXd step = J.fullPivLu().solve(-r0);
    for (int k = 0; k < n; ++k) q[k] += step[k];
    lambda += step.tail(m);
  }
  INFO("residual at rest " << residual(q, lambda).norm());
  CHECK(residual(q, lambda).norm() < 1e-9);
  return q;
}

std::vector<double> outputs_at_rest(const kanegen::runtime::Model& model) {
  const std::vector<double> q = rest_state(model), u(q.size(), 0.0);
  std::vector<double> y(model.info().ny);
  model.outputs(0.0, q.data(), u.data(), y.data());
  return y;
}

}  // namespace

TEST_CASE("a force on a mesh plate's tip-edge node set bends it as the cantilever formula says",
          "[mesh_node_sets]") {
  const kanegen::runtime::Model model =
      kanegen::runtime::make_model<kanegen_models::slender_tip_force::System>();
  const std::vector<double> y = outputs_at_rest(model);
  const double deflection = y[output_column(model, "tip.y")];
  const double beam = -1.0 * std::pow(kLength, 3) / (3 * kE * kIz);  // P L^3 / (3 E I), P = -1 N
  WARN("tip deflection " << deflection << " m, P L^3 / (3 E I) " << beam << " m");
  CHECK(deflection == Approx(beam).epsilon(0.005));
  // No axial load: the tip edge does not move along the bar to first order.
  CHECK(std::abs(y[output_column(model, "tip.x")]) < 1e-3 * std::abs(beam));
}

TEST_CASE("a loop on a mesh plate's tip-edge node set props it: the prop carries 3 w L / 8",
          "[mesh_node_sets]") {
  const kanegen::runtime::Model model =
      kanegen::runtime::make_model<kanegen_models::slender_propped::System>();
  const std::vector<double> y = outputs_at_rest(model);
  const double w = kRho * kHeight * kThickness * 9.81;  // weight per length, N/m
  const double prop = y[output_column(model, "prop.y")];
  WARN("prop force " << prop << " N, 3 w L / 8 " << 3 * w * kLength / 8 << " N");
  CHECK(prop == Approx(3 * w * kLength / 8).epsilon(0.005));  // the ground pushes the bar up
  // The carriage slides freely along the bar: no axial force.
  CHECK(std::abs(y[output_column(model, "prop.x")]) < 1e-6 * w * kLength);
}
