// SPDX-License-Identifier: GPL-2.0-or-later
// The geometric stiffness of the plane and solid elements (issue 18) against
// closed forms: a uniform stress on one (distorted) element and a linear
// displacement field u = G x give u^T K_sigma u = V tr(G S G^T), the analytic
// int sigma_ab du_i/dx_a du_i/dx_b dV; the recovered stress of a uniform
// strain is D epsilon; a bar pulled by consistent end loads and held without
// restraint of its contraction carries P / A at every Gauss point; and the
// centrifugal load's resultant is m Omega^2 times the centre of mass's radius.
#include <catch2/catch.hpp>
#include <cmath>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "fem/continuum_element.hpp"
#include "fem/continuum_foreshortening.hpp"
#include "fem/continuum_prestress.hpp"
#include "fem/mesh_body.hpp"
#include "fem/reduction.hpp"

using namespace kanegen::fem;

namespace {

const ContinuumMaterial kSteel{2.1e11, 0.3, 7850.0};
const ContinuumFamily kFamilies[] = {
    ContinuumFamily::kQuad4, ContinuumFamily::kQuad8,  ContinuumFamily::kHex8,   ContinuumFamily::kHex20,
    ContinuumFamily::kTet10, ContinuumFamily::kWedge6, ContinuumFamily::kWedge15};

/// The measure of the family's natural domain: [-1, 1]^d, the unit tetrahedron (1/6), the unit triangle
/// times [-1, 1] (1).
double natural_measure(ContinuumFamily family) {
  if (family == ContinuumFamily::kTet10) return 1.0 / 6.0;
  if (family == ContinuumFamily::kWedge6 || family == ContinuumFamily::kWedge15) return 1.0;
  return std::pow(2.0, family_dimension(family));
}

/// The family's nodes at x = A xi + offset (an affine element: a parallelogram, parallelepiped,
/// tetrahedron or wedge of volume |det A| natural_measure), with the node `bent` moved by `bend` (zero:
/// affine).
Eigen::Matrix3Xd affine_nodes(ContinuumFamily family, const Eigen::Matrix3d& A, const Eigen::Vector3d& bend) {
  const Eigen::MatrixXd c = family_natural_nodes(family);
  Eigen::Matrix3Xd x(3, c.cols());
  for (int i = 0; i < c.cols(); ++i) {
    Eigen::Vector3d xi = Eigen::Vector3d::Zero();
    xi.head(c.rows()) = c.col(i);
    x.col(i) = A * xi + Eigen::Vector3d(0.4, -0.2, 0.1);
  }
  x.col(2) += bend;
  return x;
}

/// The element dofs of the linear field u(x) = G x (the top-left d x d of G).
Eigen::VectorXd linear_field(const Eigen::Matrix3Xd& nodes, int d, const Eigen::Matrix3d& G) {
  Eigen::VectorXd u(d * nodes.cols());
  for (int i = 0; i < nodes.cols(); ++i) u.segment(d * i, d) = (G * nodes.col(i)).head(d);
  return u;
}

Eigen::Matrix3d uniform_stress(int d) {
  Eigen::Matrix3d s;
  s << 3.0e6, -1.2e6, 0.7e6, -1.2e6, -2.0e6, 0.4e6, 0.7e6, 0.4e6, 1.5e6;
  if (d == 2) s.row(2).setZero(), s.col(2).setZero();
  return s;
}

Prestress constant(const Eigen::Matrix3d& s) {
  Prestress p;
  p.stress = [s](const Eigen::Vector3d&) { return s; };
  return p;
}

}  // namespace

