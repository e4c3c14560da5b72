// SPDX-License-Identifier: GPL-2.0-or-later
// Consistency of the generated equations of motion with MuJoCo.
//
// For the shipped URDF models (arm7, chain20) and a branched tree with slides
// (data/mixed_tree.urdf, generated with the recursive forward_dynamics), at random states, the
// generated kernels must reproduce what MuJoCo computes from the same file:
//   mass_matrix       == M            (mj_fullM of qM)
//   forcing (tau = 0) == qfrc_passive - qfrc_bias   (gravity + velocity terms)
//   forward_dynamics  == qacc_smooth  (M^-1 f; contacts/constraints excluded)
// The MuJoCo side is itself checked against closed forms on a pendulum and on
// a branched tree whose joint order differs from MuJoCo's DOF order; those
// cases do not need the generator.
#include <Eigen/Dense>
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "mujoco_reference.hpp"

#if KANEGEN_HAVE_GENERATED_MODELS
#include <arm7.hpp>
#include <chain20.hpp>
#include <mixed_tree.hpp>
#endif

using kanegen_consistency::MujocoDynamics;
using kanegen_consistency::MujocoReference;

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kG = 9.81;

// Error of a against the reference b, for a whole quantity (M, f or udot):
//   max_i |a_i - b_i| / max(1, max_i |b_i|).
// Entries of one quantity span orders of magnitude and some are exactly zero,
// so entry-wise relative errors would be meaningless. Dividing by the largest
// reference entry makes the error relative to the quantity's own size; the
// floor of 1 turns it into an absolute error (in SI units) when the whole
// quantity is small (e.g. the distal block of chain20's M, ~1e-3 kg m^2), where
// a relative error would only measure round-off.
double rel_err(const Eigen::Ref<const Eigen::MatrixXd>& a, const Eigen::Ref<const Eigen::MatrixXd>& b) {
  REQUIRE(a.rows() == b.rows());
  REQUIRE(a.cols() == b.cols());
  if (a.size() == 0) return 0.0;
  return (a - b).cwiseAbs().maxCoeff() / std::max(1.0, b.cwiseAbs().maxCoeff());
}

double rel_err(double a, double b) { return std::abs(a - b) / std::max(1.0, std::abs(b)); }

struct State {
  Eigen::VectorXd q, u;
};

// Fixed seed: the same states on every run. q in [-pi, pi], u in [-2, 2].
std::vector<State> random_states(int n, int count, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> qdist(-kPi, kPi), udist(-2.0, 2.0);
  std::vector<State> states(count);
  for (State& s : states) {
    s.q.resize(n);
    s.u.resize(n);
    for (int i = 0; i < n; ++i) s.q[i] = qdist(rng);
    for (int i = 0; i < n; ++i) s.u[i] = udist(rng);
  }
  return states;
}

// Symmetric positive definite: symmetric to round-off, Cholesky succeeds and
// the smallest eigenvalue is positive.
void check_spd(const Eigen::MatrixXd& M, const char* what) {
  INFO(what);
  const double scale = M.cwiseAbs().maxCoeff();
  CHECK((M - M.transpose()).cwiseAbs().maxCoeff() <= 1e-13 * scale);
  const Eigen::MatrixXd S = 0.5 * (M + M.transpose());
  CHECK(S.llt().info() == Eigen::Success);
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(S, Eigen::EigenvaluesOnly);
  REQUIRE(eig.info() == Eigen::Success);
  INFO("eigenvalues in [" << eig.eigenvalues().minCoeff() << ", " << eig.eigenvalues().maxCoeff() << "]");
  CHECK(eig.eigenvalues().minCoeff() > 0.0);
}

}  // namespace

// ---------------------------------------------------------------------------
// The MuJoCo side alone: is MuJoCo used right?

TEST_CASE("MuJoCo reference: 1-link pendulum against the closed form", "[mujoco]") {
  // tests/consistency/data/pendulum.urdf: hinge about y, COM l below it.
  const double m = 2.5, l = 0.7, Iyy = 0.05;
  MujocoReference ref(KANEGEN_CONSISTENCY_DATA_DIR "/pendulum.urdf");
  REQUIRE(ref.nv() == 1);
  REQUIRE(ref.coordinate_joints() == std::vector<std::string>{"hinge"});
  CHECK(ref.body_mass("bob") == Approx(m).epsilon(1e-15));

  // the bob has off-diagonal inertia terms: MuJoCo's own import of them is
  // accurate to ~1e-7 only, the refined one to round-off (see mujoco_reference.hpp)
  CHECK(ref.inertia_refinement() > 1e-9);
  CHECK(ref.inertia_refinement() < 1e-5);
  MujocoReference raw(KANEGEN_CONSISTENCY_DATA_DIR "/pendulum.urdf", /*refine_inertia=*/false);
  CHECK(raw.inertia_refinement() == 0.0);

  const MujocoDynamics zero = ref.evaluate(Eigen::VectorXd::Zero(1), Eigen::VectorXd::Zero(1));
  for (const State& s : random_states(1, 20, 7)) {
    const double q = s.q[0], u = s.u[0];
    const MujocoDynamics r = ref.evaluate(s.q, s.u);
    const double M = m * l * l + Iyy;
    const double bias = m * kG * l * std::sin(q);
    INFO("q = " << q << ", u = " << u);
    CHECK(rel_err(r.M(0, 0), M) <= 1e-12);
    CHECK(rel_err(r.qfrc_bias[0], bias) <= 1e-12);
    CHECK(r.qfrc_passive[0] == 0.0);
    CHECK(rel_err(r.forcing()[0], -bias) <= 1e-12);
    CHECK(rel_err(r.qacc_smooth[0], -bias / M) <= 1e-12);
    CHECK(rel_err(r.kinetic_energy, 0.5 * M * u * u) <= 1e-12);
    // the COM rises by l (1 - cos q) from the hanging position
    CHECK(rel_err(r.potential_energy - zero.potential_energy, m * kG * l * (1.0 - std::cos(q))) <= 1e-12);
    CHECK(rel_err(raw.evaluate(s.q, s.u).M(0, 0), M) <= 1e-6);
  }
}

