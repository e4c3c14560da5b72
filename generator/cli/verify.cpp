// SPDX-License-Identifier: GPL-2.0-or-later
#include "cli/verify.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <stdexcept>

#include "cli/verify_jacobians.hpp"
#include "cli/verify_power.hpp"
#include "cli/verify_report.hpp"
#include "cli/verify_runner.hpp"
#include "model/expression_eval.hpp"
#include "model/load.hpp"
#include "model/model_error.hpp"
#include "numeric/dynamics.hpp"
#include "numeric/instance.hpp"
#include "numeric/loops.hpp"

namespace kanegen::cli {
namespace {

using nlohmann::json;

constexpr double kPi = 3.14159265358979323846;
constexpr double kInfinity = std::numeric_limits<double>::infinity();
/// A quantity's scale at a state is not taken below this fraction of its
/// largest value over the run, so that a quantity that happens to vanish at
/// one state is not held to round-off of its own (tiny) size.
constexpr double kScaleFloor = 1e-3;
/// Nor below this fraction of the largest entry of the quantity over the
/// run: an entry that is zero by structure (and round-off on one side) is
/// held to round-off of the quantity, not of itself. Round-off of a sum is
/// about 1e-16 of its terms, so 1e-6 leaves the tolerance three orders.
constexpr double kGlobalFloor = 1e-6;

std::string number(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  return buf;
}

std::string list(const std::vector<double>& v) {
  std::string s = "[";
  for (std::size_t i = 0; i < v.size(); ++i) s += (i ? ", " : "") + number(v[i]);
  return s + "]";
}

/// How the runner's arrays line up with the model; checked once, up front,
/// so that kernels of another model (--kernels) are a clear error.
struct Link {
  std::vector<std::string> coordinates;  ///< numeric order, equal to the runner's
  std::vector<int> parameter;            ///< runner parameter k -> index in Model::parameters
  std::vector<int> input;                ///< runner input k -> coordinate
  std::vector<std::string> outputs;      ///< runner output names
  std::vector<std::string> constraints;  ///< loop equations, "<loop>.<row>"
};

/// The names of the loop equations, as the model format gives them.
std::vector<std::string> constraint_names(const numeric::Instance& instance) {
  std::vector<std::string> names;
  for (const numeric::LoopData& l : instance.loops)
    for (const std::string& row : l.rows) names.push_back(l.name + "." + row);
  return names;
}

Link link_runner(const model::Model& model, const numeric::Instance& instance, const json& info) {
  const auto mismatch = [&](const std::string& what) {
    return std::runtime_error("the kernels do not match " + model.source_file + ": " + what);
  };
  Link link;
  link.coordinates = instance.coordinate_names;
  if (info["coordinates"].get<std::vector<std::string>>() != link.coordinates)
    throw mismatch("coordinates " + info["coordinates"].dump() + ", the model's are " +
                   json(link.coordinates).dump() + " (moving joints, then elastic coordinates)");
  if (info["nu"].get<int>() != instance.coordinates())
    throw mismatch("nu = " + info["nu"].dump() + ", expected " + std::to_string(instance.coordinates()));

  for (const std::string& name : info["parameters"].get<std::vector<std::string>>()) {
    const auto found = std::find_if(model.parameters.begin(), model.parameters.end(),
                                    [&](const model::Parameter& p) { return p.name == name; });
    if (found == model.parameters.end()) throw mismatch("parameter '" + name + "' is not in the model");
    link.parameter.push_back(static_cast<int>(found - model.parameters.begin()));
  }
  if (link.parameter.size() != model.parameters.size())
    throw mismatch(std::to_string(link.parameter.size()) + " parameters, the model has " +
                   std::to_string(model.parameters.size()));

  // Inputs: one per joint coordinate (tau_r on speed r, ignored if not
  // actuated; elastic speeds have none), or one per actuated joint.
  const int ntau = info["ntau"].get<int>(), joints = instance.joint_coordinates();
  std::vector<int> actuated;
  for (int r = 0; r < joints; ++r)
    if (instance.joints[instance.coordinate_joint[r]].actuated) actuated.push_back(r);
  if (ntau == joints) {
    for (int r = 0; r < ntau; ++r) link.input.push_back(r);
  } else if (ntau == static_cast<int>(actuated.size())) {
    link.input = actuated;
  } else {
    throw mismatch("ntau = " + std::to_string(ntau) + ", expected one per joint coordinate (" +
                   std::to_string(joints) + ") or per actuated joint (" + std::to_string(actuated.size()) +
                   ")");
  }

  link.constraints = constraint_names(instance);
  const std::vector<std::string> runner_constraints = info.value("constraints", std::vector<std::string>{});
  if (runner_constraints != link.constraints)
    throw mismatch("loop equations " + json(runner_constraints).dump() + ", the model's are " +
                   json(link.constraints).dump());

  link.outputs = info["outputs"].get<std::vector<std::string>>();
  std::vector<std::string> expected;
  for (const model::OutputColumn& column : instance.output_columns) expected.push_back(column.name);
  if (link.outputs != expected)
    throw mismatch("outputs " + json(link.outputs).dump() + ", expected " + json(expected).dump());
  return link;
}

/// The size of each elastic coordinate for random states: displacements of
/// about 1e-3 of the beam's length (rotations of 1e-3 rad), so that the
/// states are those of a small deformation. Modal amplitudes are scaled by
/// the largest nodal displacement of their mode.
std::vector<double> elastic_scales(const numeric::Instance& instance) {
  std::vector<double> scale(instance.coordinates(), 0.0);
  for (const numeric::BodyData& b : instance.bodies) {
    if (!b.beam) continue;
    const numeric::FlexibleData& f = *b.beam;
    double length = 0;
    for (const numeric::BeamElementData& e : f.elements) length += e.length;
    for (int k = 0; k < f.count(); ++k) {
      double translation = 0, rotation = 0;
      for (const auto& [dof, value] : f.basis[k]) {
        const bool turns = f.planar ? dof % 3 == 2 : dof % 6 >= 3;
        (turns ? rotation : translation) = std::max(turns ? rotation : translation, std::abs(value));
      }
      scale[b.elastic_first + k] = translation > 0 ? 1e-3 * length / translation : 1e-3 / rotation;
    }
  }
  return scale;
}

/// One random state with its parameters, the numeric reference and the
/// generated kernels' values.
struct Sample {
  model::ParameterValues parameters;
  numeric::Instance instance;
  numeric::State state;
  std::vector<double> runner_tau, runner_p;
  numeric::Evaluation reference;

