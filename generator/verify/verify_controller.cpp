// SPDX-License-Identifier: GPL-2.0-or-later
#include "verify/verify_controller.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <stdexcept>
#include <tuple>

#include "numeric/beam.hpp"
#include "verify/verify_differences.hpp"

namespace kanegen::verify {
namespace {

using nlohmann::json;
using Vector = std::vector<double>;

enum RowIndex { kCu, kSkew, kJacobian, kRate, kA, kB, kRows };

/// The reply's entry of `expected` numbers; another size means the runner's
/// kernels are not the model's (files from another kanegen), which verify
/// reports rather than reading past the end.
Vector sized(Vector v, std::size_t expected, const char* key) {
  if (v.size() != expected)
    throw std::runtime_error(std::string("the runner's ") + key + " has " + std::to_string(v.size()) +
                             " entries, not " + std::to_string(expected) +
                             "; its kernels do not match the model (regenerate them with this kanegen)");
  return v;
}

/// d g(s) / ds at s = 0 by central differences with one Richardson step.
Vector first_derivative(const std::function<Vector(double)>& g, double h) {
  const auto central = [&](double step) {
    Vector plus = g(step);
    const Vector minus = g(-step);
    for (std::size_t i = 0; i < plus.size(); ++i) plus[i] = (plus[i] - minus[i]) / (2 * step);
    return plus;
  };
  const Vector coarse = central(h), fine = central(h / 2);
  Vector d(coarse.size());
  for (std::size_t i = 0; i < d.size(); ++i) d[i] = (4 * fine[i] - coarse[i]) / 3;
  return d;
}

/// d2 g(s) / ds2 at s = 0 by second differences with one Richardson step.
Vector second_derivative(const std::function<Vector(double)>& g, double h) {
  const Vector at = g(0);
  const auto second = [&](double step) {
    Vector plus = g(step);
    const Vector minus = g(-step);
    for (std::size_t i = 0; i < plus.size(); ++i) plus[i] = (plus[i] - 2 * at[i] + minus[i]) / (step * step);
    return plus;
  };
  const Vector coarse = second(h), fine = second(h / 2);
  Vector d(coarse.size());
  for (std::size_t i = 0; i < d.size(); ++i) d[i] = (4 * fine[i] - coarse[i]) / 3;
  return d;
}

/// One row's comparison at one point.
struct Compared {
  Vector generated, reference, noise;
  int columns = 1;
};

class PointCheck {
 public:
  PointCheck(const ControllerPoint& p, const ControllerCheck& check)
      : p_(p), check_(check), n_(static_cast<int>(p.state.q.size())) {}

  numeric::Evaluation at(const Vector& q, const Vector& u, const Vector& tau) const {
    numeric::State s = p_.state;
    s.q = q;
    s.u = u;
    s.tau = tau;
    return numeric::evaluate(*p_.instance, s);
  }

  /// C u against minus the part of f quadratic in u: (f(u) + f(-u)) / 2 - f(0).
  Compared velocity_terms(const Vector& C) const {
    const numeric::State& s = p_.state;
    Vector minus = s.u, zero(n_, 0.0);
    for (double& x : minus) x = -x;
    const numeric::Evaluation plus = at(s.q, s.u, s.tau), back = at(s.q, minus, s.tau),
                              rest = at(s.q, zero, s.tau);
    Compared c;
    c.columns = n_;
    for (int r = 0; r < n_; ++r) {
      double cu = 0;
      for (int k = 0; k < n_; ++k) cu += C[r * n_ + k] * s.u[k];
      c.generated.push_back(cu);
      c.reference.push_back(-((plus.forcing[r] + back.forcing[r]) / 2 - rest.forcing[r]));
      c.noise.push_back(kDifferenceNoiseFactor * kDifferenceEpsilon *
                        (plus.forcing_magnitude[r] + back.forcing_magnitude[r] + rest.forcing_magnitude[r]));
    }
    return c;
  }

