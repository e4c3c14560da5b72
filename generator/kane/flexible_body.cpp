// SPDX-License-Identifier: GPL-2.0-or-later
#include "kane/flexible_body.hpp"

#include <Eigen/Eigenvalues>

#include "fem/continuum_element.hpp"
#include "fem/invariants.hpp"
#include "symbolic/variables.hpp"

namespace kanegen::kane {
using namespace kanegen::symbolic;  // the vector algebra and its operators
namespace {

using GiNaC::ex;

ex number(double v) { return symbolic::number(v); }

}  // namespace

Eigen::MatrixXd cleaned(const Eigen::MatrixXd& m) {
  const double largest = m.size() ? m.cwiseAbs().maxCoeff() : 0.0;
  return m.unaryExpr([&](double v) { return std::abs(v) <= 1e-13 * largest ? 0.0 : v; });
}

ex linear_combination(const Eigen::Ref<const Eigen::VectorXd>& c, const std::vector<ex>& x) {
  GiNaC::exvector terms;
  for (Eigen::Index k = 0; k < c.size(); ++k)
    if (c[k] != 0.0) terms.push_back(number(c[k]) * x[k]);
  return terms.empty() ? ex(0) : ex(GiNaC::add(terms));
}

namespace {

/// x^T M x for a symmetric M, as a sum over its nonzero rows.
ex quadratic(const Eigen::MatrixXd& m, const std::vector<ex>& x, Program& program) {
  ex sum = 0;
  for (Eigen::Index k = 0; k < m.rows(); ++k)
    if (m.row(k).cwiseAbs().maxCoeff() != 0.0)
      sum += x[k] * program.define(linear_combination(m.row(k).transpose(), x));
  return sum;
}

/// The foreshortening's share, in the body's coordinates: a point p moves
/// by f_a = -1/2 eta^T H_a(p) eta on top of N eta (fem/foreshortening.hpp),
/// so its elastic partial velocities are N_k + D_k with D_k,a = -(H_a eta)_k.
/// The terms kept are those of the kinetic energy's terms of second order in
/// (eta, eta_dot) and those they give in Lagrange's equations: the joint
/// rows to second order, the elastic rows to first. That is the order of the
/// linear model's own terms, and the equations stay conservative.
struct Shortening {
  std::array<Eigen::MatrixXd, 3> mass;    ///< Fm_a = int rho H_a
  std::array<Eigen::MatrixXd, 9> moment;  ///< Fr_ab = int rho r_b H_a, [3a+b]
  std::array<std::vector<ex>, 3> y;       ///< Fm_a eta (empty where Fm_a = 0)
  std::array<std::vector<ex>, 9> z;       ///< Fr_ab eta (empty where Fr_ab = 0)