  std::vector<double> mass_matrix, forcing, udot, outputs, hessian;
  double kinetic = 0, potential = 0;
  int pivot = 0;
  /// Closed loops: the generated Phi, C (row-major), gamma and lambda (NaN where not solved).
  std::vector<double> phi, jacobian, bias, lambda;
};

/// The generated constrained_dynamics stops at a singular configuration
/// where a Cholesky pivot of S = C_f M_ff^-1 C_f^T (free speeds f), taken in
/// row order, is below 1e-6 of S's largest diagonal entry. A random state is
/// not on the loops, and there the loop equations can be (nearly) dependent
/// where on the manifold they are not (a spatial hinge's alignment rows lose
/// rank where its axis turns across the other body's). Such states are drawn
/// again when the same measure, from the numeric path's M and C, is below
/// kLoopPivotMargin: ten times the cutoff, so that round-off in either never
/// decides whether a state is kept, and the generated kernels cannot excuse
/// themselves (the choice uses the numeric path alone).
constexpr double kLoopPivotMargin = 1e-5;
constexpr int kMaxRedraws = 1000;
/// The unit round-off that a backward-stable solve leaves, with some room.
constexpr double kRoundoff = 1e-15;

/// False where the loop equations are nearly dependent by the measure above.
/// A mass matrix that is not positive definite is not the loops' fault: such
/// a state is kept, and the mass-matrix rows report it.
/// S = C_f M_ff^-1 C_f^T of the numeric path (free speeds f), or an empty
/// matrix where M_ff is not positive definite.
Eigen::MatrixXd saddle_matrix(const numeric::Evaluation& e) {
  const int nc = static_cast<int>(e.phi.size());
  const int n = static_cast<int>(e.forcing.size());
  std::vector<int> free;
  for (int r = 0; r < n; ++r)
    if (std::find(e.prescribed.begin(), e.prescribed.end(), r) == e.prescribed.end()) free.push_back(r);
  const int nf = static_cast<int>(free.size());
  Eigen::MatrixXd mff(nf, nf), cf(nc, nf);
  for (int a = 0; a < nf; ++a) {
    for (int b = 0; b < nf; ++b) mff(a, b) = e.mass_matrix[free[a] * n + free[b]];
    for (int i = 0; i < nc; ++i) cf(i, a) = e.constraint_jacobian[i * n + free[a]];
  }
  const Eigen::LLT<Eigen::MatrixXd> m_factor(mff);
  if (m_factor.info() != Eigen::Success) return {};
  return cf * m_factor.solve(cf.transpose());
}

/// False where the loop equations are nearly dependent by the measure above.
/// A mass matrix that is not positive definite is not the loops' fault: such
/// a state is kept, and the mass-matrix rows report it.
bool loops_independent(const numeric::Evaluation& e) {
  const int nc = static_cast<int>(e.phi.size());
  if (nc == 0) return true;
  const Eigen::MatrixXd s = saddle_matrix(e);
  if (s.size() == 0) return true;
  const double largest = s.diagonal().maxCoeff();
  if (!(largest > 0)) return false;
  const Eigen::LLT<Eigen::MatrixXd> s_factor(s);
  if (s_factor.info() != Eigen::Success) return false;
  const Eigen::MatrixXd l = s_factor.matrixL();
  for (int j = 0; j < nc; ++j)
    if (!(l(j, j) * l(j, j) > kLoopPivotMargin * largest)) return false;
  return true;
}

/// The 2-norm condition number of S (1 without loops or where S is not
/// positive definite, which the other rows report).
double saddle_condition(const numeric::Evaluation& e) {
  if (e.phi.empty()) return 1.0;
  const Eigen::MatrixXd s = saddle_matrix(e);
  if (s.size() == 0) return 1.0;
  const Eigen::VectorXd eigenvalues = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(s).eigenvalues();
  const double smallest = eigenvalues.minCoeff(), largest = eigenvalues.maxCoeff();
  return smallest > 0 ? largest / smallest : 1.0;
}

class Sampler {
 public:
  Sampler(const model::Model& model, const Link& link, const numeric::Instance& base, unsigned long seed,
          double spread)
      : model_(model),
        link_(link),
        base_(base),
        elastic_(elastic_scales(base)),
        rng_(seed),
        spread_(spread) {}