  /// C + C^T against Mdot along u (Mdot - 2C skew-symmetric).
  Compared skew(const Vector& C) const {
    const numeric::State& s = p_.state;
    const double h = 1e-3 / along_u_rate();
    const Vector mdot =
        first_derivative([&](double step) { return at(shifted(s.q, step), s.u, s.tau).mass_matrix; }, h);
    const Vector M = at(s.q, s.u, s.tau).mass_matrix;
    Compared c;
    c.columns = n_;
    c.reference = mdot;
    for (int r = 0; r < n_; ++r)
      for (int k = 0; k < n_; ++k) {
        c.generated.push_back(C[r * n_ + k] + C[k * n_ + r]);
        const double size = std::abs(M[r * n_ + k]) + std::sqrt(std::abs(M[r * n_ + r] * M[k * n_ + k]));
        c.noise.push_back(kDifferenceNoiseFactor * kDifferenceEpsilon * size / h);
      }
    return c;
  }

  /// The size of each output's round-off: |y_i|, and for a node displacement
  /// (the displaced node less its rest position) the rest position's.
  Vector output_magnitudes(const Vector& y) const {
    Vector magnitude(y.size());
    for (std::size_t i = 0; i < y.size(); ++i) {
      magnitude[i] = std::abs(y[i]);
      const numeric::OutputData& o = p_.instance->outputs[p_.instance->output_columns[i].output];
      if (o.kind != model::OutputKind::node_displacement) continue;
      const numeric::Vec<double>& node = numeric::rest_node(*p_.instance->bodies[o.body].elastic, o.node);
      magnitude[i] += std::sqrt(node[0] * node[0] + node[1] * node[1] + node[2] * node[2]);
    }
    return magnitude;
  }

  /// J against central differences of the outputs in q.
  Compared output_jacobian(const Vector& J) const {
    const numeric::State& s = p_.state;
    const Vector y = output_magnitudes(at(s.q, s.u, s.tau).outputs);
    const int ny = static_cast<int>(y.size());
    Compared c;
    c.columns = n_;
    c.generated = J;
    c.reference.assign(static_cast<std::size_t>(ny) * n_, 0.0);
    c.noise.assign(c.reference.size(), 0.0);
    for (int j = 0; j < n_; ++j) {
      const double h = q_step(j);
      const Vector column = first_derivative(
          [&](double step) {
            Vector q = s.q;
            q[j] += step;
            return at(q, s.u, s.tau).outputs;
          },
          h);
      for (int i = 0; i < ny; ++i) {
        c.reference[i * n_ + j] = column[i];
        c.noise[i * n_ + j] = kDifferenceNoiseFactor * kDifferenceEpsilon * std::abs(y[i]) / h;
      }
    }
    return c;
  }

  /// Jdot_u against the second derivative of the outputs along q + s u.
  Compared output_jacobian_rate(const Vector& rate) const {
    const numeric::State& s = p_.state;
    // The step turns the joints by 1e-2 (Richardson leaves O(h^4)); it is not
    // shortened for the elastic speeds, which would move by 0.2 of their size
    // at most, still a small deformation: an output that is a difference (a
    // node's displacement, the displaced node less its rest position) has the
    // round-off of the larger terms, which the second difference divides by h^2.
    const double h = 1e-2 / joint_rate();
    Compared c;
    c.columns = static_cast<int>(rate.size());
    c.generated = rate;
    c.reference =
        second_derivative([&](double step) { return at(shifted(s.q, step), s.u, s.tau).outputs; }, h);
    for (double y : output_magnitudes(at(s.q, s.u, s.tau).outputs))
      c.noise.push_back(kDifferenceNoiseFactor * kDifferenceEpsilon * y / (h * h));
    return c;
  }