TEST_CASE("geometric: uniform stress, u^T K_sigma u = V tr(G S G^T) for linear fields and rotations",
          "[geometric]") {
  for (ContinuumFamily family : kFamilies) {
    INFO(ccx_type_name(family));
    const int d = family_dimension(family);
    const double t = 0.004;
    Eigen::Matrix3d A;  // sheared, so the element is no rectangle
    A << 0.15, 0.03, 0.01, -0.02, 0.05, 0.004, 0.0, 0.0, 0.03;
    if (d == 2) A.row(2).setZero(), A.col(2).setZero();
    const Eigen::Matrix3Xd nodes = affine_nodes(family, A, Eigen::Vector3d::Zero());
    const ContinuumElement element(family, nodes, kSteel, t);
    const double volume =
        std::abs(A.topLeftCorner(d, d).determinant()) * natural_measure(family) * (d == 2 ? t : 1.0);
    const Eigen::Matrix3d S = uniform_stress(d);
    const Eigen::MatrixXd kg = element.geometric_stiffness(constant(S));
    CHECK((kg - kg.transpose()).norm() == 0.0);
    Eigen::Matrix3d G;
    G << 0.3, -0.7, 0.2, 0.5, 0.1, -0.4, -0.6, 0.8, 0.9;
    if (d == 2) G.row(2).setZero(), G.col(2).setZero();
    const Eigen::VectorXd u = linear_field(nodes, d, G);
    CHECK(u.dot(kg * u) == Approx(volume * (G * S * G.transpose()).trace()).epsilon(1e-12));
    // sigma_xx alone: a small rotation theta about z (u = -theta y, v = theta x) and a stretch
    // u = eps x both give V sigma_xx (theta^2 or eps^2): int sigma_xx (du_i/dx)^2 dV.
    const double sxx = 5.0e6, theta = 1e-3, eps = 2e-3;
    const Eigen::MatrixXd kxx =
        element.geometric_stiffness(constant(Eigen::Vector3d(sxx, 0, 0).asDiagonal()));
    Eigen::Matrix3d rotation = Eigen::Matrix3d::Zero();
    rotation(0, 1) = -theta, rotation(1, 0) = theta;
    const Eigen::VectorXd r = linear_field(nodes, d, rotation);
    CHECK(r.dot(kxx * r) == Approx(volume * sxx * theta * theta).epsilon(1e-12));
    const Eigen::VectorXd s = linear_field(nodes, d, Eigen::Vector3d(eps, 0, 0).asDiagonal());
    CHECK(s.dot(kxx * s) == Approx(volume * sxx * eps * eps).epsilon(1e-12));
    // A rigid translation has no gradient: K_sigma t = 0.
    Eigen::VectorXd translation = Eigen::VectorXd::Zero(u.size());
    for (int i = 0; i < nodes.cols(); ++i) translation.segment(d * i, d).setConstant(1.0);
    CHECK((kg * translation).norm() < 1e-9 * kg.norm());
  }
}

TEST_CASE("geometric: on a distorted element the quadratic form is the quadrature's volume times the same",
          "[geometric]") {
  // Not affine: the volume is no closed form, but det J is integrated by the element's own Gauss rule
  // exactly for the linear families, and the field's gradient is still constant.
  for (ContinuumFamily family : kFamilies) {
    INFO(ccx_type_name(family));
    const int d = family_dimension(family);
    const Eigen::Matrix3d A = Eigen::Vector3d(0.1, 0.05, d == 2 ? 0.0 : 0.04).asDiagonal();
    const Eigen::Matrix3Xd nodes = affine_nodes(family, A, Eigen::Vector3d(0.03, 0.02, 0.0));
    const ContinuumElement element(family, nodes, kSteel, 0.01);
    Eigen::Matrix3d G;
    G << 0.2, 0.1, -0.3, -0.5, 0.4, 0.2, 0.1, 0.6, -0.2;
    if (d == 2) G.row(2).setZero(), G.col(2).setZero();
    const Eigen::Matrix3d S = uniform_stress(d);
    const Eigen::VectorXd u = linear_field(nodes, d, G);
    CHECK(u.dot(element.geometric_stiffness(constant(S)) * u) ==
          Approx(element.volume() * (G * S * G.transpose()).trace()).epsilon(1e-12));
  }
}

TEST_CASE("geometric: K_sigma needs a stress field", "[geometric]") {
  const ContinuumElement element(
      ContinuumFamily::kHex8,
      affine_nodes(ContinuumFamily::kHex8, Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero()), kSteel);
  Prestress axial_only;
  axial_only.axial_force = [](double) { return 1.0; };
  CHECK_THROWS_WITH(element.geometric_stiffness(axial_only), Catch::Contains("no stress field"));
}