  /// A random state at which the loop equations, if any, are independent.
  Sample draw() {
    for (int attempt = 0; attempt < kMaxRedraws; ++attempt) {
      Sample s = draw_any();
      if (loops_independent(s.reference)) return s;
      ++redrawn_;
    }
    throw model::ModelError(
        model_.source_file, "/loops",
        "the loop equations are (nearly) dependent at " + std::to_string(kMaxRedraws) +
            " random states in a row (a Cholesky pivot of C M^-1 C^T below 1e-5 of its largest diagonal "
            "entry), so verify cannot compare the constrained dynamics",
        "remove redundant loop equations (a planar mechanism needs \"planar\": true loops; see "
        "docs/closed-loops.md, singular configurations)");
  }

  /// How many states were drawn again because their loop equations were nearly dependent.
  int redrawn() const { return redrawn_; }

 private:
  Sample draw_any() {
    Sample s;
    for (const model::Parameter& p : model_.parameters)
      s.parameters[p.name] = p.value != 0 ? p.value * uniform(1 - spread_, 1 + spread_) : uniform(0, spread_);
    s.instance = numeric::instantiate(model_, s.parameters, &base_);
    const int n = s.instance.coordinates(), joints = s.instance.joint_coordinates();
    s.state.t = uniform(0, 10);
    for (int r = 0; r < joints; ++r) {
      const bool slide =
          s.instance.joints[s.instance.coordinate_joint[r]].motion == numeric::Motion::translation;
      s.state.q.push_back(slide ? uniform(-1, 1) : uniform(-kPi, kPi));
      s.state.u.push_back(uniform(-2, 2));
    }
    // Elastic coordinates of a small deformation, rates of 20 such per second.
    for (int r = joints; r < n; ++r) {
      s.state.q.push_back(elastic_[r] * uniform(-1, 1));
      s.state.u.push_back(elastic_[r] * uniform(-20, 20));
    }
    // Inputs that accelerate each joint by up to 10 per s^2 on its own, so
    // they are as large as the other forces and do not drown them.
    s.state.tau.assign(n, 0.0);
    const numeric::Evaluation unforced = numeric::evaluate(s.instance, s.state);
    for (int r = 0; r < joints; ++r) s.state.tau[r] = 10 * unforced.mass_matrix[r * n + r] * uniform(-1, 1);
    s.reference = numeric::evaluate(s.instance, s.state);
    for (int r : link_.input) s.runner_tau.push_back(s.state.tau[r]);
    for (int k : link_.parameter) s.runner_p.push_back(s.parameters.at(model_.parameters[k].name));
    return s;
  }

  double uniform(double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng_); }

  const model::Model& model_;
  const Link& link_;
  const numeric::Instance& base_;
  std::vector<double> elastic_;
  std::mt19937_64 rng_;
  double spread_;
  int redrawn_ = 0;
};

std::vector<double> flatten(const json& rows) {
  std::vector<double> flat;
  for (const json& row : rows)
    for (const json& x : row) flat.push_back(x.is_null() ? std::nan("") : x.get<double>());
  return flat;
}

std::vector<double> numbers(const json& a) {
  std::vector<double> v;
  for (const json& x : a) v.push_back(x.is_null() ? std::nan("") : x.get<double>());
  return v;
}

double scalar(const json& x) { return x.is_null() ? std::nan("") : x.get<double>(); }

void evaluate_generated(RunnerProcess& runner, Sample& s) {
  const json reply = batch_request(runner, json{{"t", s.state.t},
                                                {"q", s.state.q},
                                                {"u", s.state.u},
                                                {"tau", s.runner_tau},
                                                {"p", s.runner_p},
                                                {"kinetic_energy_hessian", true}});
  s.pivot = reply["pivot"].get<int>();
  if (s.pivot == 0) s.udot = numbers(reply["udot"]);
  s.mass_matrix = flatten(reply["mass_matrix"]);
  s.forcing = numbers(reply["forcing"]);
  s.outputs = numbers(reply["outputs"]);
  s.hessian = flatten(reply["kinetic_energy_hessian"]);
  s.kinetic = scalar(reply["kinetic_energy"]);
  s.potential = scalar(reply["potential_energy"]);
  if (reply.contains("constraints")) {
    s.phi = numbers(reply["constraints"]);
    s.jacobian = flatten(reply["constraint_jacobian"]);
    s.bias = numbers(reply["constraint_bias"]);
    s.lambda = reply["lambda"].is_null() ? std::vector<double>(s.phi.size(), std::nan(""))
                                         : numbers(reply["lambda"]);
  }
}

std::string describe(const model::Model& model, const Sample& s) {
  std::string text = "t=" + number(s.state.t) + ", q=" + list(s.state.q) + ", u=" + list(s.state.u) +
                     ", tau=" + list(s.state.tau);
  if (!model.parameters.empty()) {
    text += ", parameters";
    for (const model::Parameter& p : model.parameters)
      text += " " + p.name + "=" + number(s.parameters.at(p.name));
  }
  return text;
}

/// The comparisons of the generated values with the numeric reference and
/// the reference-free checks, one report row each.
class Comparison {
 public:
  Comparison(const Link& link, const std::vector<Sample>& samples, double rtol)
      : link_(link), samples_(samples), rtol_(rtol) {}