  /// linearize's A and B in the numeric system: the rows of qdot against
  /// [0 I 0], and M times the rows of udot against d(f - M a)/d(q, u, tau)
  /// at a = the numeric udot.
  std::pair<Compared, Compared> linearization(const Vector& A, const Vector& B, int status) const {
    const numeric::State& s = p_.state;
    const numeric::Evaluation base = at(s.q, s.u, s.tau);
    const Vector a = base.udot.empty() ? Vector(n_, std::nan("")) : base.udot;
    const auto residual = [&](const numeric::Evaluation& e) {
      Vector g = e.forcing;
      for (int r = 0; r < n_; ++r)
        for (int k = 0; k < n_; ++k) g[r] -= e.mass_matrix[r * n_ + k] * a[k];
      return g;
    };
    Vector magnitude(n_);
    for (int r = 0; r < n_; ++r) {
      magnitude[r] = std::max(base.forcing_magnitude[r], std::abs(base.forcing[r]));
      for (int k = 0; k < n_; ++k) magnitude[r] += std::abs(base.mass_matrix[r * n_ + k] * a[k]);
    }
    const int ntau = static_cast<int>(check_.input.size()), wide = 2 * n_;
    Compared ca, cb;
    ca.columns = wide;
    cb.columns = std::max(ntau, 1);
    // The rows of qdot = u.
    for (int i = 0; i < n_; ++i) {
      for (int j = 0; j < wide; ++j) {
        ca.generated.push_back(A[i * wide + j]);
        ca.reference.push_back(j == n_ + i ? 1.0 : 0.0);
        ca.noise.push_back(0);
      }
      for (int k = 0; k < ntau; ++k) {
        cb.generated.push_back(B[i * ntau + k]);
        cb.reference.push_back(0);
        cb.noise.push_back(0);
      }
    }
    // d(f - M a)/dx, column by column.
    Vector dq(static_cast<std::size_t>(n_) * wide), dtau(static_cast<std::size_t>(n_) * ntau);
    Vector steps(wide);
    for (int j = 0; j < wide; ++j) {
      const bool speed = j >= n_;
      const int c = speed ? j - n_ : j;
      steps[j] = speed ? 0.1 * check_.size[c] : q_step(c);
      const Vector column = first_derivative(
          [&](double step) {
            Vector q = s.q, u = s.u;
            (speed ? u : q)[c] += step;
            return residual(at(q, u, s.tau));
          },
          steps[j]);
      for (int r = 0; r < n_; ++r) dq[r * wide + j] = column[r];
    }
    for (int k = 0; k < ntau; ++k) {
      const Vector column = first_derivative(
          [&](double step) {
            Vector tau = s.tau;
            tau[check_.input[k]] += step;
            return residual(at(s.q, s.u, tau));
          },
          1.0);
      for (int r = 0; r < n_; ++r) dtau[r * ntau + k] = column[r];
    }
    // M times the generated rows of udot.
    const Vector& M = base.mass_matrix;
    for (int r = 0; r < n_; ++r) {
      for (int j = 0; j < wide; ++j) {
        double sum = 0;
        for (int k = 0; k < n_; ++k) sum += M[r * n_ + k] * A[(n_ + k) * wide + j];
        ca.generated.push_back(status == 0 ? sum : std::nan(""));
        ca.reference.push_back(dq[r * wide + j]);
        ca.noise.push_back(kDifferenceNoiseFactor * kDifferenceEpsilon * magnitude[r] / steps[j]);
      }
      for (int k = 0; k < ntau; ++k) {
        double sum = 0;
        for (int i = 0; i < n_; ++i) sum += M[r * n_ + i] * B[(n_ + i) * ntau + k];
        cb.generated.push_back(status == 0 ? sum : std::nan(""));
        cb.reference.push_back(dtau[r * ntau + k]);
        cb.noise.push_back(kDifferenceNoiseFactor * kDifferenceEpsilon * magnitude[r]);
      }
    }
    return {ca, cb};
  }

 private:
  /// The largest rate of q + s u against each coordinate's size, so that a
  /// step h moves no coordinate by more than h times its size.
  double along_u_rate() const {
    double rate = 0;
    for (int r = 0; r < n_; ++r) rate = std::max(rate, std::abs(p_.state.u[r]) / check_.size[r]);
    return rate > 0 ? rate : 1.0;
  }
  /// The largest joint speed, or along_u_rate() for a model without moving joints.
  double joint_rate() const {
    double rate = 0;
    for (int r = 0; r < check_.joints; ++r) rate = std::max(rate, std::abs(p_.state.u[r]));
    return rate > 0 ? rate : along_u_rate();
  }
  Vector shifted(const Vector& q, double step) const {
    Vector out = q;
    for (int r = 0; r < n_; ++r) out[r] += step * p_.state.u[r];
    return out;
  }
  /// Small against each coordinate's range of values (as verify_jacobians.cpp).
  double q_step(int r) const { return (r < check_.joints ? 1e-3 : 1e-2) * check_.size[r]; }