  bool has(const Eigen::MatrixXd& m) const { return m.size() && m.cwiseAbs().maxCoeff() != 0.0; }
  /// int rho f_a = -1/2 eta . y_a; int rho f_a r_b = -1/2 eta . z_ab.
  ex moment_of(const std::vector<ex>& v, const std::vector<ex>& eta) const {
    ex sum = 0;
    for (std::size_t k = 0; k < v.size(); ++k) sum += eta[k] * v[k];
    return -sum / 2;
  }
  /// int rho D_k,a = -y_a[k]; int rho D_k,a r_b = -z_ab[k].
  ex at(const std::vector<ex>& v, int k) const { return v.empty() ? ex(0) : -v[k]; }
};

Shortening shortening_terms(const fem::Foreshortening& f, const std::vector<ex>& eta, Program& program) {
  Shortening s;
  const auto vector_of = [&](const Eigen::MatrixXd& m) {
    std::vector<ex> v;
    if (!s.has(m)) return v;
    for (Eigen::Index k = 0; k < m.rows(); ++k)
      v.push_back(program.define(linear_combination(m.row(k).transpose(), eta)));
    return v;
  };
  for (int a = 0; a < 3; ++a) {
    s.mass[a] = cleaned(f.mass[a]);
    s.y[a] = vector_of(s.mass[a]);
  }
  for (int ab = 0; ab < 9; ++ab) {
    s.moment[ab] = cleaned(f.moment[ab]);
    s.z[ab] = vector_of(s.moment[ab]);
  }
  return s;
}

/// The nonlinear axial strain energy U_nl = sum_e S_e (e_e phi_e + phi_e^2 / 2)
/// (fem/axial_strain.hpp): subtracts its gradient from `forcing`, returns U_nl.
/// dU/deta = sum_e S_e (phi_e grad e_e + (e_e + phi_e) grad phi_e), with
/// phi_e = 1/2 sum_p w_p sum_j a_pj^2, a_pj = slopes_p,j eta, grad phi_e = sum_p w_p sum_j a_pj grad a_pj.
ex add_axial_strain(const std::vector<fem::AxialStrainElement>& elements, const std::vector<ex>& eta,
                    std::vector<ex>& forcing, Program& program) {
  ex energy = 0;
  std::vector<ex> gradient(eta.size(), 0);
  for (const fem::AxialStrainElement& element : elements) {
    const Eigen::RowVectorXd axial = cleaned(element.axial);
    const ex e = program.define(linear_combination(axial.transpose(), eta));
    ex phi = 0;
    std::vector<Eigen::MatrixXd> slopes;
    std::vector<std::vector<ex>> a(element.slopes.size());
    for (std::size_t p = 0; p < element.slopes.size(); ++p) {
      slopes.push_back(cleaned(element.slopes[p]));
      for (Eigen::Index j = 0; j < slopes[p].rows(); ++j) {
        a[p].push_back(program.define(linear_combination(slopes[p].row(j).transpose(), eta)));
        phi += number(element.weight[p] / 2) * a[p].back() * a[p].back();
      }
    }
    phi = program.define(phi);
    const ex stiffness = number(element.stiffness);
    energy += stiffness * (e * phi + phi * phi / 2);
    const ex stretch = program.define(stiffness * phi), pull = program.define(stiffness * (e + phi));
    for (std::size_t k = 0; k < eta.size(); ++k) {
      const auto index = static_cast<Eigen::Index>(k);
      if (axial[index] != 0.0) gradient[k] += stretch * number(axial[index]);
      ex slope_gradient = 0;  // (grad phi_e)_k
      for (std::size_t p = 0; p < slopes.size(); ++p)
        for (Eigen::Index j = 0; j < slopes[p].rows(); ++j)
          if (slopes[p](j, index) != 0.0)
            slope_gradient +=
                number(element.weight[p] * slopes[p](j, index)) * a[p][static_cast<std::size_t>(j)];
      if (!slope_gradient.is_zero()) gradient[k] += pull * slope_gradient;
    }
  }
  for (std::size_t k = 0; k < eta.size(); ++k)
    if (!gradient[k].is_zero()) forcing[k] = program.define(forcing[k] - gradient[k]);
  return energy;
}

/// The steps of flexible_terms, in their order: they share the body's
/// cleaned invariants, its coordinates and the integrals D.
class FlexibleBuilder {
 public:
  FlexibleBuilder(const fem::ElasticModel& beam, const kinematics::BodyState& b, const std::vector<ex>& eta,
                  const std::vector<ex>& eta_dot, Program& program)
      : beam_(beam),
        inv_(beam.reduced.invariants),
        b_(b),
        eta_(eta),
        eta_dot_(eta_dot),
        program_(program),
        n_(inv_.n),
        shortens_(beam.foreshortening.has_value()),
        second_order_mass_(shortens_ && beam.foreshortening->mode_pair.size() > 0) {
    if (shortens_) fs_ = shortening_terms(*beam.foreshortening, eta, program);
    S_ = cleaned(inv_.S);
    S_r_ = cleaned(inv_.S_r);
    J_Nrot_ = cleaned(inv_.J_Nrot);
    for (int k = 0; k < 9; ++k) S_nn_[k] = cleaned(inv_.S_nn[k]);
    for (int i = 0; i < 9; ++i) J_[i] = number(inv_.J(i / 3, i % 3));
  }

  FlexibleTerms build() {
    second_moment_integrals();
    body_inertia();
    elastic_momenta();
    const Vec3 force = rest_force();
    const Vec3 moment = rest_moment();
    out_.force = zero_vec() - force;
    out_.moment = zero_vec() - moment;
    elastic_equations();
    energies();
    return out_;
  }