TEST_CASE("geometric: the stress of a uniform uniaxial strain is E eps along x and zero elsewhere",
          "[geometric]") {
  // u = eps x, v = -nu eps y, w = -nu eps z: uniaxial stress E eps in 3D and in plane stress alike.
  for (ContinuumFamily family : kFamilies) {
    INFO(ccx_type_name(family));
    const int d = family_dimension(family);
    const double eps = 1e-4, nu = kSteel.nu;
    const Eigen::Matrix3d A = Eigen::Vector3d(0.1, 0.05, d == 2 ? 0.0 : 0.04).asDiagonal();
    const Eigen::Matrix3Xd nodes = affine_nodes(family, A, Eigen::Vector3d(0.02, -0.01, 0.0));
    const ContinuumElement element(family, nodes, kSteel, 0.01);
    const Eigen::VectorXd u = linear_field(nodes, d, Eigen::Vector3d(eps, -nu * eps, -nu * eps).asDiagonal());
    Eigen::Matrix3d expected = Eigen::Matrix3d::Zero();
    expected(0, 0) = kSteel.E * eps;
    for (const Eigen::Vector3d& xi : element.gauss_points())
      CHECK((element.stress(u, xi) - expected).norm() < 1e-9 * kSteel.E * eps);
    // A rigid rotation is stress-free.
    Eigen::Matrix3d rotation = Eigen::Matrix3d::Zero();
    rotation(0, 1) = -1e-3, rotation(1, 0) = 1e-3;
    CHECK(element.stress(linear_field(nodes, d, rotation), Eigen::Vector3d(0.3, -0.2, 0.1)).norm() <
          1e-9 * kSteel.E * 1e-3);
  }
}

TEST_CASE("geometric: a bar pulled by consistent end loads, held at its root face, carries P / A everywhere",
          "[geometric]") {
  // The root face is held along x only, plus one corner in y and z and another in z: nothing restrains
  // the Poisson contraction, so the stress is exactly uniaxial, and K_sigma is that of sigma_xx = P / A.
  const InpMesh mesh = read_inp_mesh_file(std::string(KANEGEN_FEM_DATA_DIR) + "/column_c3d20.inp");
  const MeshBody mb = build_mesh_body(mesh, kSteel);
  const double P = 500.0, A = 0.02 * 0.012, L = 0.3;
  Eigen::VectorXd f = Eigen::VectorXd::Zero(mb.body.num_dofs());
  std::vector<int> held;
  int corner = -1, other = -1;
  for (int node = 0; node < mb.body.num_nodes(); ++node) {
    const Eigen::Vector3d& x = mb.body.node_position(node);
    if (x.x() == 0.0) held.push_back(mb.body.dof(node, 0));
    if (x.norm() == 0.0) corner = node;
    if (x.x() == 0.0 && x.y() > 0.0199 && x.z() == 0.0) other = node;
  }
  REQUIRE(corner >= 0);
  REQUIRE(other >= 0);
  held.insert(held.end(), {mb.body.dof(corner, 1), mb.body.dof(corner, 2), mb.body.dof(other, 2)});
  // Serendipity faces: the consistent loads of a uniform traction are -1/12 at corners, 1/3 mid-edge.
  for (int e = 0; e < mb.body.num_elements(); ++e) {
    const ElementPlacement& placed = mb.body.element(e);
    const Eigen::MatrixXd c = family_natural_nodes(ContinuumFamily::kHex20);
    for (int i = 0; i < 20; ++i) {
      if (std::abs(mb.body.node_position(placed.nodes[i]).x() - L) > 1e-12) continue;
      const bool mid = c(1, i) == 0.0 || c(2, i) == 0.0;
      f[mb.body.dof(placed.nodes[i], 0)] += P / 2.0 * (mid ? 1.0 / 3.0 : -1.0 / 12.0);
    }
  }
  const Constraint c(mb.body.num_dofs(), held);
  const Eigen::VectorXd u = static_displacement(mb.body, c, f);
  Eigen::Matrix3d expected = Eigen::Matrix3d::Zero();
  expected(0, 0) = P / A;
  for (const ElementStress& s : gauss_point_stresses(mb.body, u)) {
    REQUIRE(s.xi.size() == 27);
    for (const Eigen::Matrix3d& sigma : s.sigma) CHECK((sigma - expected).norm() < 1e-8 * P / A);
  }
  const Eigen::MatrixXd kg = load_geometric_stiffness(mb.body, c, f);
  Eigen::VectorXd bend(mb.body.num_dofs());  // v = theta x: K_sigma gives P / A * V theta^2 = P L theta^2
  for (int node = 0; node < mb.body.num_nodes(); ++node)
    bend.segment(3 * node, 3) = Eigen::Vector3d(0.0, 1e-3 * mb.body.node_position(node).x(), 0.0);
  CHECK(bend.dot(kg * bend) == Approx(P * L * 1e-6).epsilon(1e-8));
  // Held at one face only in x, the bar could still slide sideways: refused.
  held.resize(held.size() - 3);
  CHECK_THROWS_WITH(static_displacement(mb.body, Constraint(mb.body.num_dofs(), held), f),
                    Catch::Contains("free to move rigidly"));
}