  const ControllerPoint& p_;
  const ControllerCheck& check_;
  int n_;
};

std::vector<Row> empty_rows(double tolerance) {
  return {Row("coriolis_matrix C u", "numeric velocity terms of f", tolerance),
          Row("coriolis_matrix C + C^T", "differences of numeric M", tolerance),
          Row("output_jacobian", "differences num. outputs", tolerance),
          Row("output_jacobian_rate", "differences num. outputs", tolerance),
          Row("linearize A", "differences num. f - M a", tolerance),
          Row("linearize B", "differences num. f - M a", tolerance)};
}

}  // namespace

std::vector<Row> controller_rows(runner::RunnerProcess& process, const std::vector<ControllerPoint>& points,
                                 const ControllerCheck& check) {
  const int ntau = static_cast<int>(check.input.size());
  const auto matrix_name = [](const std::vector<std::string>& rows, const std::vector<std::string>& columns) {
    return EntryName([rows, columns](int k) {
      const int width = static_cast<int>(columns.size());
      return "[" + std::to_string(k / width) + "," + std::to_string(k % width) + "] (" + rows[k / width] +
             ", " + columns[k % width] + ")";
    });
  };
  std::vector<std::string> state, state_rate, inputs;
  for (const std::string& c : check.coordinates) {
    state.push_back("q " + c);
    state_rate.push_back("qdot " + c);
  }
  for (const std::string& c : check.coordinates) {
    state.push_back("u " + c);
    state_rate.push_back("udot " + c);
  }
  for (int k = 0; k < ntau; ++k) inputs.push_back("tau " + check.coordinates[check.input[k]]);
  const auto vector_name = [](const std::vector<std::string>& entries) {
    return EntryName([entries](int k) { return "[" + std::to_string(k) + "] (" + entries[k] + ")"; });
  };
  const EntryName names[kRows] = {vector_name(check.coordinates),
                                  matrix_name(check.coordinates, check.coordinates),
                                  matrix_name(check.outputs, check.coordinates),
                                  vector_name(check.outputs),
                                  matrix_name(state_rate, state),
                                  matrix_name(state_rate, inputs)};

  std::vector<Row> rows = empty_rows(check.tolerance);
  for (const ControllerPoint& p : points) {
    const json reply = runner::call_kernels(
        process,
        json{{"t", p.state.t}, {"q", p.state.q}, {"u", p.state.u}, {"tau", p.runner_tau}, {"p", p.runner_p}},
        {"coriolis_matrix", "output_jacobian", "output_jacobian_rate", "linearize"});
    const PointCheck point(p, check);
    Compared compared[kRows];
    const std::size_t n = check.coordinates.size(), ny = check.outputs.size(), nx = 2 * n;
    const Vector C = sized(json_rows_flat(reply["coriolis_matrix"]["C"]), n * n, "coriolis_matrix");
    compared[kCu] = point.velocity_terms(C);
    compared[kSkew] = point.skew(C);
    compared[kJacobian] = point.output_jacobian(
        sized(json_rows_flat(reply["output_jacobian"]["J"]), ny * n, "output_jacobian"));
    compared[kRate] = point.output_jacobian_rate(
        sized(json_numbers(reply["output_jacobian_rate"]["Jdot_u"]), ny, "output_jacobian_rate"));
    std::tie(compared[kA], compared[kB]) = point.linearization(
        sized(json_rows_flat(reply["linearize"]["A"]), nx * nx, "linearize A"),
        sized(json_rows_flat(reply["linearize"]["B"]), nx * static_cast<std::size_t>(ntau), "linearize B"),
        static_cast<int>(reply["linearize"]["returns"].get<double>()));
    for (int j = 0; j < kRows; ++j) {
      const Compared& c = compared[j];
      if (c.reference.empty()) continue;
      rows[j].consider(compare_entries(c.generated, c.reference,
                                       difference_scales(c.reference, c.noise, c.columns, check.tolerance),
                                       names[j], p.sample));
      ++rows[j].compared;
    }
  }
  for (int j : {kJacobian, kRate})
    if (check.outputs.empty()) {
      rows[j].applicable = false;
      rows[j].note = "the model has no outputs";
    }
  if (ntau == 0) {
    rows[kB].applicable = false;
    rows[kB].note = "the model has no inputs";
  }
  return rows;
}

std::vector<Row> controller_rows_not_applicable(const std::string& reason) {
  std::vector<Row> rows = empty_rows(0.0);
  for (Row& r : rows) {
    r.applicable = false;
    r.note = reason;
  }
  return rows;
}

Row controller_absent_row(bool requested) {
  return optional_kernels_absent_row("controller kernels", "numeric path", "--controller", requested);
}

}  // namespace kanegen::verify