 private:
  /// The rows of m times x, a vector.
  Vec3 rows(const Eigen::MatrixXd& m, const std::vector<ex>& x) const {
    Vec3 v;
    for (int a = 0; a < 3; ++a) v[a] = linear_combination(m.row(a).transpose(), x);
    return v;
  }

  void second_moment_integrals() {
    // D[3a+b][k] = int rho p_a N_bk = S_r[3a+b]_k + (S_nn[3a+b]^T eta)_k, with p = r + N eta.
    for (int ab = 0; ab < 9; ++ab) {
      D_[ab].resize(n_);
      for (int k = 0; k < n_; ++k)
        D_[ab][k] = program_.define(number(S_r_(ab, k)) + linear_combination(S_nn_[ab].col(k), eta_));
    }
    // P[3a+b] = int rho p_a p_b = second_ab + S_r[3b+a] eta + D[3a+b] eta (+ int rho (r_a f_b + f_a r_b)).
    for (int a = 0; a < 3; ++a)
      for (int c = 0; c < 3; ++c) {
        ex sum = number(inv_.second_moment(a, c)) + linear_combination(S_r_.row(3 * c + a).transpose(), eta_);
        for (int k = 0; k < n_; ++k) sum += D_[3 * a + c][k] * eta_[k];
        if (shortens_) sum += fs_.moment_of(fs_.z[3 * c + a], eta_) + fs_.moment_of(fs_.z[3 * a + c], eta_);
        P_[3 * a + c] = sum;
      }
    for (int a = 0; a < 3; ++a)
      for (int c = 0; c < a; ++c) P_[3 * a + c] = P_[3 * c + a];  // symmetric: one definition each
    P_ = named(program_, P_);
  }

  /// The deformed body's mass, first and second moment about the link origin.
  void body_inertia() {
    out_.mass = number(inv_.mass);
    Vec3 first{number(inv_.first_moment[0]), number(inv_.first_moment[1]), number(inv_.first_moment[2])};
    first = first + rows(S_, eta_);
    if (shortens_)
      for (int a = 0; a < 3; ++a) first[a] += fs_.moment_of(fs_.y[a], eta_);
    out_.first_moment = named(program_, first);
    const ex trace = P_[0] + P_[4] + P_[8];
    for (int a = 0; a < 3; ++a)
      for (int c = 0; c < 3; ++c)
        out_.second_moment[3 * a + c] = (a == c ? trace : ex(0)) - P_[3 * a + c] + J_[3 * a + c];
    out_.second_moment = named(program_, out_.second_moment);
  }

  /// Momentum of eta_dot_k = 1: P_k = S_k (+ int rho D_k), L_k = int rho p x N_k + J_Nrot_k (+ int rho r x
  /// D_k). Q(a, b) = int rho D_k,a r_b.
  void elastic_momenta() {
    for (int k = 0; k < n_; ++k) {
      Vec3 linear{number(S_(0, k)), number(S_(1, k)), number(S_(2, k))};
      Vec3 angular{D_[3 * 1 + 2][k] - D_[3 * 2 + 1][k] + number(J_Nrot_(0, k)),
                   D_[3 * 2 + 0][k] - D_[3 * 0 + 2][k] + number(J_Nrot_(1, k)),
                   D_[3 * 0 + 1][k] - D_[3 * 1 + 0][k] + number(J_Nrot_(2, k))};
      if (shortens_) {
        const auto Q = [&](int a, int c) { return fs_.at(fs_.z[3 * a + c], k); };
        for (int a = 0; a < 3; ++a) linear[a] += fs_.at(fs_.y[a], k);
        angular = angular + Vec3{Q(2, 1) - Q(1, 2), Q(0, 2) - Q(2, 0), Q(1, 0) - Q(0, 1)};
      }
      out_.linear_momentum.push_back(named(program_, linear));
      out_.angular_momentum.push_back(named(program_, angular));
    }
  }

