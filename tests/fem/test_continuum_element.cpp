// SPDX-License-Identifier: GPL-2.0-or-later
// Plane-stress quadrilaterals, hexahedra (issue 18), tetrahedra and wedges
// (issue 38) against closed forms: interpolation and partition of unity, the
// strain energy of homogeneous stress states on distorted elements, rigid
// motions free of strain, the patch test on Gmsh meshes (a linear field on
// the boundary gives it exactly inside), and the inertia invariants of a
// plate and of a block (mass, first and second moments, rigid motions
// carrying the rigid body's inertia).
#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <map>
#include <memory>

#include "fem/body.hpp"
#include "fem/continuum_element.hpp"
#include "fem/invariants.hpp"
#include "fem/mesh_body.hpp"

using namespace kanegen::fem;

namespace {

const ContinuumMaterial kSteel{2.1e11, 0.3, 7850.0};
const ContinuumFamily kFamilies[] = {
    ContinuumFamily::kQuad4, ContinuumFamily::kQuad8,  ContinuumFamily::kHex8,   ContinuumFamily::kHex20,
    ContinuumFamily::kTet10, ContinuumFamily::kWedge6, ContinuumFamily::kWedge15};
// The families whose elements tile a box on a grid (box_body).
const ContinuumFamily kBoxFamilies[] = {ContinuumFamily::kQuad4, ContinuumFamily::kQuad8,
                                        ContinuumFamily::kHex8, ContinuumFamily::kHex20};

/// Nodes of one element of the family mapped from natural coordinates by x = center + A xi / 2,
/// plus a bilinear twist (eps) on the corners so the element is not a parallelepiped.
Eigen::Matrix3Xd element_nodes(ContinuumFamily family, const Eigen::Matrix3d& A,
                               const Eigen::Vector3d& center, double eps) {
  const Eigen::MatrixXd c = family_natural_nodes(family);
  Eigen::Matrix3Xd x(3, c.cols());
  for (int i = 0; i < c.cols(); ++i) {
    Eigen::Vector3d xi = Eigen::Vector3d::Zero();
    xi.head(c.rows()) = c.col(i);
    x.col(i) = center + 0.5 * A * xi;
    x(0, i) += eps * xi[0] * xi[1];  // straight edges stay straight; the element is no longer affine
  }
  return x;
}

/// A body of nx x ny (x nz) elements of the family filling the box [0, size] (plate: z = 0).
Body box_body(ContinuumFamily family, const Eigen::Vector3d& size, int nx, int ny, int nz, double thickness) {
  const int d = family_dimension(family);
  Body body(d == 2 ? plane_layout() : solid_layout());
  if (d == 2) nz = 1;
  const Eigen::Vector3d h(size.x() / nx, size.y() / ny, d == 2 ? 0.0 : size.z() / nz);
  std::map<std::array<long, 3>, int> node_at;  // by position in units of h / 2
  for (int i = 0; i < nx; ++i)
    for (int j = 0; j < ny; ++j)
      for (int k = 0; k < nz; ++k) {
        const Eigen::Vector3d center =
            h.cwiseProduct(Eigen::Vector3d(i + 0.5, j + 0.5, d == 2 ? 0.0 : k + 0.5));
        const Eigen::Matrix3Xd x = element_nodes(family, h.asDiagonal(), center, 0.0);
        std::vector<int> nodes;
        for (int n = 0; n < x.cols(); ++n) {
          std::array<long, 3> key{};
          for (int a = 0; a < 3; ++a) key[a] = h[a] > 0 ? std::lround(2.0 * x(a, n) / h[a]) : 0;
          auto it = node_at.find(key);
          if (it == node_at.end()) it = node_at.emplace(key, body.add_node(x.col(n))).first;
          nodes.push_back(it->second);
        }
        body.add_element(std::make_shared<ContinuumElement>(family, x, kSteel, thickness), nodes,
                         Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero());
      }
  return body;
}

/// Nodal values of the displacement field u(x) = G x (+ e) on the body's nodes.
Eigen::VectorXd linear_field(const Body& body, const Eigen::Matrix3d& G, const Eigen::Vector3d& e) {
  Eigen::VectorXd q(body.num_dofs());
  for (int n = 0; n < body.num_nodes(); ++n)
    for (int k = 0; k < body.dofs_per_node(); ++k) q[body.dof(n, k)] = (G * body.node_position(n) + e)[k];
  return q;
}

}  // namespace