TEST_CASE("geometric: the centrifugal load's resultant is m Omega^2 r_c", "[geometric]") {
  const InpMesh mesh = read_inp_mesh_file(std::string(KANEGEN_FEM_DATA_DIR) + "/strip_cps8.inp");
  const double t = 0.004, L = 0.3, H = 0.01, omega = 40.0;
  const MeshBody mb = build_mesh_body(mesh, kSteel, t);
  const Eigen::VectorXd f = centrifugal_load(mb.body, Eigen::Vector3d(0.0, 0.0, omega));
  double fx = 0.0, fy = 0.0;
  for (int node = 0; node < mb.body.num_nodes(); ++node) fx += f[2 * node], fy += f[2 * node + 1];
  const double m = kSteel.rho * L * H * t;
  CHECK(fx == Approx(m * omega * omega * L / 2.0).epsilon(1e-12));
  CHECK(fy == Approx(m * omega * omega * H / 2.0).epsilon(1e-12));
  // A spin about the strip's own x axis pulls nothing along x.
  const Eigen::VectorXd fx_spin = centrifugal_load(mb.body, Eigen::Vector3d(omega, 0.0, 0.0));
  for (int node = 0; node < mb.body.num_nodes(); ++node) CHECK(fx_spin[2 * node] == 0.0);
  // The stress, hence K_sigma, is linear in the load: Omega^2 times that of a unit spin.
  const Constraint root = mb.clamped(mesh, "ROOT");
  const auto kg = [&](const Eigen::Vector3d& spin) {
    return load_geometric_stiffness(mb.body, root, centrifugal_load(mb.body, spin));
  };
  const Eigen::MatrixXd unit = kg(Eigen::Vector3d::UnitZ()), spun = kg(Eigen::Vector3d(0.0, 0.0, omega));
  CHECK((spun - omega * omega * unit).norm() < 1e-9 * spun.norm());
  CHECK(spun.norm() > 0.0);
}