  /// int rho a_p dV with u_dot = 0: a_p = a0 + alpha x p + w x (w x p) + 2 w x p' + p'',
  /// p' = (N + D) eta_dot and p'' = D' eta_dot (D_a' eta_dot = -eta_dot^T H_a eta_dot).
  Vec3 rest_force() {
    const Vec3& w = b_.omega;
    const Vec3& s_p = out_.first_moment;
    s_rate_ = rows(S_, eta_dot_);  // int rho p'
    Vec3 s_accel = zero_vec();     // int rho p''
    if (shortens_)
      for (int a = 0; a < 3; ++a) {
        if (fs_.y[a].empty()) continue;
        for (int k = 0; k < n_; ++k) s_rate_[a] -= fs_.y[a][k] * eta_dot_[k];
        s_accel[a] = -quadratic(fs_.mass[a], eta_dot_, program_);
      }
    s_rate_ = named(program_, s_rate_);
    return named(program_, out_.mass * b_.accel_rest + cross(b_.alpha_rest, s_p) + cross(w, cross(w, s_p)) +
                               2 * cross(w, s_rate_) + s_accel);
  }

  /// int rho p x a_p dV with u_dot = 0, about the link origin.
  Vec3 rest_moment() {
    const Vec3& w = b_.omega;
    // Dw[3a+b] = int rho (p')_a p_b = sum_k eta_dot_k D[3b+a][k] (- eta_dot . z_ab).
    Mat3 Dw;
    for (int a = 0; a < 3; ++a)
      for (int c = 0; c < 3; ++c) {
        ex sum = 0;
        for (int k = 0; k < n_; ++k) sum += eta_dot_[k] * D_[3 * c + a][k];
        if (shortens_)
          for (std::size_t k = 0; k < fs_.z[3 * a + c].size(); ++k) sum -= eta_dot_[k] * fs_.z[3 * a + c][k];
        Dw[3 * a + c] = sum;
      }
    Dw = named(program_, Dw);
    spin_ = named(program_, mul(out_.second_moment, w));
    const Vec3 j_rate = named(program_, rows(J_Nrot_, eta_dot_));
    const ex dw_trace = Dw[0] + Dw[4] + Dw[8];
    const Vec3 coriolis_moment = dw_trace * w - mul(Dw, w);
    // int rho r x p'': its entries int rho r_b (p'')_a = -eta_dot^T Fr_ab eta_dot.
    Vec3 accel_moment = zero_vec();
    if (shortens_) {
      Mat3 psi;
      for (int ab = 0; ab < 9; ++ab)
        psi[ab] = fs_.z[ab].empty() ? ex(0) : ex(-quadratic(fs_.moment[ab], eta_dot_, program_));
      accel_moment = Vec3{psi[3 * 2 + 1] - psi[3 * 1 + 2], psi[3 * 0 + 2] - psi[3 * 2 + 0],
                          psi[3 * 1 + 0] - psi[3 * 0 + 1]};
    }
    return named(program_, cross(out_.first_moment, b_.accel_rest) + mul(out_.second_moment, b_.alpha_rest) +
                               cross(w, spin_) + cross(w, j_rate) + 2 * coriolis_moment + accel_moment);
  }

  /// The elastic equations: forcing, constant mass block, nonlinear axial strain.
  void elastic_equations() {
    const Vec3& w = b_.omega;
    const Vec3& a0 = b_.accel_rest;
    K_ = cleaned(beam_.reduced.stiffness);
    const Eigen::MatrixXd C = cleaned(beam_.damping);
    std::array<Eigen::MatrixXd, 3> coriolis;
    for (int c = 0; c < 3; ++c) coriolis[c] = cleaned(inv_.coriolis(c));
    const ex w2 = program_.define(dot(w, w));
    Mat3 ww;  // w_a w_b
    for (int i = 0; i < 9; ++i) ww[i] = w[i / 3] * w[i % 3];
    ww = named(program_, ww);
    for (int k = 0; k < n_; ++k) {
      // int rho (N_k + D_k)^T a_p: P_k . a0 + L_k . alpha + int rho (N_k + D_k)^T W^2 p + 2 sum_c w_c C_c
      // eta_dot.
      ex inertia = out_.linear_momentum[k][0] * a0[0] + out_.linear_momentum[k][1] * a0[1] +
                   out_.linear_momentum[k][2] * a0[2] + dot(out_.angular_momentum[k], b_.alpha_rest);
      for (int a = 0; a < 3; ++a) {
        inertia -= w2 * D_[3 * a + a][k];
        for (int c = 0; c < 3; ++c) inertia += ww[3 * a + c] * D_[3 * c + a][k];
        if (shortens_)  // int rho D_k . W^2 r = sum_ab (w_a w_b - w^2 delta_ab) int rho D_k,a r_b
          for (int c = 0; c < 3; ++c)
            inertia += (ww[3 * a + c] - (a == c ? w2 : ex(0))) * fs_.at(fs_.z[3 * a + c], k);
      }
      for (int c = 0; c < 3; ++c)
        inertia += 2 * w[c] * linear_combination(coriolis[c].row(k).transpose(), eta_dot_);
      const ex elastic = -linear_combination(K_.row(k).transpose(), eta_) -
                         linear_combination(C.row(k).transpose(), eta_dot_);
      out_.elastic_forcing.push_back(program_.define(elastic - inertia));
    }
    out_.damping_power = 0;
    for (int k = 0; k < n_; ++k)
      out_.damping_power -= eta_dot_[k] * linear_combination(C.row(k).transpose(), eta_dot_);
    M_ = cleaned(inv_.elastic_mass());
    for (int k = 0; k < n_; ++k)
      for (int l = 0; l < n_; ++l) out_.elastic_mass.push_back(number(M_(k, l)));
    if (second_order_mass_) add_second_order_mass();
    nonlinear_strain_ = add_axial_strain(beam_.axial_strain, eta_, out_.elastic_forcing, program_);
  }

