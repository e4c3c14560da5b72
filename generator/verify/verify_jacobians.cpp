// SPDX-License-Identifier: GPL-2.0-or-later
#include "verify/verify_jacobians.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <random>

#include "verify/verify_differences.hpp"

namespace kanegen::verify {
namespace {

using nlohmann::json;
using Vector = std::vector<double>;

/// The numeric quantities that are differenced, stacked: f (n), M a (n) and
/// C^T lambda (n), with the magnitude of the terms summed into each row.
struct Stacked {
  Vector value, magnitude;
};

Stacked stacked(const numeric::Instance& instance, const numeric::State& state, const Vector& a,
                const Vector& lambda) {
  const numeric::Evaluation e = numeric::evaluate(instance, state);
  const int n = e.n, nc = static_cast<int>(lambda.size());
  Stacked s{Vector(3 * n, 0.0), Vector(3 * n, 0.0)};
  for (int r = 0; r < n; ++r) {
    s.value[r] = e.forcing[r];
    s.magnitude[r] = std::max(e.forcing_magnitude[r], std::abs(e.forcing[r]));
    for (int c = 0; c < n; ++c) {
      s.value[n + r] += e.mass_matrix[r * n + c] * a[c];
      s.magnitude[n + r] += std::abs(e.mass_matrix[r * n + c] * a[c]);
    }
    for (int k = 0; k < nc; ++k) {
      s.value[2 * n + r] += e.constraint_jacobian[k * n + r] * lambda[k];
      s.magnitude[2 * n + r] += std::abs(e.constraint_jacobian[k * n + r] * lambda[k]);
    }
  }
  return s;
}

/// d g / d x by central differences with one Richardson step
/// ((4 D(h/2) - D(h)) / 3), m x n row-major, with each entry's round-off.
struct Differences {
  Vector jacobian, noise;
};

Differences differences(const std::function<Stacked(const Vector&)>& g, const Vector& x, const Vector& h) {
  const std::size_t n = x.size();
  const Stacked at = g(x);
  const std::size_t m = at.value.size();
  Differences d{Vector(m * n), Vector(m * n)};
  for (std::size_t k = 0; k < n; ++k) {
    const auto central = [&](double step) {
      Vector plus = x, minus = x;
      plus[k] += step;
      minus[k] -= step;
      Vector slope = g(plus).value;
      const Vector below = g(minus).value;
      for (std::size_t i = 0; i < m; ++i) slope[i] = (slope[i] - below[i]) / (2 * step);
      return slope;
    };
    const Vector coarse = central(h[k]), fine = central(h[k] / 2);
    for (std::size_t i = 0; i < m; ++i) {
      d.jacobian[i * n + k] = (4 * fine[i] - coarse[i]) / 3;
      d.noise[i * n + k] = difference_noise(at.magnitude[i], h[k]);
    }
  }
  return d;
}

/// Rows [first, first + n) of an m x n matrix.
Vector block(const Vector& m, int first, int n) {
  return Vector(m.begin() + static_cast<long>(first) * n, m.begin() + static_cast<long>(first + n) * n);
}

/// The runner's matrices and the references at one point.
struct Compared {
  Vector generated[4], reference[4], noise[4];
};

Compared evaluate_point(runner::RunnerProcess& process, const JacobianPoint& p, const JacobianCheck& check,
                        std::mt19937_64& rng) {
  const int n = static_cast<int>(p.state.q.size());
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  Vector a(n), lambda;
  for (double& x : a) x = unit(rng);
  int loops = 0;
  for (const numeric::LoopData& l : p.instance->loops) loops += static_cast<int>(l.rows.size());
  for (int k = 0; k < loops; ++k) lambda.push_back(unit(rng));

  json request{{"t", p.state.t},      {"q", p.state.q},  {"u", p.state.u},
               {"tau", p.runner_tau}, {"p", p.runner_p}, {"input_a", a}};
  std::vector<std::string> kernels{"forcing_jacobian", "mass_matrix_product_jacobian"};
  if (loops > 0) {
    request["input_lambda"] = lambda;
    kernels.push_back("constraint_force_jacobian");
  }
  const json k = runner::call_kernels(process, request, kernels);
  Compared c;
  c.generated[0] = json_rows_flat(k["forcing_jacobian"]["dfdq"]);
  c.generated[1] = json_rows_flat(k["forcing_jacobian"]["dfdu"]);
  c.generated[2] = json_rows_flat(k["mass_matrix_product_jacobian"]["dMa_dq"]);
  if (loops > 0) c.generated[3] = json_rows_flat(k["constraint_force_jacobian"]["dCl_dq"]);

  // Steps: f is quadratic in u, so its steps can be large; in q they are
  // small against each coordinate's range of values.
  Vector q_step(n), u_step(n);
  for (int r = 0; r < n; ++r) {
    q_step[r] = (r < check.joints ? 1e-3 : 1e-2) * check.size[r];
    u_step[r] = 0.1 * check.size[r];
  }
  const Differences by_q = differences(
      [&](const Vector& q) {
        numeric::State s = p.state;
        s.q = q;
        return stacked(*p.instance, s, a, lambda);
      },
      p.state.q, q_step);
  const Differences by_u = differences(
      [&](const Vector& u) {
        numeric::State s = p.state;
        s.u = u;
        return stacked(*p.instance, s, a, lambda);
      },
      p.state.u, u_step);
  c.reference[0] = block(by_q.jacobian, 0, n);
  c.noise[0] = block(by_q.noise, 0, n);
  c.reference[1] = block(by_u.jacobian, 0, n);
  c.noise[1] = block(by_u.noise, 0, n);
  c.reference[2] = block(by_q.jacobian, n, n);
  c.noise[2] = block(by_q.noise, n, n);
  c.reference[3] = block(by_q.jacobian, 2 * n, n);
  c.noise[3] = block(by_q.noise, 2 * n, n);
  return c;
}

}  // namespace

std::vector<Row> jacobian_rows(runner::RunnerProcess& process, const std::vector<JacobianPoint>& points,
                               const JacobianCheck& check) {
  const int n = static_cast<int>(check.coordinates.size());
  const EntryName name = [&check, n](int k) {
    return "[" + std::to_string(k / n) + "," + std::to_string(k % n) + "] (" + check.coordinates[k / n] +
           ", " + check.coordinates[k % n] + ")";
  };
  // Named as the report's other rows, within its columns (forcing_jacobian's
  // two matrices, mass_matrix_product_jacobian, constraint_force_jacobian).
  std::vector<Row> rows{Row("forcing_jacobian df/dq", "differences of numeric f", check.tolerance),
                        Row("forcing_jacobian df/du", "differences of numeric f", check.tolerance),
                        Row("d(M a)/dq", "differences of numeric M a", check.tolerance),
                        Row("d(C^T lambda)/dq", "differences num. C^T lambda", check.tolerance)};
  std::mt19937_64 rng(check.seed);
  bool loops = false;
  for (const JacobianPoint& p : points) {
    const Compared c = evaluate_point(process, p, check, rng);
    loops = !c.generated[3].empty();
    for (int j = 0; j < (loops ? 4 : 3); ++j) {
      rows[j].consider(compare_entries(c.generated[j], c.reference[j],
                                       difference_scales(c.reference[j], c.noise[j], n, check.tolerance),
                                       name, p.sample));
      ++rows[j].compared;
    }
  }
  if (!loops) {
    rows[3].applicable = false;
    rows[3].note = "the model has no loops";
  }
  return rows;
}

Row jacobians_absent_row(bool requested) {
  return optional_kernels_absent_row("Jacobians", "differences of the numeric path", "--jacobians",
                                     requested);
}

}  // namespace kanegen::verify