TEST_CASE("continuum: shape functions interpolate, sum to one, and have consistent gradients",
          "[continuum]") {
  for (ContinuumFamily family : kFamilies) {
    INFO(ccx_type_name(family));
    const Eigen::MatrixXd c = family_natural_nodes(family);
    const int d = static_cast<int>(c.rows()), n = static_cast<int>(c.cols());
    REQUIRE(n == family_num_nodes(family));
    for (int j = 0; j < n; ++j) {
      Eigen::Vector3d xi = Eigen::Vector3d::Zero();
      xi.head(d) = c.col(j);
      const NaturalShape s = natural_shape(family, xi);
      for (int i = 0; i < n; ++i) CHECK(s.N[i] == Approx(i == j ? 1.0 : 0.0).margin(1e-14));
    }
    const Eigen::Vector3d xi(0.31, -0.47, 0.22), h(1e-6, 0.0, 0.0);
    const NaturalShape s = natural_shape(family, xi);
    CHECK(s.N.sum() == Approx(1.0).epsilon(1e-14));
    CHECK(s.dN.colwise().sum().norm() < 1e-13);
    for (int k = 0; k < d; ++k) {
      Eigen::Vector3d step = Eigen::Vector3d::Zero();
      step[k] = 1e-6;
      const Eigen::VectorXd fd =
          (natural_shape(family, xi + step).N - natural_shape(family, xi - step).N) / 2e-6;
      CHECK((fd - s.dN.col(k)).norm() < 1e-8);
    }
  }
}

TEST_CASE("continuum: homogeneous stress states give the closed-form strain energy", "[continuum]") {
  // Uniaxial stress s along x: u = (s / E) (x, -nu y, -nu z) (plane stress: no z), energy s^2 V / (2 E);
  // simple shear u = (gamma y, 0, 0): energy G gamma^2 V / 2. Exact on a distorted element, since
  // isoparametric elements reproduce linear fields.
  const double s = 1e8, gamma = 1e-3, G = kSteel.E / (2.0 * (1.0 + kSteel.nu));
  Eigen::Matrix3d A;
  A << 0.3, 0.05, 0.02, -0.04, 0.2, 0.01, 0.0, 0.03, 0.1;
  for (ContinuumFamily family : kFamilies) {
    INFO(ccx_type_name(family));
    const bool plane = family_dimension(family) == 2;
    Eigen::Matrix3d a = A;
    if (plane) a.row(2).setZero(), a.col(2).setZero();
    const ContinuumElement element(family, element_nodes(family, a, Eigen::Vector3d(1, 2, 0), 0.02), kSteel,
                                   plane ? 0.004 : 1.0);
    Body body(element.node_layout());
    std::vector<int> nodes;
    for (int i = 0; i < element.num_nodes(); ++i)
      nodes.push_back(body.add_node(element.node_positions().col(i)));
    body.add_element(std::make_shared<ContinuumElement>(element), nodes, Eigen::Matrix3d::Identity(),
                     Eigen::Vector3d::Zero());
    const double V = element.volume();
    const Eigen::MatrixXd K = body.stiffness();
    const Eigen::VectorXd uniaxial =
        linear_field(body, (s / kSteel.E) * Eigen::Vector3d(1.0, -kSteel.nu, -kSteel.nu).asDiagonal(),
                     Eigen::Vector3d::Zero());
    CHECK(0.5 * uniaxial.dot(K * uniaxial) == Approx(s * s * V / (2.0 * kSteel.E)).epsilon(1e-10));
    Eigen::Matrix3d shear = Eigen::Matrix3d::Zero();
    shear(0, 1) = gamma;
    const Eigen::VectorXd sheared = linear_field(body, shear, Eigen::Vector3d::Zero());
    CHECK(0.5 * sheared.dot(K * sheared) == Approx(G * gamma * gamma * V / 2.0).epsilon(1e-10));
    // Rigid motions (translation, and for plane elements the rotation about z; infinitesimal rotations
    // are linear fields with antisymmetric G) store no energy.
    Eigen::Matrix3d spin = Eigen::Matrix3d::Zero();
    spin(0, 1) = -1e-3, spin(1, 0) = 1e-3;
    const Eigen::VectorXd rigid = linear_field(body, spin, Eigen::Vector3d(1e-3, -2e-3, 3e-3));
    CHECK((K * rigid).norm() < 1e-9 * K.norm() * rigid.norm());
  }
}