  /// A mesh body's elastic mass to second order (fem::add_second_order_mass):
  /// int rho (N + D)^T (N + D), D_k = sum_i eta_i d_ik, positive definite
  /// whatever the basis. The kinetic energy of the points' motion relative to
  /// the link, 1/2 int rho |(N + D) eta_dot|^2, depends on eta and eta_dot
  /// alone, so Lagrange's equations of it are int rho (N_k + D_k) . ((N + D)
  /// eta_ddot + D' eta_dot), D' eta_dot = sum_ij eta_dot_i eta_dot_j d_ij: the
  /// block's change dM and the forcing -int rho (N_k + D_k) . D' eta_dot. The
  /// rest stays at the linear model's order; the equations stay Lagrange's of
  /// the kinetic energy energies() reports, so the model stays conservative.
  void add_second_order_mass() {
    const Eigen::MatrixXd A = cleaned(beam_.foreshortening->mode_pair);
    const int pairs = fem::pair_count(n_);
    const auto pair = [&](int i, int j) { return fem::pair_index(i, j, n_); };
    // rates_p = (2 - delta_ij) eta_dot_i eta_dot_j, so that sum_ij x_ij eta_dot_i eta_dot_j = rates . x.
    std::vector<ex> rates(pairs);
    for (int i = 0; i < n_; ++i)
      for (int j = i; j < n_; ++j)
        rates[pair(i, j)] = program_.define((i == j ? 1 : 2) * eta_dot_[i] * eta_dot_[j]);
    // int rho d_p . d_q = sum_s c_s,p c_s,q over the eigenpairs of the (positive semidefinite) pair_pair
    // above round-off: D_k . D_l = sum_s y_s,k y_s,l with y_s,k = sum_i eta_i c_s,(ik), a sum of
    // outer products y_s y_s^T, positive semidefinite term by term.
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(beam_.foreshortening->pair_pair);
    const double largest = eigen.eigenvalues().cwiseAbs().maxCoeff();
    std::vector<std::vector<ex>> y;  // [s][k]
    std::vector<ex> z;               // [s]: sum_p c_s,p rates_p
    for (Eigen::Index s = 0; s < eigen.eigenvalues().size(); ++s) {
      if (eigen.eigenvalues()[s] <= 1e-12 * largest) continue;
      const Eigen::VectorXd c = cleaned(std::sqrt(eigen.eigenvalues()[s]) * eigen.eigenvectors().col(s));
      Eigen::MatrixXd per_mode(n_, n_);  // column k: c_s,(ik) over i
      for (int k = 0; k < n_; ++k)
        for (int i = 0; i < n_; ++i) per_mode(i, k) = c[pair(i, k)];
      y.emplace_back();
      for (int k = 0; k < n_; ++k)
        y.back().push_back(program_.define(linear_combination(per_mode.col(k), eta_)));
      z.push_back(program_.define(linear_combination(c, rates)));
    }
    // dM_kl = sum_i eta_i (A_k,(il) + A_l,(ik)) + D_k . D_l.
    dM_.assign(static_cast<std::size_t>(n_ * n_), ex(0));
    for (int k = 0; k < n_; ++k)
      for (int l = k; l < n_; ++l) {
        Eigen::VectorXd linear(n_);
        for (int i = 0; i < n_; ++i) linear[i] = A(k, pair(i, l)) + A(l, pair(i, k));
        ex change = linear_combination(cleaned(linear), eta_);
        for (const std::vector<ex>& ys : y) change += ys[k] * ys[l];
        change = program_.define(change);
        dM_[k * n_ + l] = dM_[l * n_ + k] = change;
        out_.elastic_mass[k * n_ + l] += change;
        if (l != k) out_.elastic_mass[l * n_ + k] += change;
      }
    // int rho (N_k + D_k) . D' eta_dot = sum_p rates_p (A_k,p + int rho D_k . d_p), the last sum_s y_s,k z_s.
    for (int k = 0; k < n_; ++k) {
      ex inertia = linear_combination(A.row(k).transpose(), rates);
      for (std::size_t s = 0; s < y.size(); ++s) inertia += y[s][k] * z[s];
      out_.elastic_forcing[k] = program_.define(out_.elastic_forcing[k] - inertia);
    }
  }