TEST_CASE("MuJoCo reference: DOFs are mapped to URDF file order by joint name", "[mujoco]") {
  // tests/consistency/data/branched.urdf: file order a2, b1, a1; MuJoCo
  // numbers the DOFs depth-first (b1, a1, a2). Coordinates below are in
  // file order: index 0 = a2, 1 = b1, 2 = a1.
  const double m1 = 1.5, l1 = 0.2, I1 = 0.02, L1 = 0.5, m2 = 0.8, l2 = 0.3, I2 = 0.01, mb = 3.0, lb = 0.4,
               Ib = 0.06;
  MujocoReference ref(KANEGEN_CONSISTENCY_DATA_DIR "/branched.urdf");
  REQUIRE(ref.coordinate_joints() == std::vector<std::string>{"joint_a2", "joint_b1", "joint_a1"});
  REQUIRE(ref.dof_of_coordinate() != std::vector<int>{0, 1, 2});  // the case this test is about

  for (const State& s : random_states(3, 20, 11)) {
    const double qa2 = s.q[0], qb = s.q[1], qa1 = s.q[2];
    const double ua2 = s.u[0], ua1 = s.u[2];
    const MujocoDynamics r = ref.evaluate(s.q, s.u);
    // planar double pendulum a1-a2 (angles from the downward vertical) and a
    // single pendulum b1, independent of each other
    const double c2 = std::cos(qa2), s2 = std::sin(qa2);
    Eigen::Matrix3d M = Eigen::Matrix3d::Zero();
    M(2, 2) = I1 + m1 * l1 * l1 + I2 + m2 * (L1 * L1 + l2 * l2 + 2.0 * L1 * l2 * c2);
    M(0, 0) = I2 + m2 * l2 * l2;
    M(0, 2) = M(2, 0) = I2 + m2 * (l2 * l2 + L1 * l2 * c2);
    M(1, 1) = Ib + mb * lb * lb;
    Eigen::Vector3d bias;
    bias[2] = -m2 * L1 * l2 * s2 * (2.0 * ua1 * ua2 + ua2 * ua2) + (m1 * l1 + m2 * L1) * kG * std::sin(qa1) +
              m2 * l2 * kG * std::sin(qa1 + qa2);
    bias[0] = m2 * L1 * l2 * s2 * ua1 * ua1 + m2 * l2 * kG * std::sin(qa1 + qa2);
    bias[1] = mb * lb * kG * std::sin(qb);
    INFO("q = " << s.q.transpose() << ", u = " << s.u.transpose());
    CHECK(rel_err(r.M, M) <= 1e-12);
    CHECK(rel_err(r.qfrc_bias, bias) <= 1e-12);
    const Eigen::Vector3d qacc = M.llt().solve(-bias);
    CHECK(rel_err(r.qacc_smooth, qacc) <= 1e-12);
  }
}

// ---------------------------------------------------------------------------
// The shipped URDFs as MuJoCo reads them.

TEST_CASE("MuJoCo loads the shipped URDFs as written", "[mujoco][models]") {
  const auto path = GENERATE(as<std::string>{}, KANEGEN_ARM7_URDF, KANEGEN_CHAIN20_URDF);
  INFO(path);
  const std::vector<std::string> joints = kanegen_consistency::urdf_moving_joints(path);
  MujocoReference ref(path);
  CHECK(ref.nv() == static_cast<int>(joints.size()));
  CHECK(ref.model()->nq == ref.nv());
  CHECK(ref.model()->nu == 0);  // no actuators: nothing but gravity and inertia acts

  // every link is a body of the same mass (fusestatic="false" in the file)
  const auto masses = kanegen_consistency::urdf_link_masses(path);
  CHECK(static_cast<int>(masses.size()) == ref.model()->nbody - 1);  // world is body 0
  for (const auto& [link, mass] : masses) {
    INFO("link " << link);
    CHECK(ref.body_mass(link) == Approx(mass).epsilon(1e-14));
  }
  INFO("inertia refinement " << ref.inertia_refinement());
  CHECK(ref.inertia_refinement() < 1e-5);
  // no springs, dampers, armature or friction loss
  for (int i = 0; i < ref.nv(); ++i) {
    CHECK(ref.model()->dof_damping[i] == 0.0);
    CHECK(ref.model()->dof_armature[i] == 0.0);
    CHECK(ref.model()->dof_frictionloss[i] == 0.0);
  }
  for (const State& s : random_states(ref.nv(), 20, 3)) {
    const MujocoDynamics r = ref.evaluate(s.q, s.u);
    CHECK(r.qfrc_passive.cwiseAbs().maxCoeff() == 0.0);
    check_spd(r.M, "MuJoCo M");
  }
}