  /// A generated quantity against a reference one at every sample, entry
  /// by entry: each entry's error is relative to its own size there (or to
  /// `magnitude`, the sum of the magnitudes of the terms that make it),
  /// floored (see kScaleFloor, kGlobalFloor), so that a small term of one
  /// entry is not hidden by a large other entry (an elastic force next to a
  /// joint torque). `matrix`: an n x n symmetric quantity (M), whose entry
  /// [r,s] is also measured against sqrt(|b_rr b_ss|) (the bound of a
  /// positive semidefinite matrix's entries), so that a coupling that is zero
  /// by structure is held to round-off of its diagonal.
  using Values = std::function<std::vector<double>(const Sample&)>;
  Row vectors(const std::string& quantity, const std::string& against, const Values& generated,
              const Values& reference, const EntryName& name, bool matrix = false,
              const Values& magnitude = nullptr) const {
    Row row(quantity, against, rtol_);
    const std::size_t n = link_.coordinates.size();
    const auto size = [&](const Sample& s) {
      std::vector<double> b = magnitude ? magnitude(s) : reference(s);
      for (double& x : b) x = std::abs(x);
      return b;
    };
    std::vector<double> run;  // per entry: its largest size over the samples
    double all = 0;
    for (const Sample& s : samples_) {
      const std::vector<double> b = size(s);
      run.resize(std::max(run.size(), b.size()), 0.0);
      for (std::size_t k = 0; k < b.size(); ++k) run[k] = std::max(run[k], b[k]);
      all = std::max(all, max_abs(b));
    }
    for (std::size_t i = 0; i < samples_.size(); ++i) {
      const std::vector<double> b = reference(samples_[i]), local = size(samples_[i]);
      std::vector<double> scales(b.size());
      for (std::size_t k = 0; k < b.size(); ++k) {
        scales[k] = scale(std::max(local[k], std::abs(b[k])), run[k], all);
        if (matrix && b.size() == n * n)
          scales[k] = std::max(scales[k], std::sqrt(std::abs(b[k / n * (n + 1)] * b[k % n * (n + 1)])));
      }
      row.consider(compare_entries(generated(samples_[i]), b, scales, name, static_cast<int>(i)));
      ++row.compared;
    }
    return row;
  }

  /// udot by its normwise backward error in the numeric system,
  /// |M udot - f| / (|M| |udot| + |f|) (infinity norms, over the speeds that
  /// are solved for): round-off level whatever the conditioning of M, which
  /// the forward error is not. With loops, in the numeric saddle-point
  /// system with the generated lambda: the rows M udot - C^T lambda = f
  /// (speeds solved for) and C udot = gamma, x = (udot, lambda). A prescribed speed's udot is its prescribed
  /// acceleration, compared as a value (relative to its size, floored by
  /// kScaleFloor of the largest prescribed acceleration of the run).
  Row udot() const {
    Row row("udot", "numeric M udot = f", rtol_);
    const int n = static_cast<int>(link_.coordinates.size());
    double run = 0;
    for (const Sample& s : samples_) run = std::max(run, max_abs(s.reference.prescribed_acceleration));
    for (std::size_t i = 0; i < samples_.size(); ++i) {
      const Sample& s = samples_[i];
      ++row.compared;
      Worst w;
      w.where = static_cast<int>(i);
      if (s.pivot != 0) {
        w.abs = w.rel = kInfinity;
        w.entry = "(the generated LDL^T stopped at pivot " + std::to_string(s.pivot) + ")";
        row.consider(w);
        continue;
      }
      std::vector<char> given(n, 0);
      for (int p : s.reference.prescribed) given[p] = 1;
      const std::vector<double>& M = s.reference.mass_matrix;
      const std::vector<double>& C = s.reference.constraint_jacobian;
      const int nc = static_cast<int>(s.reference.phi.size());
      double residual = 0, norm_m = 0, norm_f = 0, norm_udot = std::max(max_abs(s.udot), max_abs(s.lambda));
      const auto row_done = [&](double sum, double row_sum, double rhs) {
        residual = std::isnan(sum) || std::isnan(residual) ? std::nan("") : std::max(residual, std::abs(sum));
        norm_m = std::max(norm_m, row_sum);
        norm_f = std::max(norm_f, std::abs(rhs));
      };
      for (int r = 0; r < n; ++r) {
        if (given[r]) continue;
        double row_sum = 0, sum = -s.reference.forcing[r];
        for (int c = 0; c < n; ++c) {
          sum += M[r * n + c] * s.udot[c];
          row_sum += std::abs(M[r * n + c]);
        }
        for (int k = 0; k < nc; ++k) {
          sum -= C[k * n + r] * s.lambda[k];
          row_sum += std::abs(C[k * n + r]);
        }
        row_done(sum, row_sum, s.reference.forcing[r]);
      }
      for (int k = 0; k < nc; ++k) {
        double row_sum = 0, sum = -s.reference.constraint_bias[k];
        for (int c = 0; c < n; ++c) {
          sum += C[k * n + c] * s.udot[c];
          row_sum += std::abs(C[k * n + c]);
        }
        row_done(sum, row_sum, s.reference.constraint_bias[k]);
      }
      const std::vector<double> reference =
          s.reference.udot.empty() ? std::vector<double>(n, std::nan("")) : s.reference.udot;
      w = compare(s.udot, reference, 1.0, coordinate_name(), static_cast<int>(i));
      const double denominator = norm_m * norm_udot + norm_f;
      w.rel = std::isnan(residual) ? residual : denominator > 0 ? residual / denominator : residual;
      for (std::size_t k = 0; k < s.reference.prescribed.size(); ++k) {
        const int p = s.reference.prescribed[k];
        const double a = s.reference.prescribed_acceleration[k], d = std::abs(s.udot[p] - a);
        double scale = std::max(std::abs(a), kScaleFloor * run);
        if (scale == 0) scale = 1;
        if (d / scale > w.rel || std::isnan(d)) {
          w.rel = d / scale;
          w.abs = d;
          w.entry = coordinate_name()(p) + " (prescribed acceleration)";
          w.generated = s.udot[p];
          w.numeric = a;
        }
      }
      row.consider(w);
    }
    return row;
  }