  /// T = 1/2 (m v0^2 + 2 v0.(w x s_p) + w.I w) + v0.(int rho p') + w.(L eta_dot) + 1/2 eta_dot^T M eta_dot:
  /// 1/2 u^T M u with the mass matrix these terms give. The strain energy.
  void energies() {
    const Vec3& v0 = b_.velocity;
    const Vec3& w = b_.omega;
    ex elastic_kinetic = 0;
    for (int k = 0; k < n_; ++k)
      elastic_kinetic += eta_dot_[k] * linear_combination(M_.row(k).transpose(), eta_dot_);
    if (!dM_.empty())
      for (int k = 0; k < n_; ++k)
        for (int l = 0; l < n_; ++l) elastic_kinetic += eta_dot_[k] * dM_[k * n_ + l] * eta_dot_[l];
    Vec3 l_rate = zero_vec();
    for (int k = 0; k < n_; ++k) l_rate = l_rate + eta_dot_[k] * out_.angular_momentum[k];
    out_.kinetic_energy =
        (out_.mass * dot(v0, v0) + 2 * dot(v0, cross(w, out_.first_moment)) + dot(w, spin_)) / 2 +
        dot(v0, s_rate_) + dot(w, l_rate) + elastic_kinetic / 2;
    ex strain = 0;
    for (int k = 0; k < n_; ++k) strain += eta_[k] * linear_combination(K_.row(k).transpose(), eta_);
    out_.strain_energy = strain / 2 + nonlinear_strain_;
  }

  const fem::ElasticModel& beam_;
  const fem::InertiaInvariants& inv_;
  const kinematics::BodyState& b_;
  const std::vector<ex>& eta_;
  const std::vector<ex>& eta_dot_;
  Program& program_;
  const int n_;
  const bool shortens_;
  const bool second_order_mass_;  ///< a mesh body's elastic mass to second order
  Shortening fs_;
  Eigen::MatrixXd S_, S_r_, J_Nrot_, K_, M_;
  std::array<Eigen::MatrixXd, 9> S_nn_;
  Mat3 J_;
  std::array<std::vector<ex>, 9> D_;  ///< int rho p_a N_bk, [3a+b][k]
  std::vector<ex> dM_;                ///< n x n: the elastic mass's second-order change, or empty
  Mat3 P_;                            ///< int rho p_a p_b, [3a+b]
  Vec3 s_rate_, spin_;                ///< int rho p', and I w
  ex nonlinear_strain_;
  FlexibleTerms out_;
};

}  // namespace

FlexibleTerms flexible_terms(const fem::ElasticModel& beam, const kinematics::BodyState& b,
                             const std::vector<ex>& eta, const std::vector<ex>& eta_dot, Program& program) {
  return FlexibleBuilder(beam, b, eta, eta_dot, program).build();
}

}  // namespace kanegen::kane
