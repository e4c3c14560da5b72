// SPDX-License-Identifier: GPL-2.0-or-later
// A rigid body on a planar joint (coordinates x, y along e1, e2 across the
// joint's axis n, and the turn theta about n), against the closed form from
// Newton and Euler's equations. With the centre of mass at c (body axes; in
// the plane c1 = c.e1, c2 = c.e2, since the body axes are the joint's at
// theta = 0), r = (c1 cos - c2 sin, c1 sin + c2 cos) in (e1, e2), mass m,
// I = n^T I_c n and gravity (gx, gy) in the plane:
//   M = [[m, 0, -m r2], [0, m, m r1], [-m r2, m r1, I + m |r|^2]]
//   f = (m gx + m w^2 r1, m gy + m w^2 r2, m (r1 gy - r2 gx)) + tau
// The plane's axes follow docs/model-format.md: e1 is the coordinate axis
// least aligned with n (the first on a tie) made normal to it, e2 = n x e1;
// they are written out here, not taken from the loader.
#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "planar_body.hpp"
#include "planar_tilted.hpp"

namespace {

using V3 = std::array<double, 3>;

double dot(const V3& a, const V3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

struct PlanarBody {
  double m = 0, c1 = 0, c2 = 0, cn = 0, inertia = 0;  ///< inertia: about n through the centre of mass
  double gx = 0, gy = 0, gn = 0, g_origin = 0;        ///< gravity in (e1, e2, n); g . (joint origin)

  std::array<double, 2> r(double theta) const {
    return {c1 * std::cos(theta) - c2 * std::sin(theta), c1 * std::sin(theta) + c2 * std::cos(theta)};
  }
  std::array<double, 9> mass_matrix(const double* q) const {
    const auto [r1, r2] = r(q[2]);
    return {m, 0, -m * r2, 0, m, m * r1, -m * r2, m * r1, inertia + m * (r1 * r1 + r2 * r2)};
  }
  std::array<double, 3> forcing(const double* q, const double* u, const double* tau) const {
    const auto [r1, r2] = r(q[2]);
    const double w2 = u[2] * u[2];
    return {m * gx + m * w2 * r1 + tau[0], m * gy + m * w2 * r2 + tau[1], m * (r1 * gy - r2 * gx) + tau[2]};
  }
  double kinetic(const double* q, const double* u) const {
    const auto [r1, r2] = r(q[2]);
    const double v1 = u[0] - u[2] * r2, v2 = u[1] + u[2] * r1;
    return 0.5 * m * (v1 * v1 + v2 * v2) + 0.5 * inertia * u[2] * u[2];
  }
  double potential(const double* q) const {
    const auto [r1, r2] = r(q[2]);
    return -m * (g_origin + gx * (q[0] + r1) + gy * (q[1] + r2) + gn * cn);
  }
};

/// A generated model's kernels that the closed form checks.
template <class Params>
struct Kernels {
  void (*mass_matrix)(const Params&, const double*, double*);
  void (*forcing)(const Params&, double, const double*, const double*, const double*, double*);
  double (*kinetic_energy)(const Params&, const double*, const double*);
  double (*potential_energy)(const Params&, const double*);
};

template <class Params>
void check_against(const PlanarBody& body, const Params& p, const Kernels<Params>& k, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> any(-3.0, 3.0);
  for (int sample = 0; sample < 20; ++sample) {
    INFO("sample " << sample);
    const double q[3] = {any(rng), any(rng), any(rng)}, u[3] = {any(rng), any(rng), any(rng)};
    const double tau[3] = {any(rng), any(rng), any(rng)};
    double mm[9], f[3];
    k.mass_matrix(p, q, mm);
    k.forcing(p, 0.0, q, u, tau, f);
    const std::array<double, 9> m_ref = body.mass_matrix(q);
    const std::array<double, 3> f_ref = body.forcing(q, u, tau);
    for (int i = 0; i < 9; ++i) CHECK(mm[i] == Approx(m_ref[i]).margin(1e-13));
    for (int i = 0; i < 3; ++i) CHECK(f[i] == Approx(f_ref[i]).margin(1e-12));
    CHECK(k.kinetic_energy(p, q, u) == Approx(body.kinetic(q, u)).margin(1e-12));
    CHECK(k.potential_energy(p, q) == Approx(body.potential(q)).margin(1e-12));
  }
}

}  // namespace

TEST_CASE("a body on a planar joint across z matches the closed form", "[regression][planar]") {
  namespace model = kanegen_models::planar_body;
  model::Params p;
  CHECK(std::string(model::coordinate_names[0]) == "slide_x");
  CHECK(std::string(model::coordinate_names[1]) == "slide_y");
  CHECK(std::string(model::coordinate_names[2]) == "slide_theta");
  PlanarBody body;  // n = z: e1 = x, e2 = y
  body.m = p.m;
  body.c1 = p.cx;
  body.c2 = p.cy;
  body.cn = 0.2;
  body.inertia = p.izz;
  body.gy = -p.g;
  check_against(body, p,
                Kernels<model::Params>{&model::mass_matrix, &model::forcing, &model::kinetic_energy,
                                       &model::potential_energy},
                11);

  // The model file's initial state, and the outputs at it.
  CHECK(std::vector<double>(model::q0, model::q0 + 3) == std::vector<double>{0.1, 0.2, 0.4});
  CHECK(std::vector<double>(model::u0, model::u0 + 3) == std::vector<double>{1.0, 2.0, 3.0});
  double y[4];
  model::outputs(p, 0.0, model::q0, model::u0, y);
  const auto [r1, r2] = body.r(0.4);
  CHECK(y[0] == Approx(0.1 + r1).margin(1e-14));
  CHECK(y[1] == Approx(0.2 + r2).margin(1e-14));
  CHECK(y[2] == Approx(0.2).margin(1e-14));
  CHECK(y[3] == Approx(0.4).margin(1e-14));
}

TEST_CASE("a body on an oblique, turned and offset planar joint matches the closed form",
          "[regression][planar]") {
  namespace model = kanegen_models::planar_tilted;
  model::Params p;
  const double s = 1 / std::sqrt(2.0);
  const V3 e1{1, 0, 0}, e2{0, s, -s}, n{0, s, s};  // n = [0, 1, 1] / sqrt 2
  // Gravity (0, 0, -g) in the joint frame: R0^T g, R0 = Rz(yaw) Ry(pitch) Rx(roll).
  const double roll = 0.3, pitch = -0.2, yaw = 0.5;
  const double cr = std::cos(roll), sr = std::sin(roll), cp = std::cos(pitch), sp = std::sin(pitch);
  const double cyaw = std::cos(yaw), syaw = std::sin(yaw);
  const double r0[3][3] = {{cyaw * cp, cyaw * sp * sr - syaw * cr, cyaw * sp * cr + syaw * sr},
                           {syaw * cp, syaw * sp * sr + cyaw * cr, syaw * sp * cr - cyaw * sr},
                           {-sp, cp * sr, cp * cr}};
  V3 g_joint{};
  for (int i = 0; i < 3; ++i) g_joint[i] = r0[2][i] * -p.g;  // (R0^T g)_i = R0_{2i} g_z
  const V3 c{0.25, -0.15, 0.1};
  const double ic[3][3] = {{0.06, 0.004, -0.003}, {0.004, 0.05, 0.002}, {-0.003, 0.002, 0.04}};
  PlanarBody body;
  body.m = p.m;
  body.c1 = dot(c, e1);
  body.c2 = dot(c, e2);
  body.cn = dot(c, n);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) body.inertia += n[i] * ic[i][j] * n[j];
  body.gx = dot(g_joint, e1);
  body.gy = dot(g_joint, e2);
  body.gn = dot(g_joint, n);
  body.g_origin = -p.g * 0.3;  // g . (0.1, 0.2, 0.3)
  check_against(body, p,
                Kernels<model::Params>{&model::mass_matrix, &model::forcing, &model::kinetic_energy,
                                       &model::potential_energy},
                12);
}