  Row symmetry() const {
    return vectors(
        "M symmetric", "M transposed", [](const Sample& s) { return s.mass_matrix; },
        [&](const Sample& s) { return transposed(s.mass_matrix); }, matrix_name(), true);
  }

  /// Every eigenvalue of the generated M positive; the note gives the smallest
  /// ratio of smallest to largest eigenvalue met (1 / condition number).
  Row positive_definite() const {
    Row row("M positive definite", "eigenvalues > 0", 0.0);
    const int n = static_cast<int>(link_.coordinates.size());
    double smallest = kInfinity, eigenvalue = 0;
    int at = -1;
    for (std::size_t i = 0; i < samples_.size(); ++i) {
      const Eigen::MatrixXd M = Eigen::Map<const Eigen::MatrixXd>(samples_[i].mass_matrix.data(), n, n);
      const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(0.5 * (M + M.transpose()),
                                                               Eigen::EigenvaluesOnly);
      const double low = eig.eigenvalues().minCoeff(), high = eig.eigenvalues().maxCoeff();
      const double largest = std::max(std::abs(low), std::abs(high));
      const double ratio = eig.info() == Eigen::Success && largest > 0 ? low / largest : std::nan("");
      ++row.compared;
      if (!(ratio >= smallest)) {
        smallest = ratio;
        eigenvalue = low;
        at = static_cast<int>(i);
      }
      if (std::isnan(ratio)) break;
    }
    Worst w;
    w.where = at;
    w.rel = w.abs = smallest > 0 ? 0.0 : kInfinity;
    w.entry = "(smallest eigenvalue " + number(eigenvalue) + ")";
    w.generated = eigenvalue;
    row.worst = w;
    char note[96];
    std::snprintf(note, sizeof note, "smallest eigenvalue ratio %.3g (sample %d, eigenvalue %.3g)", smallest,
                  at, eigenvalue);
    row.note = note;
    if (!row.passed())
      row.failure = "M positive definite: smallest eigenvalue " + number(eigenvalue) + " of the generated M";
    return row;
  }

  /// M against the Hessian of the generated kinetic energy in u (exact
  /// second differences of a quadratic, computed by the runner).
  Row kinetic_hessian() const {
    return vectors(
        "d2T/du2", "generated M", [](const Sample& s) { return s.hessian; },
        [](const Sample& s) { return s.mass_matrix; }, matrix_name(), true);
  }

  double rtol() const { return rtol_; }
  EntryName coordinate_name() const {
    return [this](int r) { return "[" + std::to_string(r) + "] (" + link_.coordinates[r] + ")"; };
  }
  EntryName matrix_name() const {
    const int n = static_cast<int>(link_.coordinates.size());
    return [this, n](int k) {
      return "[" + std::to_string(k / n) + "," + std::to_string(k % n) + "] (" + link_.coordinates[k / n] +
             ", " + link_.coordinates[k % n] + ")";
    };
  }
  EntryName constraint_name() const {
    return [this](int k) { return "[" + std::to_string(k) + "] (" + link_.constraints[k] + ")"; };
  }
  EntryName jacobian_name() const {
    const int n = static_cast<int>(link_.coordinates.size());
    return [this, n](int k) {
      return "[" + std::to_string(k / n) + "," + std::to_string(k % n) + "] (" + link_.constraints[k / n] +
             ", " + link_.coordinates[k % n] + ")";
    };
  }
  EntryName output_name() const {
    return [this](int k) { return "[" + std::to_string(k) + "] (" + link_.outputs[k] + ")"; };
  }

 private:
  /// An entry's scale: its size, not below kScaleFloor of its largest size
  /// over the run, nor kGlobalFloor of the largest entry of the quantity.
  static double scale(double local, double run, double all) {
    const double s = std::max({local, kScaleFloor * run, kGlobalFloor * all});
    return s == 0 ? 1.0 : s;
  }

  std::vector<double> transposed(const std::vector<double>& m) const {
    const int n = static_cast<int>(link_.coordinates.size());
    std::vector<double> t(m.size());
    for (int r = 0; r < n; ++r)
      for (int c = 0; c < n; ++c) t[c * n + r] = m[r * n + c];
    return t;
  }

