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

FlexibleTerms flexible_terms(const fem::ModelBeam& beam, bool geometric_stiffening,
                             const kinematics::BodyState& b, const std::vector<ex>& eta,
                             const std::vector<ex>& eta_dot, Program& program) {
  const fem::ReducedBody& body = beam.reduced;
  const fem::InertiaInvariants& inv = body.invariants;
  const int n = inv.n;
  FlexibleTerms out;

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
  // P[3a+b] = int rho p_a p_b = second_ab + S_r[3b+a] eta + D[3a+b] eta.
  Mat3 P;
  for (int a = 0; a < 3; ++a)
    for (int c = 0; c < 3; ++c) {
      ex sum = number(inv.second_moment(a, c)) + linear_combination(S_r.row(3 * c + a).transpose(), eta);
      for (int k = 0; k < n; ++k) sum += D[3 * a + c][k] * eta[k];
      P[3 * a + c] = sum;
    }
  for (int a = 0; a < 3; ++a)
    for (int c = 0; c < a; ++c) P[3 * a + c] = P[3 * c + a];  // symmetric: one definition each
  P = named(program, P);

  out.mass = number(inv.mass);
  out.first_moment = named(
      program, Vec3{number(inv.first_moment[0]), number(inv.first_moment[1]), number(inv.first_moment[2])} +
                   rows(S, eta));
  const ex trace = P[0] + P[4] + P[8];
  for (int a = 0; a < 3; ++a)
    for (int c = 0; c < 3; ++c)
      out.second_moment[3 * a + c] = (a == c ? trace : ex(0)) - P[3 * a + c] + J[3 * a + c];
  out.second_moment = named(program, out.second_moment);

  // Momentum of eta_dot_k = 1: P_k = S_k, L_k = int rho p x N_k + J_Nrot_k.
  for (int k = 0; k < n; ++k) {
    out.linear_momentum.push_back({number(S(0, k)), number(S(1, k)), number(S(2, k))});
    out.angular_momentum.push_back(
        named(program, Vec3{D[3 * 1 + 2][k] - D[3 * 2 + 1][k] + number(J_Nrot(0, k)),
                            D[3 * 2 + 0][k] - D[3 * 0 + 2][k] + number(J_Nrot(1, k)),
                            D[3 * 0 + 1][k] - D[3 * 1 + 0][k] + number(J_Nrot(2, k))}));
  }

  // Rest accelerations (u_dot = 0): a_p = a0 + alpha x p + w x (w x p) + 2 w x N eta_dot.
  const Vec3& w = b.omega;
  const Vec3& a0 = b.accel_rest;
  const Vec3& alpha = b.alpha_rest;
  const Vec3 s_p = out.first_moment;
  const Vec3 s_rate = named(program, rows(S, eta_dot));  // int rho N eta_dot
  const Vec3 force =
      named(program, out.mass * a0 + cross(alpha, s_p) + cross(w, cross(w, s_p)) + 2 * cross(w, s_rate));
  // Dw[3a+b] = int rho (N eta_dot)_a p_b = sum_k eta_dot_k D[3b+a][k].
  Mat3 Dw;
  for (int a = 0; a < 3; ++a)
    for (int c = 0; c < 3; ++c) {
      ex sum = 0;
      for (int k = 0; k < n; ++k) sum += eta_dot[k] * D[3 * c + a][k];
      Dw[3 * a + c] = sum;
    }
  Dw = named(program, Dw);
  const Vec3 spin = named(program, mul(out.second_moment, w));
  const Vec3 j_rate = named(program, rows(J_Nrot, eta_dot));
  const ex dw_trace = Dw[0] + Dw[4] + Dw[8];
  const Vec3 coriolis_moment = dw_trace * w - mul(Dw, w);
  const Vec3 moment = named(program, cross(s_p, a0) + mul(out.second_moment, alpha) + cross(w, spin) +
                                         cross(w, j_rate) + 2 * coriolis_moment);
  out.force = zero_vec() - force;
  out.moment = zero_vec() - moment;

  // Elastic equations.
  const Eigen::MatrixXd K = cleaned(body.stiffness), C = cleaned(beam.damping);
  std::array<Eigen::MatrixXd, 3> coriolis;
  for (int c = 0; c < 3; ++c) coriolis[c] = cleaned(inv.coriolis(c));
  ex a_const = 0, a_lin = 0;
  Eigen::MatrixXd Ku, Kl;
  if (geometric_stiffening && body.geometric) {
    // Axial load per unit mass a_const + a_lin x of the link's motion (fem/rotating.hpp).
    a_lin = program.define(w[1] * w[1] + w[2] * w[2]);
    a_const = program.define(-a0[0]);
    Ku = cleaned(body.geometric->uniform);
    Kl = cleaned(body.geometric->linear);
  }
  const ex w2 = program.define(dot(w, w));
  Mat3 ww;  // w_a w_b
  for (int i = 0; i < 9; ++i) ww[i] = w[i / 3] * w[i % 3];
  ww = named(program, ww);
  for (int k = 0; k < n; ++k) {
    // int rho N_k^T a_p: S^T a0 + L^T alpha + int rho N_k^T W^2 p + 2 sum_c w_c C_c eta_dot.
    ex inertia = out.linear_momentum[k][0] * a0[0] + out.linear_momentum[k][1] * a0[1] +
                 out.linear_momentum[k][2] * a0[2] + dot(out.angular_momentum[k], alpha);
    for (int a = 0; a < 3; ++a) {
      inertia -= w2 * D[3 * a + a][k];
      for (int c = 0; c < 3; ++c) inertia += ww[3 * a + c] * D[3 * c + a][k];
    }
    for (int c = 0; c < 3; ++c)
      inertia += 2 * w[c] * linear_combination(coriolis[c].row(k).transpose(), eta_dot);
    ex elastic =
        -linear_combination(K.row(k).transpose(), eta) - linear_combination(C.row(k).transpose(), eta_dot);
    if (Ku.size())
      elastic -= a_const * linear_combination(Ku.row(k).transpose(), eta) +
                 a_lin * linear_combination(Kl.row(k).transpose(), eta);
    out.elastic_forcing.push_back(program.define(elastic - inertia));
  }
  const Eigen::MatrixXd M = cleaned(inv.elastic_mass());
  for (int k = 0; k < n; ++k)
    for (int l = 0; l < n; ++l) out.elastic_mass.push_back(number(M(k, l)));

  // T = 1/2 (m v0^2 + 2 v0.(w x s_p) + w.I w) + v0.(S eta_dot) + w.(L eta_dot) + 1/2 eta_dot^T M eta_dot.
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
  out.strain_energy = strain / 2;
  return out;
}

}  // namespace kanegen::kane
