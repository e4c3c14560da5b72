// SPDX-License-Identifier: GPL-2.0-or-later
#include "cli/modes.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "cli/linearize.hpp"
#include "fem/modal.hpp"
#include "model/load.hpp"
#include "model/model_error.hpp"
#include "runner/runner_process.hpp"
#include "symbolic/variables.hpp"

namespace kanegen::cli {
namespace {

using nlohmann::json;
using nlohmann::ordered_json;

constexpr double kPi = 3.14159265358979323846;
/// |omega^2| below this fraction of the largest is reported as 0 (a rigid-body
/// mode): the eigensolver's round-off is about 1e-16 of the largest, and the
/// central differences' is smaller still for any sensible step.
constexpr double kZeroEigenvalue = 1e-12;

std::string join(const std::vector<std::string>& names) {
  std::string s;
  for (const std::string& n : names) s += (s.empty() ? "" : ", ") + n;
  return s.empty() ? "none" : s;
}

/// Applies NAME=VALUE assignments (`option`: --set, --q0, --u0) to `values`, indexed like `names`.
void assign(const std::vector<std::string>& sets, const char* option, const char* what,
            const std::vector<std::string>& names, std::vector<double>& values) {
  for (const std::string& set : sets) {
    const std::string given = std::string(option) + " '" + set + "': ";
    const std::size_t eq = set.find('=');
    if (eq == std::string::npos || eq == 0) throw std::runtime_error(given + "expected NAME=VALUE");
    const std::string name = set.substr(0, eq), text = set.substr(eq + 1);
    const auto at = std::find(names.begin(), names.end(), name);
    if (at == names.end())
      throw std::runtime_error(given + "unknown " + what + " '" + name + "'; " + what + "s: " + join(names));
    char* end = nullptr;
    const double v = std::strtod(text.c_str(), &end);
    if (text.empty() || *end != '\0' || !std::isfinite(v))
      throw std::runtime_error(given + "'" + text + "' is not a finite number");
    values[static_cast<std::size_t>(at - names.begin())] = v;
  }
}

/// A prescribed coordinate at t = 0: position, speed and acceleration.
struct Prescribed {
  double q = 0, u = 0, a = 0;
};

Prescribed prescribed_at_start(const model::Model& model, const model::Joint& joint,
                               const std::map<std::string, double>& parameters) {
  const symbolic::Variables vars(model);
  GiNaC::exmap values{{vars.t, 0}};
  for (std::size_t i = 0; i < model.parameters.size(); ++i)
    values[vars.params[i]] = GiNaC::numeric(parameters.at(model.parameters[i].name));
  // The piece in force at t = 0 (as the generated code chooses it).
  const auto piece =
      std::find_if(joint.prescribed.begin(), joint.prescribed.end(),
                   [](const model::PrescribedPiece& p) { return !p.has_until || 0.0 < p.until; });
  const GiNaC::ex q = vars.time_expression(piece->q, piece->where);
  const auto at_start = [&](const GiNaC::ex& e, const char* what) {
    const GiNaC::ex v = GiNaC::evalf(e.subs(values));
    const double x = GiNaC::is_a<GiNaC::numeric>(v) && GiNaC::ex_to<GiNaC::numeric>(v).is_real()
                         ? GiNaC::ex_to<GiNaC::numeric>(v).to_double()
                         : std::nan("");
    if (!std::isfinite(x))
      throw model::ModelError(model.source_file, piece->where,
                              std::string("the prescribed ") + what + " of joint '" + joint.name +
                                  "' has no finite value at t = 0",
                              "give a motion that is smooth at t = 0");
    return x;
  };
  return {at_start(q, "position"), at_start(q.diff(vars.t), "speed"),
          at_start(q.diff(vars.t, 2), "acceleration")};
}

/// Throws if M is not positive definite, naming the first coordinate whose
/// pivot of M = L D L^T (in the given order) is not positive.
void require_positive_definite(const Eigen::MatrixXd& M, const std::vector<std::string>& names,
                               const std::string& file) {
  const int n = static_cast<int>(M.rows());
  const double scale = std::max(M.diagonal().cwiseAbs().maxCoeff(), 1e-300);
  Eigen::MatrixXd L = Eigen::MatrixXd::Identity(n, n);
  Eigen::VectorXd d(n);
  for (int j = 0; j < n; ++j) {
    d[j] = M(j, j);
    for (int k = 0; k < j; ++k) d[j] -= L(j, k) * L(j, k) * d[k];
    if (!(d[j] > 1e-12 * scale)) {
      const std::string name = "'" + names[j] + "'";
      throw std::runtime_error(
          file + ": the mass matrix of the eigen-coordinates is singular at the initial state: " +
          "coordinate " + name + " adds no inertia (a zero pivot of M = L D L^T); give the " +
          "bodies that " + name + " moves mass or inertia, or leave it out (drop --free-joints)");
    }
    for (int i = j + 1; i < n; ++i) {
      double s = M(i, j);
      for (int k = 0; k < j; ++k) s -= L(i, k) * L(j, k) * d[k];
      L(i, j) = s / d[j];
    }
  }
}

ordered_json matrix_json(const Eigen::MatrixXd& m) {
  ordered_json rows = ordered_json::array();
  for (Eigen::Index i = 0; i < m.rows(); ++i) {
    ordered_json row = ordered_json::array();
    for (Eigen::Index j = 0; j < m.cols(); ++j) row.push_back(m(i, j));
    rows.push_back(row);
  }
  return rows;
}

/// The operating point and the eigen-coordinates.
struct Problem {
  OperatingPoint point;
  LinearizeOptions linearize;
  std::vector<std::string> names;  ///< of the selected coordinates
  std::vector<std::string> parameter_names;
  ordered_json held = ordered_json::array(), prescribed = ordered_json::array();
};

Problem set_up(const model::Model& model, const json& info, const ModesOptions& options) {
  const auto coordinates = info.at("coordinates").get<std::vector<std::string>>();
  const auto speeds = info.at("speeds").get<std::vector<std::string>>();
  const int nq = info.at("nq").get<int>();
  if (info.at("nu").get<int>() != nq)
    throw std::runtime_error(model.source_file +
                             ": kanegen modes linearizes in coordinates whose rates are the speeds, and this "
                             "model turns a spherical or free joint by a quaternion; simulate it instead, or "
                             "build the joint from revolute joints for its modes (docs/model-format.md)");
  Problem pb;
  pb.parameter_names = info.at("parameters").get<std::vector<std::string>>();
  OperatingPoint& point = pb.point;
  point.p = info.at("parameter_defaults").get<std::vector<double>>();
  assign(options.sets, "--set", "parameter", pb.parameter_names, point.p);
  std::map<std::string, double> parameters;
  for (std::size_t k = 0; k < pb.parameter_names.size(); ++k) parameters[pb.parameter_names[k]] = point.p[k];
  point.q = info.at("q0").get<std::vector<double>>();
  point.u = info.at("u0").get<std::vector<double>>();
  assign(options.q0, "--q0", "coordinate", coordinates, point.q);
  assign(options.u0, "--u0", "speed", speeds, point.u);

  // Joint coordinates come first, in file order, then the elastic ones.
  LinearizeOptions& lin = pb.linearize;
  lin.other_accelerations.assign(static_cast<std::size_t>(nq), 0.0);
  lin.velocity = options.matrices;
  lin.step = options.step;
  const bool flexible =
      std::any_of(model.bodies.begin(), model.bodies.end(), [](const auto& b) { return b.flexible; });
  const bool joints_in = options.free_joints || !flexible;
  int index = 0;
  for (const model::Joint& joint : model.joints) {
    if (!joint.moves()) continue;
    if (index >= nq || coordinates[index] != joint.name)
      throw std::runtime_error("the runner's coordinates do not match " + model.source_file);
    if (joint.is_prescribed()) {
      for (const auto& [option, given] : {std::pair{"--q0", &options.q0}, std::pair{"--u0", &options.u0}})
        for (const std::string& set : *given)
          if (set.rfind(coordinates[index] + "=", 0) == 0 || set.rfind(speeds[index] + "=", 0) == 0)
            throw std::runtime_error(
                std::string(option) + " '" + set + "': joint '" + joint.name +
                "' is prescribed, so its state at t = 0 is given by the model; drop the option");
      const Prescribed p = prescribed_at_start(model, joint, parameters);
      point.q[index] = p.q;
      point.u[index] = p.u;
      lin.other_accelerations[index] = p.a;
      pb.prescribed.push_back({{"joint", joint.name}, {"q", p.q}, {"u", p.u}, {"acceleration", p.a}});
    } else if (joints_in) {
      lin.selected.push_back(index);
    } else {
      pb.held.push_back(joint.name);
    }
    ++index;
  }
  for (int k = index; k < nq; ++k) lin.selected.push_back(k);
  if (lin.selected.empty())
    throw std::runtime_error(model.source_file +
                             ": nothing to analyse: every joint is prescribed and there is no flexible body");
  for (int k : lin.selected) pb.names.push_back(coordinates[k]);
  return pb;
}

/// The first `shown` modes as JSON; `first_unstable`: the index of the first mode with omega^2 < 0, or -1.
ordered_json modes_json(const fem::ModalBasis& basis, const std::vector<std::string>& names, int shown,
                        int& first_unstable) {
  const int n = static_cast<int>(names.size()), count = static_cast<int>(basis.eigenvalues.size());
  const double scale = basis.eigenvalues.cwiseAbs().maxCoeff();
  ordered_json modes = ordered_json::array();
  first_unstable = -1;
  for (int i = 0; i < count; ++i) {
    double lambda = basis.eigenvalues[i];
    if (std::abs(lambda) <= kZeroEigenvalue * scale) lambda = 0.0;
    const bool stable = lambda >= 0.0;
    if (!stable && first_unstable < 0) first_unstable = i;
    if (i >= shown) continue;
    const double omega = std::sqrt(std::max(lambda, 0.0));
    ordered_json mode{{"mode", i + 1},
                      {"eigenvalue", lambda},
                      {"omega_rad_s", omega},
                      {"frequency_hz", omega / (2.0 * kPi)},
                      {"stable", stable}};
    if (!stable) mode["growth_rate"] = std::sqrt(-lambda);
    ordered_json shape = ordered_json::object();
    for (int k = 0; k < n; ++k) shape[names[k]] = basis.shapes(k, i);
    mode["shape"] = shape;
    modes.push_back(mode);
  }
  return modes;
}

/// Whether a flexible body carries its geometric stiffness in the nonlinear
/// axial strain (nodal coordinates with stiffening, fem/axial_strain.hpp):
/// its stiffening lives in the axial stretch of the loaded equilibrium.
bool stiffens_by_strain(const model::Model& model) {
  return std::any_of(model.bodies.begin(), model.bodies.end(), [](const model::Body& b) {
    return b.flexible && b.elastic.geometric_stiffening && b.elastic.modes == 0 &&
           b.elastic.assumed_modes.empty();
  });
}

/// Moves the elastic coordinates of the operating point to the equilibrium
/// of their own equations, r_e(q) = 0 with every joint held at its initial
/// state (or prescribed), by Newton's method on the linearisation of those
/// rows alone (dq_e = K_ee^-1 r_e). Returns the iterations taken; throws if
/// K_ee is singular or Newton does not converge.
int find_elastic_equilibrium(runner::RunnerProcess& process, Problem& pb, const std::vector<bool>& elastic,
                             const std::string& file) {
  LinearizeOptions lin = pb.linearize;
  lin.velocity = false;
  lin.selected.clear();
  for (std::size_t i = 0; i < elastic.size(); ++i)
    if (elastic[i]) lin.selected.push_back(pb.linearize.selected[i]);
  for (int iteration = 1; iteration <= 30; ++iteration) {
    const Linearization lz = linearize(process, pb.point, lin);
    const Eigen::FullPivLU<Eigen::MatrixXd> lu(lz.stiffness);
    if (!lu.isInvertible())
      throw std::runtime_error(file +
                               ": no elastic equilibrium near the initial state (the elastic stiffness "
                               "is singular there: a mechanism, or a load at buckling)");
    const Eigen::VectorXd dq = lu.solve(lz.forcing);
    double step = 0.0, size = 0.0;
    for (std::size_t i = 0; i < lin.selected.size(); ++i) {
      double& q = pb.point.q[static_cast<std::size_t>(lin.selected[i])];
      q += dq[static_cast<Eigen::Index>(i)];
      step = std::max(step, std::abs(dq[static_cast<Eigen::Index>(i)]));
      size = std::max(size, std::abs(q));
    }
    // Converged when the step is round-off beside the largest coordinate
    // (or zero: an unloaded body stays at 0).
    if (step <= 1e-12 * size || step == 0.0) return iteration;
  }
  throw std::runtime_error(file +
                           ": no elastic equilibrium near the initial state after 30 Newton steps (the "
                           "loads may be past buckling); the modes need the prestressed equilibrium");
}

/// The modes on the loops' tangent space: the motions dq = N z of the
/// eigen-coordinates with C dq = 0 (N an orthonormal basis of C's null
/// space), K phi = omega^2 M phi reduced to N^T K N z = omega^2 N^T M N z,
/// the shapes N z (mass-normalised, largest entry positive).
fem::ModalBasis modes_on_loops(const Eigen::MatrixXd& M, const Eigen::MatrixXd& K, const Eigen::MatrixXd& C,
                               const std::string& file) {
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(C, Eigen::ComputeFullV);
  const Eigen::VectorXd& sigma = svd.singularValues();
  int rank = 0;
  while (rank < sigma.size() && sigma[rank] > 1e-10 * sigma[0]) ++rank;
  const Eigen::Index n = C.cols();
  if (rank == n)
    throw std::runtime_error(
        file +
        ": the loops leave the eigen-coordinates no motion at the initial state (the "
        "mechanism is driven or held rigid): free its joints (--free-joints), or compute "
        "the modes of the open tree (remove \"loops\")");
  const Eigen::MatrixXd N = svd.matrixV().rightCols(n - rank);
  fem::ModalBasis basis = fem::modal_analysis(N.transpose() * M * N, N.transpose() * K * N);
  basis.shapes = N * basis.shapes;
  for (Eigen::Index j = 0; j < basis.shapes.cols(); ++j) {
    Eigen::Index largest = 0;
    basis.shapes.col(j).cwiseAbs().maxCoeff(&largest);
    if (basis.shapes(largest, j) < 0) basis.shapes.col(j) *= -1.0;
  }
  return basis;
}

}  // namespace

int modes(const ModesOptions& options) {
  const model::Model model = model::load_model(options.model, options.build.load);
  // The elastic equilibrium moves the elastic coordinates alone, which would leave the loops open.
  if (!model.loops.empty() && stiffens_by_strain(model))
    throw model::ModelError(
        model.source_file, model.loops.front().where,
        "kanegen modes does not take closed loops with a nodal beam's geometric stiffening",
        "set \"geometric_stiffening\": false on the beams in the loops, use modes, or "
        "compute the modes of the open tree (remove \"loops\")");
  const std::string runner = runner::build_runner(options.model, options.build);
  const json info = runner::runner_info(runner);
  Problem pb = set_up(model, info, options);
  const int joint_count = static_cast<int>(std::count_if(model.joints.begin(), model.joints.end(),
                                                         [](const model::Joint& j) { return j.moves(); }));
  std::vector<bool> elastic;
  for (int k : pb.linearize.selected) elastic.push_back(k >= joint_count);

  Linearization lz;
  int equilibrium_iterations = 0;
  {
    runner::RunnerProcess process(runner, {"batch"});
    if (stiffens_by_strain(model))
      equilibrium_iterations = find_elastic_equilibrium(process, pb, elastic, model.source_file);
    if (!model.loops.empty()) {
      // The loop forces of the model's own constrained dynamics at the state, held at their value: their
      // geometric stiffness enters K (a load carried through a loop stiffens or softens it).
      const json reply =
          runner::call_kernels(
              process, json{{"t", pb.point.t}, {"q", pb.point.q}, {"u", pb.point.u}, {"p", pb.point.p}},
              {"constrained_dynamics"})
              .at("constrained_dynamics");
      if (reply.at("returns").get<double>() != 0)
        throw std::runtime_error(model.source_file +
                                 ": the loops are singular at the initial state (no loop forces); choose a "
                                 "state where they are independent");
      pb.linearize.loop_forces = reply.at("lambda").get<std::vector<double>>();
    }
    lz = linearize(process, pb.point, pb.linearize);
    if (process.finish() != 0) throw std::runtime_error(runner + " batch failed");
  }
  require_positive_definite(lz.mass, pb.names, model.source_file);
  const Eigen::MatrixXd M = (lz.mass + lz.mass.transpose()) / 2.0;
  const Eigen::MatrixXd K = (lz.stiffness + lz.stiffness.transpose()) / 2.0;
  const double k_norm = K.norm();
  const double asymmetry =
      k_norm > 0 ? (lz.stiffness - lz.stiffness.transpose()).norm() / (2.0 * k_norm) : 0.0;
  const fem::ModalBasis basis =
      lz.loops.rows() > 0 ? modes_on_loops(M, K, lz.loops, model.source_file) : fem::modal_analysis(M, K);
  const int n = static_cast<int>(pb.names.size()), count = static_cast<int>(basis.eigenvalues.size());
  int first_unstable = -1;
  const ordered_json modes =
      modes_json(basis, pb.names, options.count > 0 ? std::min(options.count, count) : count, first_unstable);

  ordered_json out{{"model", info.at("name").get<std::string>()}, {"time", pb.point.t}};
  ordered_json params = ordered_json::object();
  for (std::size_t k = 0; k < pb.parameter_names.size(); ++k) params[pb.parameter_names[k]] = pb.point.p[k];
  out["parameters"] = params;
  out["coordinates"] = pb.names;
  if (equilibrium_iterations > 0) {
    // The operating point's elastic coordinates, moved to their equilibrium.
    ordered_json at = ordered_json::object();
    for (std::size_t i = 0; i < pb.names.size(); ++i)
      if (elastic[i]) at[pb.names[i]] = pb.point.q[static_cast<std::size_t>(pb.linearize.selected[i])];
    out["equilibrium"] = {{"newton_steps", equilibrium_iterations}, {"q", at}};
  }
  out["held"] = pb.held;
  out["prescribed"] = pb.prescribed;
  if (!model.loops.empty()) out["loop_forces"] = pb.linearize.loop_forces;
  out["stable"] = first_unstable < 0;
  out["stiffness_asymmetry"] = asymmetry;
  out["modes"] = modes;
  if (options.matrices)
    out["matrices"] = {{"mass", matrix_json(lz.mass)},
                       {"stiffness", matrix_json(lz.stiffness)},
                       {"velocity", matrix_json(lz.velocity)},
                       {"forcing", std::vector<double>(lz.forcing.data(), lz.forcing.data() + n)}};
  std::printf("%s\n", out.dump(2).c_str());
  if (first_unstable >= 0) {
    const double lambda = basis.eigenvalues[first_unstable];
    std::fprintf(
        stderr,
        "error: %s: the model linearised about its initial state is unstable: mode %d has omega^2 = %.6g "
        "1/s^2 (it grows like exp(%.6g t)); the modes are printed with \"stable\": false. An unstable "
        "mode is a divergence, e.g. an upright pendulum, a compressive load past buckling or a beam "
        "spun past its first bending frequency without geometric stiffening\n",
        model.source_file.c_str(), first_unstable + 1, lambda, std::sqrt(-lambda));
    return 1;
  }
  return 0;
}

}  // namespace kanegen::cli