  const Link& link_;
  const std::vector<Sample>& samples_;
  double rtol_;
};

/// The runner's parameter defaults, q0 and u0 against the model file.
Row defaults_row(const model::Model& model, const numeric::Instance& defaults, const Link& link,
                 const json& info, double rtol) {
  std::vector<double> generated, reference;
  std::vector<std::string> names;
  const std::vector<double> p = info["parameter_defaults"].get<std::vector<double>>();
  for (std::size_t k = 0; k < p.size(); ++k) {
    generated.push_back(p[k]);
    reference.push_back(model.parameters[link.parameter[k]].value);
    names.push_back("parameter " + model.parameters[link.parameter[k]].name);
  }
  const std::vector<double> q0 = info["q0"].get<std::vector<double>>(),
                            u0 = info["u0"].get<std::vector<double>>();
  // Joints: the model file's q0 and u0, or the prescribed motion at t = 0
  // (its first piece, at the parameters' defaults); elastic coordinates: the
  // model file's values by name, else 0.
  std::vector<double> elastic_q(defaults.coordinates(), 0.0), elastic_u(defaults.coordinates(), 0.0);
  for (const numeric::BodyData& body : defaults.bodies) {
    if (!body.beam) continue;
    const auto in_model = std::find_if(model.bodies.begin(), model.bodies.end(),
                                       [&](const model::Body& b) { return b.name == body.name; });
    for (int k = 0; k < body.beam->count(); ++k) {
      const std::string& name = body.beam->names[k];
      const auto q = in_model->beam.initial_q.find(name), u = in_model->beam.initial_u.find(name);
      if (q != in_model->beam.initial_q.end()) elastic_q[body.elastic_first + k] = q->second;
      if (u != in_model->beam.initial_u.end()) elastic_u[body.elastic_first + k] = u->second;
    }
  }
  for (int r = 0; r < defaults.coordinates(); ++r) {
    double q = elastic_q[r], u = elastic_u[r];
    if (r < defaults.joint_coordinates()) {
      const model::Joint& j = model.joints[defaults.coordinate_joint[r]];
      q = j.q0;
      u = j.u0;
      if (j.is_prescribed()) {
        numeric::JointData first = defaults.joints[defaults.coordinate_joint[r]];
        first.prescribed.resize(1);
        first.prescribed[0].has_until = false;
        const std::array<double, 3> motion = numeric::prescribed_motion(first, 0.0);
        q = motion[0];
        u = motion[1];
      }
    }
    generated.insert(generated.end(), {q0.at(r), u0.at(r)});
    reference.insert(reference.end(), {q, u});
    names.insert(names.end(), {"q0 " + link.coordinates[r], "u0 " + link.coordinates[r]});
  }
  Row row("defaults", "model file", rtol);
  row.where_kind = "info";
  row.consider(compare(
      generated, reference, std::max(1.0, max_abs(reference)), [&](int k) { return names[k]; }, 0));
  row.compared = 1;
  return row;
}

std::string failure_message(const Row& r, const std::string& state) {
  if (!r.failure.empty())
    return r.failure + " at " + r.where_kind + " " + std::to_string(r.worst.where) +
           (state.empty() ? "" : "; " + state);
  char errors[128];
  std::snprintf(errors, sizeof errors, " (abs error %.3g, error measure %.3g > tolerance %.3g)", r.worst.abs,
                r.worst.rel, r.tolerance);
  std::string m = r.quantity + " " + r.worst.entry + ": generated " + number(r.worst.generated) + ", " +
                  r.against + " " + number(r.worst.numeric) + errors + " at " + r.where_kind + " " +
                  std::to_string(r.worst.where);
  return state.empty() ? m : m + "; " + state;
}

void check_options(const VerifyOptions& o) {
  if (o.samples < 1) throw std::invalid_argument("--samples must be at least 1");
  if (!(o.rtol > 0)) throw std::invalid_argument("--rtol must be positive");
  if (!(o.spread >= 0 && o.spread < 1)) throw std::invalid_argument("--spread must be in [0, 1)");
  if (o.trajectories < 0 || !(o.duration > 0))
    throw std::invalid_argument("--trajectories >= 0, --duration > 0");
}

/// A progress line on stderr, with --verbose (that is, without --quiet).
void progress(const VerifyOptions& o, const std::string& line) {
  if (o.build.verbose) std::fprintf(stderr, "kanegen: verify: %s\n", line.c_str());
}

/// The random states with the generated kernels' values at each.
std::vector<Sample> draw_samples(RunnerProcess& process, const model::Model& model, const Link& link,
                                 const numeric::Instance& base, const VerifyOptions& o) {
  Sampler sampler(model, link, base, o.seed, o.spread);
  std::vector<Sample> samples;
  for (int i = 0; i < o.samples; ++i) {
    samples.push_back(sampler.draw());
    evaluate_generated(process, samples.back());
  }
  if (sampler.redrawn() > 0)
    progress(
        o, std::to_string(sampler.redrawn()) +
               " random states had (nearly) dependent loop equations and were drawn again (docs/verify.md)");
  return samples;
}

/// Closed loops: the loop kernels and the loop forces (numeric/loops.hpp).
void add_loop_rows(const Comparison& c, const Link& link, std::vector<Row>& rows) {
  const auto loop_row = [&](const std::string& quantity, const std::string& against,
                            const Comparison::Values& generated, const Comparison::Values& reference,
                            const EntryName& name) {
    rows.push_back(c.vectors(quantity, against, generated, reference, name));
    if (link.constraints.empty()) {
      rows.back().applicable = false;
      rows.back().note = "the model has no loops";
    }
  };
  loop_row(
      "constraints", "numeric Phi", [](const Sample& s) { return s.phi; },
      [](const Sample& s) { return s.reference.phi; }, c.constraint_name());
  loop_row(
      "constraint_jacobian", "numeric dPhi/dq (duals)", [](const Sample& s) { return s.jacobian; },
      [](const Sample& s) { return s.reference.constraint_jacobian; }, c.jacobian_name());
  loop_row(
      "constraint_bias", "numeric -(dC/dt) u (duals)", [](const Sample& s) { return s.bias; },
      [](const Sample& s) { return s.reference.constraint_bias; }, c.constraint_name());
  // lambda is only as accurate as S = C M^-1 C^T is conditioned (many loops
  // in a random, unclosed state can make it 1e10): its entries are measured
  // against their size times kappa(S) eps / rtol where that exceeds 1, the
  // forward error that a backward-stable solve may leave. The backward error
  // of (udot, lambda) together, which no conditioning excuses, is the udot row.
  const double rtol = c.rtol();
  rows.push_back(c.vectors(
      "lambda", "numeric lambda", [](const Sample& s) { return s.lambda; },
      [](const Sample& s) {
        return s.reference.lambda.empty() ? std::vector<double>(s.reference.phi.size(), std::nan(""))
                                          : s.reference.lambda;
      },
      c.constraint_name(), false,
      [rtol](const Sample& s) {
        std::vector<double> size = s.reference.lambda;
        const double allowance = std::max(1.0, saddle_condition(s.reference) * kRoundoff / rtol);
        for (double& v : size) v = std::abs(v) * allowance;
        return size;
      }));
  if (link.constraints.empty()) {
    rows.back().applicable = false;
    rows.back().note = "the model has no loops";
  }
}

/// The generated values against the numeric reference, and the checks of M
/// that need none.
void add_comparison_rows(const Comparison& c, const Link& link, std::vector<Row>& rows) {
  rows.push_back(c.vectors(
      "mass_matrix", "numeric M", [](const Sample& s) { return s.mass_matrix; },
      [](const Sample& s) { return s.reference.mass_matrix; }, c.matrix_name(), true));
  rows.push_back(c.vectors(
      "forcing", "numeric f", [](const Sample& s) { return s.forcing; },
      [](const Sample& s) { return s.reference.forcing; }, c.coordinate_name(), false,
      [](const Sample& s) { return s.reference.forcing_magnitude; }));
  rows.push_back(c.udot());
  rows.push_back(c.vectors(
      "kinetic_energy", "numeric T", [](const Sample& s) { return std::vector<double>{s.kinetic}; },
      [](const Sample& s) { return std::vector<double>{s.reference.kinetic_energy}; },
      [](int) { return std::string(); }));
  rows.push_back(c.vectors(
      "potential_energy", "numeric V", [](const Sample& s) { return std::vector<double>{s.potential}; },
      [](const Sample& s) { return std::vector<double>{s.reference.potential_energy}; },
      [](int) { return std::string(); }));
  rows.push_back(c.vectors(
      "outputs", "numeric outputs", [](const Sample& s) { return s.outputs; },
      [](const Sample& s) { return s.reference.outputs; }, c.output_name()));
  if (link.outputs.empty()) {
    rows.back().applicable = false;
    rows.back().note = "the model has no outputs";
  }
  add_loop_rows(c, link, rows);
  rows.push_back(c.symmetry());
  rows.push_back(c.positive_definite());
  rows.push_back(c.kinetic_hessian());
}

/// The power balance along the trajectory from sample k's state, with its
/// prescribed speeds on their motion.
Worst trajectory_power_balance(RunnerProcess& process, const Sample& s, int k, double duration,
                               long* points) {
  TrajectoryStart from{&s.instance, s.state, s.runner_tau, s.runner_p};
  std::vector<int> prescribed;
  for (int r = 0; r < s.instance.joint_coordinates(); ++r) {
    const numeric::JointData& j = s.instance.joints[s.instance.coordinate_joint[r]];
    if (!j.is_prescribed()) continue;
    const std::array<double, 3> motion = numeric::prescribed_motion(j, s.state.t);
    from.state.q[r] = motion[0];
    from.state.u[r] = motion[1];
    prescribed.push_back(r);
  }
  // Closed loops: from the state projected onto the constraints (off
  // them a random slider-crank's rod soon turns across the slide, a
  // singular configuration), and if that runs into one too (a projected
  // parallelogram may land on its folded, singular branch), from the
  // state as drawn; the loop forces' power makes both valid (docs/verify.md).
  TrajectoryStart projected = from;
  const bool loops =
      !s.instance.loops.empty() &&
      numeric::project_onto_loops(s.instance, prescribed, projected.state.q, projected.state.u);
  Worst w = power_balance(process, loops ? projected : from, duration, k, points);
  if (loops && std::isinf(w.rel) && w.entry.rfind("(integration failed", 0) == 0)
    w = power_balance(process, from, duration, k, points);
  return w;
}

Row power_balance_row(RunnerProcess& process, const std::vector<Sample>& samples, const VerifyOptions& o) {
  Row power("power balance", "integral of numeric P_nc", 100 * o.rtol);
  power.where_kind = "trajectory";
  const int trajectories = std::min(o.trajectories, o.samples);
  if (trajectories == 0) {
    power.applicable = false;
    power.note = "--trajectories 0";
    return power;
  }
  char line[96];
  std::snprintf(line, sizeof line, "%d trajectories of %g s for the power balance ...", trajectories,
                o.duration);
  progress(o, line);
  for (int k = 0; k < trajectories; ++k)
    power.consider(trajectory_power_balance(process, samples[k], k, o.duration, &power.compared));
  return power;
}

/// The Jacobian kernels are compared at this many of the samples (each
/// costs 8 numeric evaluations per coordinate).
constexpr int kJacobianSamples = 10;
/// Their tolerance when --rtol is smaller: that of the differences they are
/// compared with (the round-off of the differences is allowed for apart).
constexpr double kJacobianTolerance = 1e-6;

/// The Jacobian kernels against differences of the numeric path (verify_jacobians.hpp), if the kernels have
/// them.
void add_jacobian_rows(RunnerProcess& process, const json& info, const numeric::Instance& base,
                       const Link& link, const std::vector<Sample>& samples, const VerifyOptions& o,
                       std::vector<Row>& rows) {
  if (!info.value("jacobians", false)) {
    rows.push_back(jacobians_absent_row(o.build.jacobians));
    return;
  }
  JacobianCheck check;
  check.coordinates = link.coordinates;
  check.size = elastic_scales(base);
  check.joints = base.joint_coordinates();
  for (int r = 0; r < check.joints; ++r) check.size[r] = 1.0;
  check.tolerance = std::max(o.rtol, kJacobianTolerance);
  check.seed = o.seed;
  std::vector<JacobianPoint> points;
  for (int i = 0; i < std::min(o.samples, kJacobianSamples); ++i)
    points.push_back({&samples[i].instance, samples[i].state, samples[i].runner_tau, samples[i].runner_p, i});
  progress(o, "the Jacobian kernels at " + std::to_string(points.size()) +
                  " states against differences of the numeric path ...");
  for (Row& r : jacobian_rows(process, points, check)) rows.push_back(std::move(r));
}

/// Each failed row's message, with the state it failed at.
std::vector<std::string> failures_of(const std::vector<Row>& rows, const model::Model& model,
                                     const std::vector<Sample>& samples) {
  std::vector<std::string> failures;
  for (const Row& r : rows) {
    if (r.passed()) continue;
    const bool at_sample = r.where_kind == "sample" || r.where_kind == "trajectory";
    const std::string state = !at_sample || r.worst.where < 0
                                  ? std::string()
                                  : (r.where_kind == "trajectory" ? "from state " : "state ") +
                                        describe(model, samples[r.worst.where]);
    failures.push_back(failure_message(r, state));
  }
  return failures;
}

/// The report on stdout (a table or JSON), the failures on stderr.
void print_report(const ReportHeader& header, const std::vector<Row>& rows,
                  const std::vector<std::string>& failures, bool json) {
  if (json) {
    std::printf("%s\n", report_json(header, rows, failures).dump(2).c_str());
  } else {
    print_table(stdout, header, rows);
    std::printf("%s: %s in %.2f s\n", header.model.c_str(), failures.empty() ? "verified" : "MISMATCH",
                header.seconds);
  }
  std::fflush(stdout);
  for (const std::string& f : failures) std::fprintf(stderr, "error: %s\n", f.c_str());
}

}  // namespace

