// SPDX-License-Identifier: GPL-2.0-or-later
// Hand-written model tables with exact Jacobian kernels, for the
// generalized-alpha tests: a stiff two-mass chain (linear, with an exact
// solution), a pendulum written as a point mass on a circle (a closed loop,
// index 3), and a pendulum on a cart whose mass matrix depends on q, free
// or with the cart's motion prescribed.
#pragma once

#include <cmath>
#include <cstring>
#include <new>

#include "kanegen/runtime/model_table.hpp"

namespace genalpha_models {

using kanegen::runtime::ModelTable;

/// set_parameter/get_parameter for a Params made of P::np doubles named P::names.
template <class P>
bool set_param(void* p, const char* name, double value) {
  for (int i = 0; i < P::np; ++i)
    if (std::strcmp(P::names[i], name) == 0) {
      static_cast<double*>(p)[i] = value;
      return true;
    }
  return false;
}
template <class P>
double get_param(const void* p, int i) {
  return static_cast<const double*>(p)[i];
}
template <class P>
const P& par(const void* p) {
  return *static_cast<const P*>(p);
}

/// The kernels every table needs and that these models share.
template <class P>
ModelTable base_table(const char* name, int n, const char* const* names, const double* q0, const double* u0) {
  ModelTable t{};
  t.name = name;
  t.nq = t.nu = n;
  t.coordinate_names = t.speed_names = names;
  t.parameter_names = P::names;
  t.np = P::np;
  t.q0 = q0;
  t.u0 = u0;
  t.parameters_size = sizeof(P);
  t.default_parameters = [](void* p) { new (p) P(); };
  t.set_parameter = set_param<P>;
  t.get_parameter = get_param<P>;
  t.coordinate_rates = [](const double* q, const double* u, double* qdot) {
    (void)q;
    for (int i = 0; i < P::n; ++i) qdot[i] = u[i];
  };
  t.outputs = [](const void*, double, const double*, const double*, double*) {};
  return t;
}

// ---------------------------------------------------------------------------
// Wall -k1- m1 -k2- m2, x1 and x2 from rest lengths: M = diag(m1, m2),
// f = [-k1 x1 + k2 (x2 - x1), -k2 (x2 - x1)] - c u. With k2 >> k1 it is stiff.
struct ChainParams {
  static constexpr int np = 5, n = 2;
  static constexpr const char* names[np] = {"m1", "m2", "k1", "k2", "c"};
  double m1 = 1.0, m2 = 1.0, k1 = 1.0, k2 = 100.0, c = 0.0;
};

inline void chain_forcing(const void* p, double, const double* q, const double* u, const double*, double* f) {
  const ChainParams& s = par<ChainParams>(p);
  f[0] = -s.k1 * q[0] + s.k2 * (q[1] - q[0]) - s.c * u[0];
  f[1] = -s.k2 * (q[1] - q[0]) - s.c * u[1];
}

inline ModelTable chain_table() {
  using P = ChainParams;
  static const char* const names[] = {"x1", "x2"};
  static const double q0[] = {0.0, 0.0}, u0[] = {0.0, 0.0};
  ModelTable t = base_table<P>("chain2", 2, names, q0, u0);
  t.initial_state = [](const void*, double* q, double* u) { q[0] = q[1] = u[0] = u[1] = 0.0; };
  t.mass_matrix = [](const void* p, const double*, double* M) {
    M[0] = par<P>(p).m1;
    M[1] = M[2] = 0.0;
    M[3] = par<P>(p).m2;
  };
  t.forcing = chain_forcing;
  t.forward_dynamics = [](const void* p, double tt, const double* q, const double* u, const double* tau,
                          double* udot) {
    // As a generated kernel: the 1-based pivot of a singular M, else 0.
    if (par<P>(p).m1 == 0.0) return 1;
    if (par<P>(p).m2 == 0.0) return 2;
    chain_forcing(p, tt, q, u, tau, udot);
    udot[0] /= par<P>(p).m1;
    udot[1] /= par<P>(p).m2;
    return 0;
  };
  t.kinetic_energy = [](const void* p, const double*, const double* u) {
    return 0.5 * (par<P>(p).m1 * u[0] * u[0] + par<P>(p).m2 * u[1] * u[1]);
  };
  t.potential_energy = [](const void* p, const double* q) {
    const P& s = par<P>(p);
    return 0.5 * (s.k1 * q[0] * q[0] + s.k2 * (q[1] - q[0]) * (q[1] - q[0]));
  };
  t.forcing_jacobian = [](const void* p, double, const double*, const double*, const double*, double* dfdq,
                          double* dfdu) {
    const P& s = par<P>(p);
    dfdq[0] = -s.k1 - s.k2;
    dfdq[1] = s.k2;
    dfdq[2] = s.k2;
    dfdq[3] = -s.k2;
    dfdu[0] = dfdu[3] = -s.c;
    dfdu[1] = dfdu[2] = 0.0;
  };
  t.mass_matrix_product_jacobian = [](const void*, const double*, const double*, double* d) {
    for (int i = 0; i < 4; ++i) d[i] = 0.0;
  };
  return t;
}

// ---------------------------------------------------------------------------
// A pendulum as a point mass (x, y) on Phi = x^2 + y^2 - L^2 = 0 under
// gravity -g y: M = m I, f = [0, -m g], C = [2x, 2y],
// gamma = -2 (xdot^2 + ydot^2), d(C^T lambda)/dq = 2 lambda I.
struct PointParams {
  static constexpr int np = 3, n = 2;
  static constexpr const char* names[np] = {"m", "L", "g"};
  double m = 1.0, L = 1.0, g = 9.81;
};

inline int point_dynamics(const void* p, double, const double* q, const double* u, const double*,
                          double* udot, double* lambda) {
  const PointParams& s = par<PointParams>(p);
  const double cx = 2.0 * q[0], cy = 2.0 * q[1];
  const double S = (cx * cx + cy * cy) / s.m;  // C M^-1 C^T
  if (!(S > 0.0)) return -1;
  const double gamma = -2.0 * (u[0] * u[0] + u[1] * u[1]);
  lambda[0] = (gamma - cy * (-s.g)) / S;  // S lambda = gamma - C M^-1 f
  udot[0] = cx * lambda[0] / s.m;
  udot[1] = -s.g + cy * lambda[0] / s.m;
  return 0;
}

inline ModelTable point_pendulum_table() {
  using P = PointParams;
  static const char* const names[] = {"x", "y"};
  static const char* const loops[] = {"circle"};
  static const double q0[] = {1.0, 0.0}, u0[] = {0.0, 0.0};
  ModelTable t = base_table<P>("point_pendulum", 2, names, q0, u0);
  t.nc = 1;
  t.constraint_names = loops;
  t.initial_state = [](const void* p, double* q, double* u) {
    q[0] = par<P>(p).L;
    q[1] = u[0] = u[1] = 0.0;
  };
  t.mass_matrix = [](const void* p, const double*, double* M) {
    M[0] = M[3] = par<P>(p).m;
    M[1] = M[2] = 0.0;
  };
  t.forcing = [](const void* p, double, const double*, const double*, const double*, double* f) {
    f[0] = 0.0;
    f[1] = -par<P>(p).m * par<P>(p).g;
  };
  t.constraints = [](const void* p, const double* q, double* phi) {
    phi[0] = q[0] * q[0] + q[1] * q[1] - par<P>(p).L * par<P>(p).L;
  };
  t.constraint_jacobian = [](const void*, const double* q, double* C) {
    C[0] = 2.0 * q[0];
    C[1] = 2.0 * q[1];
  };
  t.constraint_bias = [](const void*, const double*, const double* u, double* gamma) {
    gamma[0] = -2.0 * (u[0] * u[0] + u[1] * u[1]);
  };
  t.constrained_dynamics = point_dynamics;
  t.forward_dynamics = [](const void* p, double tt, const double* q, const double* u, const double* tau,
                          double* udot) {
    double lambda = 0.0;
    return point_dynamics(p, tt, q, u, tau, udot, &lambda);
  };
  t.kinetic_energy = [](const void* p, const double*, const double* u) {
    return 0.5 * par<P>(p).m * (u[0] * u[0] + u[1] * u[1]);
  };
  t.potential_energy = [](const void* p, const double* q) { return par<P>(p).m * par<P>(p).g * q[1]; };
  t.forcing_jacobian = [](const void*, double, const double*, const double*, const double*, double* dfdq,
                          double* dfdu) {
    for (int i = 0; i < 4; ++i) dfdq[i] = dfdu[i] = 0.0;
  };
  t.mass_matrix_product_jacobian = [](const void*, const double*, const double*, double* d) {
    for (int i = 0; i < 4; ++i) d[i] = 0.0;
  };
  t.constraint_force_jacobian = [](const void*, const double*, const double* lambda, double* d) {
    d[0] = d[3] = 2.0 * lambda[0];
    d[1] = d[2] = 0.0;
  };
  return t;
}

// ---------------------------------------------------------------------------
// A pendulum (mass m2, length L, angle th from the downward vertical) on a
// cart (mass m1, position x): T = (m1 + m2) xd^2 / 2 + m2 L cos(th) xd thd
// + m2 L^2 thd^2 / 2, V = -m2 g L cos(th), so
// M = [[m1 + m2, m2 L cos th], [m2 L cos th, m2 L^2]],
// f = [m2 L sin(th) thd^2, -m2 g L sin th]. In the prescribed variant the
// cart follows x = A sin(W t).
struct CartParams {
  static constexpr int np = 6, n = 2;
  static constexpr const char* names[np] = {"m1", "m2", "L", "g", "A", "W"};
  double m1 = 2.0, m2 = 1.0, L = 0.5, g = 9.81, A = 0.1, W = 3.0;
};

inline void cart_mass_matrix(const void* p, const double* q, double* M) {
  const CartParams& s = par<CartParams>(p);
  M[0] = s.m1 + s.m2;
  M[1] = M[2] = s.m2 * s.L * std::cos(q[1]);
  M[3] = s.m2 * s.L * s.L;
}

inline void cart_forcing(const void* p, double, const double* q, const double* u, const double*, double* f) {
  const CartParams& s = par<CartParams>(p);
  f[0] = s.m2 * s.L * std::sin(q[1]) * u[1] * u[1];
  f[1] = -s.m2 * s.g * s.L * std::sin(q[1]);
}

inline ModelTable cart_pendulum_table(bool prescribed) {
  using P = CartParams;
  static const char* const names[] = {"x", "th"};
  static const int roles[] = {2, 0};
  static const double q0[] = {0.0, 1.2}, u0[] = {0.0, 0.0};
  ModelTable t = base_table<P>(prescribed ? "cart_pendulum_prescribed" : "cart_pendulum", 2, names, q0, u0);
  t.mass_matrix = cart_mass_matrix;
  t.forcing = cart_forcing;
  if (prescribed) {
    t.coordinate_roles = roles;
    t.initial_state = [](const void* p, double* q, double* u) {
      q[0] = 0.0;
      q[1] = 1.2;
      u[0] = par<P>(p).A * par<P>(p).W;
      u[1] = 0.0;
    };
    // As generated: the given acceleration, and the pendulum's row solved with it.
    t.forward_dynamics = [](const void* p, double tt, const double* q, const double* u, const double* tau,
                            double* udot) {
      const P& s = par<P>(p);
      double M[4], f[2];
      cart_mass_matrix(p, q, M);
      cart_forcing(p, tt, q, u, tau, f);
      udot[0] = -s.A * s.W * s.W * std::sin(s.W * tt);
      udot[1] = (f[1] - M[2] * udot[0]) / M[3];
      return 0;
    };
  } else {
    t.initial_state = [](const void*, double* q, double* u) {
      q[0] = 0.0;
      q[1] = 1.2;
      u[0] = u[1] = 0.0;
    };
    t.forward_dynamics = [](const void* p, double tt, const double* q, const double* u, const double* tau,
                            double* udot) {
      double M[4], f[2];
      cart_mass_matrix(p, q, M);
      cart_forcing(p, tt, q, u, tau, f);
      const double det = M[0] * M[3] - M[1] * M[2];
      if (!(det > 0.0)) return 1;
      udot[0] = (M[3] * f[0] - M[1] * f[1]) / det;
      udot[1] = (M[0] * f[1] - M[2] * f[0]) / det;
      return 0;
    };
  }
  t.kinetic_energy = [](const void* p, const double* q, const double* u) {
    double M[4];
    cart_mass_matrix(p, q, M);
    return 0.5 * (M[0] * u[0] * u[0] + 2.0 * M[1] * u[0] * u[1] + M[3] * u[1] * u[1]);
  };
  t.potential_energy = [](const void* p, const double* q) {
    return -par<P>(p).m2 * par<P>(p).g * par<P>(p).L * std::cos(q[1]);
  };
  t.forcing_jacobian = [](const void* p, double, const double* q, const double* u, const double*,
                          double* dfdq, double* dfdu) {
    const P& s = par<P>(p);
    dfdq[0] = dfdq[2] = 0.0;
    dfdq[1] = s.m2 * s.L * std::cos(q[1]) * u[1] * u[1];
    dfdq[3] = -s.m2 * s.g * s.L * std::cos(q[1]);
    dfdu[0] = dfdu[2] = dfdu[3] = 0.0;
    dfdu[1] = 2.0 * s.m2 * s.L * std::sin(q[1]) * u[1];
  };
  t.mass_matrix_product_jacobian = [](const void* p, const double* q, const double* a, double* d) {
    const double k = -par<P>(p).m2 * par<P>(p).L * std::sin(q[1]);
    d[0] = d[2] = 0.0;
    d[1] = k * a[1];
    d[3] = k * a[0];
  };
  return t;
}

// ---------------------------------------------------------------------------
// Three masses on springs to the wall, tied by one linear loop equation
// 10 x1 - 20 x2 + 5 x3 = 0: linear, so exact Newton converges in one
// iteration. Its saddle-point matrix keeps row 1 at column 0 (m1 > 10) and
// takes the loop row, which has a multiplier from column 0, as the pivot of
// column 1 (20 > m2): a row swap that moves a multiplier.
struct TiedParams {
  static constexpr int np = 6, n = 3;
  static constexpr const char* names[np] = {"m1", "m2", "m3", "k1", "k2", "k3"};
  double m1 = 20.0, m2 = 2.0, m3 = 3.0, k1 = 40.0, k2 = 50.0, k3 = 60.0;
};

inline constexpr double kTie[3] = {10.0, -20.0, 5.0};

inline int tied_dynamics(const void* p, double, const double* q, const double* u, const double*, double* udot,
                         double* lambda) {
  const TiedParams& s = par<TiedParams>(p);
  const double m[3] = {s.m1, s.m2, s.m3}, f[3] = {-s.k1 * q[0], -s.k2 * q[1], -s.k3 * q[2]};
  (void)u;
  double S = 0.0, cmf = 0.0;  // C M^-1 C^T, C M^-1 f; gamma = 0 (C constant)
  for (int i = 0; i < 3; ++i) {
    S += kTie[i] * kTie[i] / m[i];
    cmf += kTie[i] * f[i] / m[i];
  }
  lambda[0] = -cmf / S;
  for (int i = 0; i < 3; ++i) udot[i] = (f[i] + kTie[i] * lambda[0]) / m[i];
  return 0;
}

inline ModelTable tied_table() {
  using P = TiedParams;
  static const char* const names[] = {"x1", "x2", "x3"};
  static const char* const loops[] = {"tie"};
  static const int roles[] = {0, 0, 0};
  static const double q0[] = {1.0, 0.5, 0.0}, u0[] = {0.0, 0.0, 0.0};
  ModelTable t = base_table<P>("tied", 3, names, q0, u0);
  t.nc = 1;
  t.constraint_names = loops;
  t.coordinate_roles = roles;
  t.initial_state = [](const void*, double* q, double* u) {
    q[0] = 1.0;
    q[1] = 0.5;
    q[2] = u[0] = u[1] = u[2] = 0.0;
  };
  t.mass_matrix = [](const void* p, const double*, double* M) {
    for (int i = 0; i < 9; ++i) M[i] = 0.0;
    M[0] = par<P>(p).m1;
    M[4] = par<P>(p).m2;
    M[8] = par<P>(p).m3;
  };
  t.forcing = [](const void* p, double, const double* q, const double*, const double*, double* f) {
    f[0] = -par<P>(p).k1 * q[0];
    f[1] = -par<P>(p).k2 * q[1];
    f[2] = -par<P>(p).k3 * q[2];
  };
  t.constraints = [](const void*, const double* q, double* phi) {
    phi[0] = kTie[0] * q[0] + kTie[1] * q[1] + kTie[2] * q[2];
  };
  t.constraint_jacobian = [](const void*, const double*, double* C) {
    for (int i = 0; i < 3; ++i) C[i] = kTie[i];
  };
  t.constraint_bias = [](const void*, const double*, const double*, double* gamma) { gamma[0] = 0.0; };
  t.constrained_dynamics = tied_dynamics;
  t.forward_dynamics = [](const void* p, double tt, const double* q, const double* u, const double* tau,
                          double* udot) {
    double lambda = 0.0;
    return tied_dynamics(p, tt, q, u, tau, udot, &lambda);
  };
  t.kinetic_energy = [](const void* p, const double*, const double* u) {
    const P& s = par<P>(p);
    return 0.5 * (s.m1 * u[0] * u[0] + s.m2 * u[1] * u[1] + s.m3 * u[2] * u[2]);
  };
  t.potential_energy = [](const void* p, const double* q) {
    const P& s = par<P>(p);
    return 0.5 * (s.k1 * q[0] * q[0] + s.k2 * q[1] * q[1] + s.k3 * q[2] * q[2]);
  };
  t.forcing_jacobian = [](const void* p, double, const double*, const double*, const double*, double* dfdq,
                          double* dfdu) {
    for (int i = 0; i < 9; ++i) dfdq[i] = dfdu[i] = 0.0;
    dfdq[0] = -par<P>(p).k1;
    dfdq[4] = -par<P>(p).k2;
    dfdq[8] = -par<P>(p).k3;
  };
  t.mass_matrix_product_jacobian = [](const void*, const double*, const double*, double* d) {
    for (int i = 0; i < 9; ++i) d[i] = 0.0;
  };
  t.constraint_force_jacobian = [](const void*, const double*, const double*, double* d) {
    for (int i = 0; i < 9; ++i) d[i] = 0.0;
  };
  return t;
}

}  // namespace genalpha_models