// ---------------------------------------------------------------------------
// The generated kernels against MuJoCo.

#if KANEGEN_HAVE_GENERATED_MODELS

namespace {

struct MaxErrors {
  double M = 0, f = 0, udot = 0, T = 0, V = 0;
};

template <class S>
MaxErrors compare_with_mujoco(const std::string& urdf, unsigned seed, int count) {
  const std::vector<std::string> joints = kanegen_consistency::urdf_moving_joints(urdf);
  REQUIRE(S::nq == static_cast<int>(joints.size()));
  REQUIRE(S::nu == S::nq);  // URDF: u = qdot
  // the generated coordinates are the moving joints in file order
  std::vector<std::string> names(S::coordinate_names(), S::coordinate_names() + S::nq);
  REQUIRE(names == joints);

  MujocoReference ref(urdf, names);
  REQUIRE(ref.nv() == S::nu);

  const typename S::Params p{};
  const int n = S::nu;
  std::vector<double> tau(std::max(S::ntau, 1), 0.0);
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> M(n, n);
  Eigen::VectorXd f(n), udot(n), qdot(n);

  MaxErrors worst;
  const std::vector<State> states = random_states(n, count, seed);
  const double V0 = S::potential_energy(p, states[0].q.data());
  const double V0_ref = ref.evaluate(states[0].q, states[0].u).potential_energy;
  for (std::size_t k = 0; k < states.size(); ++k) {
    const State& s = states[k];
    INFO("state " << k << ": q = " << s.q.transpose() << ", u = " << s.u.transpose());
    const MujocoDynamics r = ref.evaluate(s.q, s.u);

    S::mass_matrix(p, s.q.data(), M.data());
    S::forcing(p, 0.0, s.q.data(), s.u.data(), tau.data(), f.data());
    REQUIRE(S::forward_dynamics(p, 0.0, s.q.data(), s.u.data(), tau.data(), udot.data()) == 0);
    S::coordinate_rates(s.q.data(), s.u.data(), qdot.data());

    const double eM = rel_err(M, r.M), ef = rel_err(f, r.forcing()), eu = rel_err(udot, r.qacc_smooth);
    const double eT = rel_err(S::kinetic_energy(p, s.q.data(), s.u.data()), r.kinetic_energy);
    const double eV =
        rel_err(S::potential_energy(p, s.q.data()) - V0, r.potential_energy - V0_ref);  // same zero level
    CHECK(eM <= 1e-9);
    CHECK(ef <= 1e-9);
    CHECK(eu <= 1e-9);
    CHECK(eT <= 1e-9);
    CHECK(eV <= 1e-9);
    CHECK(rel_err(qdot, s.u) == 0.0);
    worst.M = std::max(worst.M, eM);
    worst.f = std::max(worst.f, ef);
    worst.udot = std::max(worst.udot, eu);
    worst.T = std::max(worst.T, eT);
    worst.V = std::max(worst.V, eV);

    check_spd(M, "generated M");
  }
  std::printf("%-8s vs MuJoCo, %d states: max rel. error M %.2e, f %.2e, udot %.2e, T %.2e, V %.2e\n",
              S::name, count, worst.M, worst.f, worst.udot, worst.T, worst.V);
  return worst;
}

}  // namespace

TEST_CASE("arm7: generated kernels agree with MuJoCo", "[generated][arm7]") {
  using S = kanegen_models::arm7::System;
  CHECK(std::string(S::name) == "arm7");
  compare_with_mujoco<S>(KANEGEN_ARM7_URDF, 2024, 50);
}

TEST_CASE("chain20: generated kernels agree with MuJoCo", "[generated][chain20]") {
  using S = kanegen_models::chain20::System;
  CHECK(std::string(S::name) == "chain20");
  compare_with_mujoco<S>(KANEGEN_CHAIN20_URDF, 2025, 30);
}

TEST_CASE("mixed_tree: the recursive forward_dynamics agrees with MuJoCo", "[generated][recursive]") {
  using S = kanegen_models::mixed_tree::System;
  CHECK(std::string(S::name) == "mixed_tree");
  compare_with_mujoco<S>(KANEGEN_MIXED_TREE_URDF, 2026, 40);
}

#endif  // KANEGEN_HAVE_GENERATED_MODELS