TEST_CASE("continuum: inertia invariants of a plate and a block match the closed forms", "[continuum]") {
  // Plate a x b x t and block a x b x c, each in 3 x 2 (x 2) elements, corner at the origin.
  const double a = 0.3, b = 0.05, c = 0.02, t = 0.004, rho = kSteel.rho;
  for (ContinuumFamily family : kBoxFamilies) {
    INFO(ccx_type_name(family));
    const bool plane = family_dimension(family) == 2;
    const Body body = box_body(family, Eigen::Vector3d(a, b, c), 3, 2, 2, t);
    const InertiaInvariants inv = body_invariants(body);
    const double m = rho * a * b * (plane ? t : c);
    const Eigen::Vector3d center(a / 2, b / 2, plane ? 0.0 : c / 2);
    // int rho r r^T about the origin: m (center center^T + diag(a^2, b^2, c^2) / 12); a plate is thin.
    const Eigen::Matrix3d second =
        m * (center * center.transpose() +
             Eigen::Vector3d(a * a, b * b, plane ? 0.0 : c * c).asDiagonal().toDenseMatrix() / 12.0);
    CHECK(inv.mass == Approx(m).epsilon(1e-13));
    CHECK((inv.first_moment - m * center).norm() < 1e-13 * m * a);
    CHECK((inv.second_moment - second).norm() < 1e-12 * second.norm());
    CHECK(inv.J.norm() == 0.0);
    // The invariants' translational mass is the assembled consistent mass.
    CHECK((inv.NtN() - body.mass()).norm() < 1e-12 * body.mass().norm());
    // A rigid translation e: S q = m e, q^T (int rho N^T N) q = m |e|^2.
    const Eigen::Vector3d e = plane ? Eigen::Vector3d(0.3, -0.7, 0.0) : Eigen::Vector3d(0.3, -0.7, 0.2);
    const Eigen::VectorXd qt = linear_field(body, Eigen::Matrix3d::Zero(), e);
    CHECK((inv.S * qt - m * e).norm() < 1e-12 * m);
    CHECK(qt.dot(inv.NtN() * qt) == Approx(m * e.squaredNorm()).epsilon(1e-12));
    // A small rigid rotation w, d = w x r: S q = w x (m center), int rho skew(r) N q = (I_O) w, the
    // rigid inertia about the origin, I_O = tr(second) 1 - second; and q^T NtN q = w^T I_O w.
    const Eigen::Vector3d w = plane ? Eigen::Vector3d(0.0, 0.0, 0.4) : Eigen::Vector3d(0.2, -0.5, 0.4);
    const Eigen::VectorXd qr = linear_field(body, skew(w), Eigen::Vector3d::Zero());
    const Eigen::Matrix3d I_O = second.trace() * Eigen::Matrix3d::Identity() - second;
    CHECK((inv.S * qr - w.cross(m * center)).norm() < 1e-12 * m * a);
    CHECK((inv.skew_r_N() * qr - I_O * w).norm() < 1e-12 * I_O.norm());
    CHECK(qr.dot(inv.NtN() * qr) == Approx(w.dot(I_O * w)).epsilon(1e-12));
    // Every S_nn is symmetric in (a, b) pairs as invariants.hpp states; Coriolis matrices antisymmetric.
    for (int k = 0; k < 3; ++k) CHECK((inv.coriolis(k) + inv.coriolis(k).transpose()).norm() < 1e-15 * m);
  }
}

