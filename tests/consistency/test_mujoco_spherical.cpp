// SPDX-License-Identifier: GPL-2.0-or-later
// Spherical and free joints against MuJoCo: the generated kernels of
// data/ball_chain.json and data/free_body.json against MuJoCo's ball and
// free joints on their MJCF twins (data/*.xml), at random states.
//
// The states match without conversion but for the order of q: MuJoCo's
// qpos holds a quaternion as w, x, y, z, kanegen's q its x, y, z at the
// joint's speeds and every w after the other coordinates
// (docs/model-format.md); both take the child's angular velocity in its own
// axes as the speeds, and a free joint's slides as the origin's velocity in
// the parent's (world) axes.
#include <mujoco/mujoco.h>

#include <Eigen/Dense>
#include <algorithm>
#include <ball_chain.hpp>
#include <catch2/catch.hpp>
#include <cstdio>
#include <free_body.hpp>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

using RowMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

double rel_err(const Eigen::Ref<const RowMatrix>& a, const Eigen::Ref<const RowMatrix>& b) {
  REQUIRE(a.rows() == b.rows());
  REQUIRE(a.cols() == b.cols());
  return (a - b).cwiseAbs().maxCoeff() / std::max(1.0, b.cwiseAbs().maxCoeff());
}

/// One MJCF model with constraints off, so that qacc_smooth = M^-1 (qfrc_passive - qfrc_bias).
class Mujoco {
 public:
  explicit Mujoco(const std::string& path) {
    char error[1000] = "";
    model_ = mj_loadXML(path.c_str(), nullptr, error, sizeof error);
    if (!model_) throw std::runtime_error(path + ": " + error);
    model_->opt.disableflags |= mjDSBL_CONSTRAINT | mjDSBL_CONTACT;
    model_->opt.enableflags |= mjENBL_ENERGY;
    data_ = mj_makeData(model_);
  }
  ~Mujoco() {
    mj_deleteData(data_);
    mj_deleteModel(model_);
  }
  Mujoco(const Mujoco&) = delete;
  Mujoco& operator=(const Mujoco&) = delete;

  const mjModel* model() const { return model_; }
  const mjData* data() const { return data_; }
  void evaluate(const std::vector<double>& qpos, const std::vector<double>& qvel) {
    std::copy(qpos.begin(), qpos.end(), data_->qpos);
    std::copy(qvel.begin(), qvel.end(), data_->qvel);
    mj_forward(model_, data_);
  }
  RowMatrix mass_matrix() const {
    RowMatrix m(model_->nv, model_->nv);
    mj_fullM(model_, m.data(), data_->qM);
    return m;
  }

 private:
  mjModel* model_ = nullptr;
  mjData* data_ = nullptr;
};

/// Where a spherical joint's quaternion lies in MuJoCo's qpos (its w) and in
/// kanegen's q (its x, then its w).
struct Quaternion {
  int qpos, q_xyz, q_w;
};

/// A random state: unit quaternions, other coordinates in [-1, 1], speeds in [-2, 2].
struct States {
  std::vector<double> qpos, q, u;
};

States random_state(std::mt19937_64& rng, int nq, int nu, const std::vector<int>& plain_qpos,
                    const std::vector<int>& plain_q, const std::vector<Quaternion>& quaternions) {
  std::uniform_real_distribution<double> value(-1.0, 1.0), speed(-2.0, 2.0);
  States s{std::vector<double>(static_cast<std::size_t>(nq)),
           std::vector<double>(static_cast<std::size_t>(nq)),
           std::vector<double>(static_cast<std::size_t>(nu))};
  for (std::size_t k = 0; k < plain_q.size(); ++k) s.q[plain_q[k]] = s.qpos[plain_qpos[k]] = value(rng);
  for (const Quaternion& j : quaternions) {
    Eigen::Vector4d wxyz(value(rng), value(rng), value(rng), value(rng));
    wxyz.normalize();
    for (int c = 0; c < 4; ++c) s.qpos[j.qpos + c] = wxyz[c];
    for (int c = 0; c < 3; ++c) s.q[j.q_xyz + c] = wxyz[1 + c];
    s.q[j.q_w] = wxyz[0];
  }
  for (double& x : s.u) x = speed(rng);
  return s;
}

struct Layout {
  std::vector<int> plain_qpos, plain_q;  ///< hinges and slides
  std::vector<double> qpos_offset;       ///< added to kanegen's plain q to give MuJoCo's qpos
  std::vector<Quaternion> quaternions;
};