int verify(const VerifyOptions& o) {
  check_options(o);
  const auto start = std::chrono::steady_clock::now();
  const model::Model model = model::load_model(o.model, o.build.load);
  const std::string runner = o.kernels_dir.empty() ? build_runner(o.model, o.build)
                                                   : build_runner_from_directory(o.kernels_dir, o.build);
  const json info = runner_info(runner);
  const numeric::Instance base = numeric::instantiate(model, model::default_parameter_values(model));
  const Link link = link_runner(model, base, info);

  progress(o, std::to_string(o.samples) + " random states of " + model.name +
                  " against the numeric derivation ...");
  RunnerProcess process(runner, {"batch"});
  const std::vector<Sample> samples = draw_samples(process, model, link, base, o);
  std::vector<Row> rows;
  rows.push_back(defaults_row(model, base, link, info, o.rtol));
  add_comparison_rows(Comparison(link, samples, o.rtol), link, rows);
  rows.push_back(power_balance_row(process, samples, o));
  add_jacobian_rows(process, info, base, link, samples, o, rows);
  process.finish();

  const std::vector<std::string> failures = failures_of(rows, model, samples);
  const ReportHeader header{model.name,
                            static_cast<int>(link.coordinates.size()),
                            static_cast<int>(model.parameters.size()),
                            o.samples,
                            o.seed,
                            o.rtol,
                            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()};
  print_report(header, rows, failures, o.json);
  return failures.empty() ? 0 : 1;
}

}  // namespace kanegen::cli