TEST_CASE("continuum: inverted elements and bad input are refused", "[continuum]") {
  for (ContinuumFamily family : kFamilies) {
    INFO(ccx_type_name(family));
    const bool plane = family_dimension(family) == 2;
    Eigen::Matrix3d A = Eigen::Vector3d(0.2, 0.1, plane ? 0.0 : 0.1).asDiagonal();
    A(1, 1) = -0.1;  // mirrored: det J < 0 everywhere
    CHECK_THROWS_AS(ContinuumElement(family, element_nodes(family, A, Eigen::Vector3d::Zero(), 0.0), kSteel),
                    InvertedElementError);
    A(1, 1) = 0.1;
    // A mid-edge or corner node pulled across the element folds it.
    Eigen::Matrix3Xd folded = element_nodes(family, A, Eigen::Vector3d::Zero(), 0.0);
    folded(0, 0) = 0.25;
    CHECK_THROWS_AS(ContinuumElement(family, folded, kSteel), InvertedElementError);
    const Eigen::Matrix3Xd fine = element_nodes(family, A, Eigen::Vector3d::Zero(), 0.0);
    CHECK_THROWS_WITH(ContinuumElement(family, fine, ContinuumMaterial{2e11, 0.5, 7850.0}),
                      Catch::Contains("nu < 0.5"));
    CHECK_THROWS_AS(ContinuumElement(family, fine.leftCols(3), kSteel), std::invalid_argument);
    CHECK_THROWS_WITH(ContinuumElement(family, fine, kSteel).geometric_stiffness(Prestress{}),
                      Catch::Contains("no stress field"));
  }
  Eigen::Matrix3Xd tilted = element_nodes(ContinuumFamily::kQuad4, Eigen::Vector3d(1, 1, 0).asDiagonal(),
                                          Eigen::Vector3d::Zero(), 0.0);
  tilted(2, 2) = 0.1;
  CHECK_THROWS_WITH(ContinuumElement(ContinuumFamily::kQuad4, tilted, kSteel, 0.01),
                    Catch::Contains("not in one plane z = const"));
}

TEST_CASE("continuum: consistent mass of a rectangle and a brick is the textbook matrix", "[continuum]") {
  // Per direction, the bilinear consistent mass couples node pairs with weight 2 (same) or 1 (other)
  // over 6 (m = 1): M_ij = m prod_k (c_ik c_jk == 1 ? 2 : 1) / 6^d, the textbook m/36 [4 2 1 2] of the
  // rectangle and m/216 [8 4 2 1] of the brick; every translation component carries the same matrix.
  for (ContinuumFamily family : {ContinuumFamily::kQuad4, ContinuumFamily::kHex8}) {
    INFO(ccx_type_name(family));
    const int d = family_dimension(family);
    const Eigen::Matrix3d A = Eigen::Vector3d(0.3, 0.1, d == 2 ? 0.0 : 0.05).asDiagonal();
    const ContinuumElement element(family, element_nodes(family, A, Eigen::Vector3d(1, 1, 0), 0.0), kSteel,
                                   0.004);
    const double m = kSteel.rho * (d == 2 ? 0.3 * 0.1 * 0.004 : 0.3 * 0.1 * 0.05);
    const Eigen::MatrixXd c = family_natural_nodes(family), M = element.mass();
    for (int i = 0; i < c.cols(); ++i)
      for (int j = 0; j < c.cols(); ++j) {
        double expected = m;
        for (int k = 0; k < d; ++k) expected *= (c(k, i) == c(k, j) ? 2.0 : 1.0) / 6.0;
        for (int a = 0; a < d; ++a)
          for (int b = 0; b < d; ++b)
            CHECK(M(d * i + a, d * j + b) == Approx(a == b ? expected : 0.0).margin(1e-15 * m));
      }
  }
}