template <class S>
void compare_with_mujoco(const std::string& mjcf, const Layout& layout, unsigned seed, int count) {
  Mujoco ref(mjcf);
  REQUIRE(ref.model()->nq == S::nq);
  REQUIRE(ref.model()->nv == S::nu);
  const typename S::Params p{};
  const int n = S::nu;
  std::vector<double> tau(std::max(S::ntau, 1), 0.0);
  RowMatrix M(n, n);
  Eigen::VectorXd f(n), udot(n), qdot(S::nq);
  std::mt19937_64 rng(seed);
  double worst_m = 0, worst_f = 0, worst_udot = 0, worst_energy = 0, worst_rates = 0;
  double v_offset = 0;
  for (int k = 0; k < count; ++k) {
    States s = random_state(rng, S::nq, S::nu, layout.plain_qpos, layout.plain_q, layout.quaternions);
    for (std::size_t i = 0; i < layout.plain_qpos.size(); ++i)
      s.qpos[layout.plain_qpos[i]] += layout.qpos_offset[i];
    ref.evaluate(s.qpos, s.u);
    const mjData* d = ref.data();
    S::mass_matrix(p, s.q.data(), M.data());
    S::forcing(p, 0.0, s.q.data(), s.u.data(), tau.data(), f.data());
    REQUIRE(S::forward_dynamics(p, 0.0, s.q.data(), s.u.data(), tau.data(), udot.data()) == 0);
    S::coordinate_rates(s.q.data(), s.u.data(), qdot.data());

    const Eigen::Map<const Eigen::VectorXd> bias(d->qfrc_bias, n), passive(d->qfrc_passive, n),
        qacc(d->qacc_smooth, n);
    const double e_m = rel_err(M, ref.mass_matrix());
    const double e_f = rel_err(f, passive - bias);
    const double e_udot = rel_err(udot, qacc);
    // MuJoCo's V is m g z with z = 0 at the world origin; kanegen's the same up to a constant.
    const double v = S::potential_energy(p, s.q.data()) - d->energy[0];
    if (k == 0) v_offset = v;
    const double e_energy = std::max(std::abs(S::kinetic_energy(p, s.q.data(), s.u.data()) - d->energy[1]),
                                     std::abs(v - v_offset)) /
                            std::max(1.0, std::abs(d->energy[0]) + std::abs(d->energy[1]));
    // q_dot of each quaternion against MuJoCo's own integration of it
    // (mj_integratePos, the quaternion turned by exp of the angular velocity
    // in the child's axes), by a central difference over +-h: error O(h^2).
    // (MuJoCo 2.2.2's mju_derivQuat takes the angular velocity in the
    // parent's axes, so it is not the reference here.)
    double e_rates = 0;
    const double h = 1e-5;
    std::vector<double> ahead = s.qpos, behind = s.qpos;
    mj_integratePos(ref.model(), ahead.data(), s.u.data(), h);
    mj_integratePos(ref.model(), behind.data(), s.u.data(), -h);
    for (const Quaternion& j : layout.quaternions) {
      const auto rate = [&](int c) { return (ahead[j.qpos + c] - behind[j.qpos + c]) / (2 * h); };
      e_rates = std::max({e_rates, std::abs(qdot[j.q_w] - rate(0)), std::abs(qdot[j.q_xyz] - rate(1)),
                          std::abs(qdot[j.q_xyz + 1] - rate(2)), std::abs(qdot[j.q_xyz + 2] - rate(3))});
    }
    INFO("state " << k);
    CHECK(e_m <= 1e-12);
    CHECK(e_f <= 1e-12);
    CHECK(e_udot <= 1e-12);
    CHECK(e_energy <= 1e-12);
    CHECK(e_rates <= 1e-8);
    worst_m = std::max(worst_m, e_m);
    worst_f = std::max(worst_f, e_f);
    worst_udot = std::max(worst_udot, e_udot);
    worst_energy = std::max(worst_energy, e_energy);
    worst_rates = std::max(worst_rates, e_rates);
  }
  std::printf(
      "%-10s vs MuJoCo, %d states: max rel. error M %.1e, f %.1e, udot %.1e, T and V %.1e, q_dot %.1e\n",
      S::name, count, worst_m, worst_f, worst_udot, worst_energy, worst_rates);
}

}  // namespace

TEST_CASE("spherical joint: generated kernels agree with MuJoCo's ball joint", "[generated][spherical]") {
  using S = kanegen_models::ball_chain::System;
  // q: shoulder x, y, z, elbow, shoulder w; qpos: shoulder w, x, y, z, elbow.
  REQUIRE(std::vector<std::string>(S::coordinate_names(), S::coordinate_names() + S::nq) ==
          std::vector<std::string>{"shoulder_qx", "shoulder_qy", "shoulder_qz", "elbow", "shoulder_qw"});
  REQUIRE(std::vector<std::string>(S::speed_names(), S::speed_names() + S::nu) ==
          std::vector<std::string>{"shoulder_wx", "shoulder_wy", "shoulder_wz", "elbow_dot"});
  Layout layout{{4}, {3}, {0.0}, {{0, 0, 4}}};
  compare_with_mujoco<S>(KANEGEN_CONSISTENCY_DATA_DIR "/ball_chain.xml", layout, 21, 30);
}

TEST_CASE("free joint: generated kernels agree with MuJoCo's free joint", "[generated][spherical]") {
  using S = kanegen_models::free_body::System;
  // q: base x, y, z, base qx, qy, qz, wrist qx, qy, qz, base qw, wrist qw;
  // qpos: the box origin x, y, z (kanegen's slides start at the joint
  // origin, z = 1), base w, x, y, z, wrist w, x, y, z.
  REQUIRE(std::vector<std::string>(S::coordinate_names(), S::coordinate_names() + S::nq) ==
          std::vector<std::string>{"base_x", "base_y", "base_z", "base_qx", "base_qy", "base_qz", "wrist_qx",
                                   "wrist_qy", "wrist_qz", "base_qw", "wrist_qw"});
  Layout layout{{0, 1, 2}, {0, 1, 2}, {0.0, 0.0, 1.0}, {{3, 3, 9}, {7, 6, 10}}};
  compare_with_mujoco<S>(KANEGEN_CONSISTENCY_DATA_DIR "/free_body.xml", layout, 22, 30);
}
