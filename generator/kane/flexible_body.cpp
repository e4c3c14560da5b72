// SPDX-License-Identifier: GPL-2.0-or-later
#include "kane/flexible_body.hpp"

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

}  // namespace

FlexibleTerms flexible_terms(const fem::ModelBeam& beam, const kinematics::BodyState& b,
                             const std::vector<ex>& eta, const std::vector<ex>& eta_dot, Program& program) {
  const fem::ReducedBody& body = beam.reduced;
  const fem::InertiaInvariants& inv = body.invariants;
  const int n = inv.n;
  FlexibleTerms out;
  const bool shortens = beam.foreshortening.has_value();
  const Shortening fs = shortens ? shortening_terms(*beam.foreshortening, eta, program) : Shortening{};

  const Eigen::MatrixXd S = cleaned(inv.S), S_r = cleaned(inv.S_r), J_Nrot = cleaned(inv.J_Nrot);
  std::array<Eigen::MatrixXd, 9> S_nn;
  for (int k = 0; k < 9; ++k) S_nn[k] = cleaned(inv.S_nn[k]);
  Mat3 J;
  for (int i = 0; i < 9; ++i) J[i] = number(inv.J(i / 3, i % 3));
  const auto rows = [&](const Eigen::MatrixXd& m, const std::vector<ex>& x) {
    Vec3 v;
    for (int a = 0; a < 3; ++a) v[a] = linear_combination(m.row(a).transpose(), x);
    return v;
  };

  // D[3a+b][k] = int rho p_a N_bk = S_r[3a+b]_k + (S_nn[3a+b]^T eta)_k, with p = r + N eta.
  std::array<std::vector<ex>, 9> D;
  for (int ab = 0; ab < 9; ++ab) {
    D[ab].resize(n);
    for (int k = 0; k < n; ++k)
      D[ab][k] = program.define(number(S_r(ab, k)) + linear_combination(S_nn[ab].col(k), eta));
  }
  // P[3a+b] = int rho p_a p_b = second_ab + S_r[3b+a] eta + D[3a+b] eta (+ int rho (r_a f_b + f_a r_b)).
  Mat3 P;
  for (int a = 0; a < 3; ++a)
    for (int c = 0; c < 3; ++c) {
      ex sum = number(inv.second_moment(a, c)) + linear_combination(S_r.row(3 * c + a).transpose(), eta);
      for (int k = 0; k < n; ++k) sum += D[3 * a + c][k] * eta[k];
      if (shortens) sum += fs.moment_of(fs.z[3 * c + a], eta) + fs.moment_of(fs.z[3 * a + c], eta);
      P[3 * a + c] = sum;
    }
  for (int a = 0; a < 3; ++a)
    for (int c = 0; c < a; ++c) P[3 * a + c] = P[3 * c + a];  // symmetric: one definition each
  P = named(program, P);

  out.mass = number(inv.mass);
  Vec3 first{number(inv.first_moment[0]), number(inv.first_moment[1]), number(inv.first_moment[2])};
  first = first + rows(S, eta);
  if (shortens)
    for (int a = 0; a < 3; ++a) first[a] += fs.moment_of(fs.y[a], eta);
  out.first_moment = named(program, first);
  const ex trace = P[0] + P[4] + P[8];
  for (int a = 0; a < 3; ++a)
    for (int c = 0; c < 3; ++c)
      out.second_moment[3 * a + c] = (a == c ? trace : ex(0)) - P[3 * a + c] + J[3 * a + c];
  out.second_moment = named(program, out.second_moment);

  // Momentum of eta_dot_k = 1: P_k = S_k (+ int rho D_k), L_k = int rho p x N_k + J_Nrot_k (+ int rho r x
  // D_k). Q(a, b) = int rho D_k,a r_b.
  for (int k = 0; k < n; ++k) {
    Vec3 linear{number(S(0, k)), number(S(1, k)), number(S(2, k))};
    Vec3 angular{D[3 * 1 + 2][k] - D[3 * 2 + 1][k] + number(J_Nrot(0, k)),
                 D[3 * 2 + 0][k] - D[3 * 0 + 2][k] + number(J_Nrot(1, k)),
                 D[3 * 0 + 1][k] - D[3 * 1 + 0][k] + number(J_Nrot(2, k))};
    if (shortens) {
      const auto Q = [&](int a, int c) { return fs.at(fs.z[3 * a + c], k); };
      for (int a = 0; a < 3; ++a) linear[a] += fs.at(fs.y[a], k);
      angular = angular + Vec3{Q(2, 1) - Q(1, 2), Q(0, 2) - Q(2, 0), Q(1, 0) - Q(0, 1)};
    }
    out.linear_momentum.push_back(named(program, linear));
    out.angular_momentum.push_back(named(program, angular));
  }

  // Rest accelerations (u_dot = 0): a_p = a0 + alpha x p + w x (w x p) + 2 w x p' + p'',
  // p' = (N + D) eta_dot and p'' = D' eta_dot (D_a' eta_dot = -eta_dot^T H_a eta_dot).
  const Vec3& w = b.omega;
  const Vec3& a0 = b.accel_rest;
  const Vec3& alpha = b.alpha_rest;
  const Vec3 s_p = out.first_moment;
  Vec3 s_rate = rows(S, eta_dot);  // int rho p'
  Vec3 s_accel = zero_vec();       // int rho p''
  if (shortens)
    for (int a = 0; a < 3; ++a) {
      if (fs.y[a].empty()) continue;
      for (int k = 0; k < n; ++k) s_rate[a] -= fs.y[a][k] * eta_dot[k];
      s_accel[a] = -quadratic(fs.mass[a], eta_dot, program);
    }
  s_rate = named(program, s_rate);
  const Vec3 force = named(
      program, out.mass * a0 + cross(alpha, s_p) + cross(w, cross(w, s_p)) + 2 * cross(w, s_rate) + s_accel);
  // Dw[3a+b] = int rho (p')_a p_b = sum_k eta_dot_k D[3b+a][k] (- eta_dot . z_ab).
  Mat3 Dw;
  for (int a = 0; a < 3; ++a)
    for (int c = 0; c < 3; ++c) {
      ex sum = 0;
      for (int k = 0; k < n; ++k) sum += eta_dot[k] * D[3 * c + a][k];
      if (shortens)
        for (std::size_t k = 0; k < fs.z[3 * a + c].size(); ++k) sum -= eta_dot[k] * fs.z[3 * a + c][k];
      Dw[3 * a + c] = sum;
    }
  Dw = named(program, Dw);
  const Vec3 spin = named(program, mul(out.second_moment, w));
  const Vec3 j_rate = named(program, rows(J_Nrot, eta_dot));
  const ex dw_trace = Dw[0] + Dw[4] + Dw[8];
  const Vec3 coriolis_moment = dw_trace * w - mul(Dw, w);
  // int rho r x p'': its entries int rho r_b (p'')_a = -eta_dot^T Fr_ab eta_dot.
  Vec3 accel_moment = zero_vec();
  if (shortens) {
    Mat3 psi;
    for (int ab = 0; ab < 9; ++ab)
      psi[ab] = fs.z[ab].empty() ? ex(0) : ex(-quadratic(fs.moment[ab], eta_dot, program));
    accel_moment = Vec3{psi[3 * 2 + 1] - psi[3 * 1 + 2], psi[3 * 0 + 2] - psi[3 * 2 + 0],
                        psi[3 * 1 + 0] - psi[3 * 0 + 1]};
  }
  const Vec3 moment = named(program, cross(s_p, a0) + mul(out.second_moment, alpha) + cross(w, spin) +
                                         cross(w, j_rate) + 2 * coriolis_moment + accel_moment);
  out.force = zero_vec() - force;
  out.moment = zero_vec() - moment;

  // Elastic equations.
  const Eigen::MatrixXd K = cleaned(body.stiffness), C = cleaned(beam.damping);
  std::array<Eigen::MatrixXd, 3> coriolis;
  for (int c = 0; c < 3; ++c) coriolis[c] = cleaned(inv.coriolis(c));
  const ex w2 = program.define(dot(w, w));
  Mat3 ww;  // w_a w_b
  for (int i = 0; i < 9; ++i) ww[i] = w[i / 3] * w[i % 3];
  ww = named(program, ww);
  for (int k = 0; k < n; ++k) {
    // int rho (N_k + D_k)^T a_p: P_k . a0 + L_k . alpha + int rho (N_k + D_k)^T W^2 p + 2 sum_c w_c C_c
    // eta_dot.
    ex inertia = out.linear_momentum[k][0] * a0[0] + out.linear_momentum[k][1] * a0[1] +
                 out.linear_momentum[k][2] * a0[2] + dot(out.angular_momentum[k], alpha);
    for (int a = 0; a < 3; ++a) {
      inertia -= w2 * D[3 * a + a][k];
      for (int c = 0; c < 3; ++c) inertia += ww[3 * a + c] * D[3 * c + a][k];
      if (shortens)  // int rho D_k . W^2 r = sum_ab (w_a w_b - w^2 delta_ab) int rho D_k,a r_b
        for (int c = 0; c < 3; ++c)
          inertia += (ww[3 * a + c] - (a == c ? w2 : ex(0))) * fs.at(fs.z[3 * a + c], k);
    }
    for (int c = 0; c < 3; ++c)
      inertia += 2 * w[c] * linear_combination(coriolis[c].row(k).transpose(), eta_dot);
    const ex elastic =
        -linear_combination(K.row(k).transpose(), eta) - linear_combination(C.row(k).transpose(), eta_dot);
    out.elastic_forcing.push_back(program.define(elastic - inertia));
  }
  const Eigen::MatrixXd M = cleaned(inv.elastic_mass());
  for (int k = 0; k < n; ++k)
    for (int l = 0; l < n; ++l) out.elastic_mass.push_back(number(M(k, l)));
  const ex nonlinear_strain = add_axial_strain(beam.axial_strain, eta, out.elastic_forcing, program);

  // T = 1/2 (m v0^2 + 2 v0.(w x s_p) + w.I w) + v0.(int rho p') + w.(L eta_dot) + 1/2 eta_dot^T M eta_dot:
  // 1/2 u^T M u with the mass matrix these terms give.
  const Vec3& v0 = b.velocity;
  ex elastic_kinetic = 0;
  for (int k = 0; k < n; ++k)
    elastic_kinetic += eta_dot[k] * linear_combination(M.row(k).transpose(), eta_dot);
  Vec3 l_rate = zero_vec();
  for (int k = 0; k < n; ++k) l_rate = l_rate + eta_dot[k] * out.angular_momentum[k];
  out.kinetic_energy = (out.mass * dot(v0, v0) + 2 * dot(v0, cross(w, s_p)) + dot(w, spin)) / 2 +
                       dot(v0, s_rate) + dot(w, l_rate) + elastic_kinetic / 2;
  ex strain = 0;
  for (int k = 0; k < n; ++k) strain += eta[k] * linear_combination(K.row(k).transpose(), eta);
  out.strain_energy = strain / 2 + nonlinear_strain;
  return out;
}

}  // namespace kanegen::kane