TEST_CASE("continuum: tetrahedra and wedges pass the patch test on Gmsh meshes of a bar", "[continuum]") {
  // The bars of data/bar_c3d10.inp, bar_c3d6.inp and bar_c3d15.inp (Gmsh, CalculiX's node order): a
  // linear field u = G x + e prescribed on the boundary nodes (x = 0, x = L, y = 0, y = H, z = 0 or z = T)
  // must come out exactly at every inner node from K u = 0, its strain constant: exact if the elements
  // reproduce constant strain across their shared faces. The same field as a rigid motion stores no energy.
  const double L = 0.2, H = 0.02, T = 0.012;
  Eigen::Matrix3d G;
  G << 1e-3, 2e-4, -3e-4, 5e-4, -7e-4, 1e-4, -2e-4, 3e-4, 4e-4;
  for (const char* name : {"bar_c3d10", "bar_c3d6", "bar_c3d15"}) {
    INFO(name);
    const InpMesh mesh = read_inp_mesh_file(std::string(KANEGEN_FEM_DATA_DIR) + "/" + name + ".inp");
    const MeshBody mb = build_mesh_body(mesh, kSteel);
    const Body& body = mb.body;
    const Eigen::MatrixXd K = body.stiffness();
    const Eigen::VectorXd exact = linear_field(body, G, Eigen::Vector3d(1e-3, -2e-3, 3e-3));
    std::vector<int> inner, outer;
    for (int n = 0; n < body.num_nodes(); ++n) {
      const Eigen::Vector3d x = body.node_position(n);
      const bool boundary = std::abs(x.x()) < 1e-12 || std::abs(x.x() - L) < 1e-12 ||
                            std::abs(x.y()) < 1e-12 || std::abs(x.y() - H) < 1e-12 ||
                            std::abs(x.z()) < 1e-12 || std::abs(x.z() - T) < 1e-12;
      for (int k = 0; k < 3; ++k) (boundary ? outer : inner).push_back(body.dof(n, k));
    }
    REQUIRE(!inner.empty());
    Eigen::MatrixXd Kii(inner.size(), inner.size()), Kio(inner.size(), outer.size());
    for (std::size_t i = 0; i < inner.size(); ++i) {
      for (std::size_t j = 0; j < inner.size(); ++j) Kii(i, j) = K(inner[i], inner[j]);
      for (std::size_t j = 0; j < outer.size(); ++j) Kio(i, j) = K(inner[i], outer[j]);
    }
    Eigen::VectorXd u_outer(outer.size()), u_exact(inner.size());
    for (std::size_t j = 0; j < outer.size(); ++j) u_outer[j] = exact[outer[j]];
    for (std::size_t i = 0; i < inner.size(); ++i) u_exact[i] = exact[inner[i]];
    const Eigen::VectorXd u_inner = Kii.llt().solve(-Kio * u_outer);
    CHECK((u_inner - u_exact).norm() < 1e-10 * u_exact.norm());
    // Rigid motions (a translation and an infinitesimal rotation) are free of strain.
    const Eigen::Vector3d w(0.2, -0.5, 0.4);
    const Eigen::VectorXd rigid = linear_field(body, skew(w), Eigen::Vector3d(1e-3, -2e-3, 3e-3));
    CHECK((K * rigid).norm() < 1e-9 * K.norm() * rigid.norm());
    // The mass is the bar's, whatever the quadrature (it integrates rho over the element exactly).
    const Eigen::VectorXd ex = linear_field(body, Eigen::Matrix3d::Zero(), Eigen::Vector3d::UnitX());
    CHECK(ex.dot(body.mass() * ex) == Approx(kSteel.rho * L * H * T).epsilon(1e-12));
  }
}