TEST_CASE(
    "geometric: a thin solid held at its root face is held, however thin (the spin-up beam as a rectangle)",
    "[geometric]") {
  // thin_bar_c3d20.inp: 10 m x 77.5 mm x 5.16 mm, 20 x 1 x 1 C3D20, the beam's A = 4e-4 m^2 and
  // Iz = 2e-7 m^4. Its pivots reach 1e-15 of K's largest diagonal: a pivot ratio of 1e-6 refused it.
  const InpMesh mesh = read_inp_mesh_file(std::string(KANEGEN_FEM_DATA_DIR) + "/thin_bar_c3d20.inp");
  const ContinuumMaterial aluminium{7e10, 0.3, 3000.0};
  const MeshBody mb = build_mesh_body(mesh, aluminium, 1.0, "BAR");
  const Constraint root = mb.clamped(mesh, "ROOT");
  // 1 N across the tip face, in the plane of Iz: Euler-Bernoulli's P L^3 / 3 E Iz (shear: 5e-5 of it).
  const std::vector<int> tip = mb.node_set_dofs(mesh, "TIP");
  Eigen::VectorXd f = Eigen::VectorXd::Zero(mb.body.num_dofs());
  const int nodes = static_cast<int>(tip.size()) / 3;
  for (int dof : tip)
    if (dof % 3 == 1) f[dof] = 1.0 / nodes;
  const Eigen::VectorXd u = static_displacement(mb.body, root, f);
  double deflection = 0.0;
  for (int dof : tip)
    if (dof % 3 == 1) deflection += u[dof] / nodes;
  CHECK(deflection == Approx(1000.0 / (3.0 * 7e10 * 2e-7)).epsilon(0.02));
  // The fields of geometric stiffening, which the generator solves for its clamped modes.
  const Eigen::MatrixXd d = second_order_fields(mb.body, root, reduce_modal(mb.body, root, 4).basis);
  CHECK(d.allFinite());
  CHECK(d.norm() > 0.0);
}

TEST_CASE("geometric: held dofs that leave a rigid motion free are refused, naming the motion",
          "[geometric]") {
  const InpMesh mesh = read_inp_mesh_file(std::string(KANEGEN_FEM_DATA_DIR) + "/thin_bar_c3d20.inp");
  const MeshBody mb = build_mesh_body(mesh, kSteel, 1.0, "BAR");
  const Eigen::VectorXd f = Eigen::VectorXd::Ones(mb.body.num_dofs());
  // The root face held in x and y only: the bar slides along z.
  std::vector<int> held;
  for (int dof : mb.node_set_dofs(mesh, "ROOT"))
    if (dof % 3 != 2) held.push_back(dof);
  CHECK_THROWS_WITH(
      static_displacement(mb.body, Constraint(mb.body.num_dofs(), held), f),
      Catch::Contains("free to move rigidly (a translation along (0, 0, 1) of the part with node 0)"));
  // Only the root face's lower edge (z = -2.58 mm) held: the bar turns about it.
  held.clear();
  for (int node = 0; node < mb.body.num_nodes(); ++node) {
    const Eigen::Vector3d& x = mb.body.node_position(node);
    if (x.x() == 0.0 && x.z() < -0.002)
      for (int k = 0; k < 3; ++k) held.push_back(mb.body.dof(node, k));
  }
  REQUIRE(held.size() == 9);
  CHECK_THROWS_WITH(
      static_displacement(mb.body, Constraint(mb.body.num_dofs(), held), f),
      Catch::Contains("free to move rigidly (a rotation about the axis (0, 1, 0) through (0, 0, -0.00258) "
                      "of the part with node 0)"));
  // Nothing held: refused as before.
  CHECK_THROWS_WITH(static_displacement(mb.body, Constraint(mb.body.num_dofs(), {}), f),
                    Catch::Contains("free to move rigidly"));
}

TEST_CASE("geometric: a second, unconnected part of a mesh must be held too", "[geometric]") {
  // Two CPS4 squares side by side that share no node; only the first is clamped.
  std::istringstream in(
      "*NODE\n1, 0, 0\n2, 1, 0\n3, 1, 1\n4, 0, 1\n5, 1, 0\n6, 2, 0\n7, 2, 1\n8, 1, 1\n"
      "*ELEMENT, type=CPS4, ELSET=PLATE\n1, 1, 2, 3, 4\n2, 5, 6, 7, 8\n*NSET, NSET=LEFT\n1, 4\n");
  const InpMesh mesh = read_inp_mesh(in, "two_parts.inp");
  const MeshBody mb = build_mesh_body(mesh, kSteel, 0.01);
  const Constraint left = mb.clamped(mesh, "LEFT");
  const Eigen::VectorXd f = Eigen::VectorXd::Ones(mb.body.num_dofs());
  CHECK_THROWS_WITH(static_displacement(mb.body, left, f), Catch::Contains("free to move rigidly (a ") &&
                                                               Catch::Contains("of the part with node 4)"));
}
