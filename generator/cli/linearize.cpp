// SPDX-License-Identifier: GPL-2.0-or-later
#include "cli/linearize.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace kanegen::cli {
namespace {

using nlohmann::json;

double finite(const json& x, const char* what) {
  if (!x.is_number() || !std::isfinite(x.get<double>()))
    throw std::runtime_error(std::string("the kernels gave a non-finite ") + what +
                             " at the operating point (or a step away from it); check the initial state and "
                             "the parameters");
  return x.get<double>();
}

/// r = f_s - M_s,o a_o and, if asked, M_ss, at one state.
class Rows {
 public:
  Rows(runner::RunnerProcess& runner, const OperatingPoint& point, const LinearizeOptions& options)
      : runner_(runner), point_(point), options_(options) {}

  Eigen::VectorXd residual(const std::vector<double>& q, const std::vector<double>& u,
                           Eigen::MatrixXd* mass = nullptr, Eigen::MatrixXd* loops = nullptr) {
    const std::vector<double>& lambda = options_.loop_forces;
    const int nc = static_cast<int>(lambda.size());
    std::vector<std::string> kernels{"mass_matrix", "forcing"};
    if (nc > 0) kernels.push_back("constraint_jacobian");
    const json reply =
        runner::call_kernels(runner_, json{{"t", point_.t}, {"q", q}, {"u", u}, {"p", point_.p}}, kernels);
    const json& M = reply.at("mass_matrix").at("M");
    const json& f = reply.at("forcing").at("f");
    const std::vector<int>& s = options_.selected;
    const int n = static_cast<int>(s.size()), nu = static_cast<int>(f.size());
    const json& C = nc > 0 ? reply.at("constraint_jacobian").at("C") : reply;
    Eigen::VectorXd r(n);
    for (int i = 0; i < n; ++i) {
      double value = finite(f[s[i]], "forcing");
      for (int o = 0; o < nu; ++o) {
        const double a = options_.other_accelerations[o];
        if (a != 0.0 && !std::binary_search(s.begin(), s.end(), o))
          value -= finite(M[s[i]][o], "mass matrix") * a;
      }
      for (int k = 0; k < nc; ++k) value += finite(C[k][s[i]], "constraint jacobian") * lambda[k];
      r[i] = value;
    }
    if (loops) {
      loops->resize(nc, n);
      for (int k = 0; k < nc; ++k)
        for (int j = 0; j < n; ++j) (*loops)(k, j) = finite(C[k][s[j]], "constraint jacobian");
    }
    if (mass) {
      mass->resize(n, n);
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) (*mass)(i, j) = finite(M[s[i]][s[j]], "mass matrix");
    }
    return r;
  }

 private:
  runner::RunnerProcess& runner_;
  const OperatingPoint& point_;
  const LinearizeOptions& options_;
};

/// -d r / d x_s by central differences, x = q or u, at steps h and h / 2,
/// combined by Richardson's extrapolation (4 D(h/2) - D(h)) / 3: exact for
/// polynomials up to degree 4 in each coordinate (the nonlinear axial strain
/// of geometric stiffening makes the elastic forces cubic), else O(h^4).
Eigen::MatrixXd derivative(Rows& rows, const OperatingPoint& point, const LinearizeOptions& options,
                           bool speeds) {
  const int n = static_cast<int>(options.selected.size());
  Eigen::MatrixXd d(n, n);
  for (int j = 0; j < n; ++j) {
    std::vector<double> q = point.q, u = point.u;
    std::vector<double>& x = speeds ? u : q;
    const int k = options.selected[j];
    const double x0 = x[k];
    const auto central = [&](double h) -> Eigen::VectorXd {
      const double up = x0 + h, down = x0 - h;  // the steps as represented
      x[k] = up;
      const Eigen::VectorXd plus = rows.residual(q, u);
      x[k] = down;
      const Eigen::VectorXd minus = rows.residual(q, u);
      x[k] = x0;
      return -(plus - minus) / (up - down);
    };
    const double h = options.step * std::max(1.0, std::abs(x0));
    d.col(j) = (4.0 * central(h / 2) - central(h)) / 3.0;
  }
  return d;
}

}  // namespace

Linearization linearize(runner::RunnerProcess& runner, const OperatingPoint& point,
                        const LinearizeOptions& options) {
  if (options.other_accelerations.size() != point.u.size())
    throw std::logic_error("linearize: one given acceleration per speed is needed");
  Rows rows(runner, point, options);
  Linearization out;
  out.forcing = rows.residual(point.q, point.u, &out.mass, &out.loops);
  out.stiffness = derivative(rows, point, options, false);
  if (options.velocity) out.velocity = derivative(rows, point, options, true);
  return out;
}

}  // namespace kanegen::cli
