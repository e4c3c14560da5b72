// SPDX-License-Identifier: GPL-2.0-or-later
#include "fem/continuum_element.hpp"

#include <cmath>
#include <sstream>

namespace kanegen::fem {

namespace {

/// Isotropic elasticity matrix: plane stress (3 x 3, strains xx, yy, gamma_xy)
/// or 3D (6 x 6, strains xx, yy, zz, gamma_xy, gamma_yz, gamma_zx).
Eigen::MatrixXd elasticity(int dimension, double E, double nu) {
  if (dimension == 2) {
    Eigen::MatrixXd d(3, 3);
    d << 1.0, nu, 0.0, nu, 1.0, 0.0, 0.0, 0.0, 0.5 * (1.0 - nu);
    return E / (1.0 - nu * nu) * d;
  }
  const double lambda = E * nu / ((1.0 + nu) * (1.0 - 2.0 * nu)), mu = E / (2.0 * (1.0 + nu));
  Eigen::MatrixXd d = Eigen::MatrixXd::Zero(6, 6);
  d.topLeftCorner(3, 3).setConstant(lambda);
  d.topLeftCorner(3, 3).diagonal().array() += 2.0 * mu;
  d.bottomRightCorner(3, 3).diagonal().setConstant(mu);
  return d;
}

/// Strain-displacement matrix B (3 or 6 rows x num_dofs) from dN/dx.
Eigen::MatrixXd strain_matrix(const Eigen::MatrixXd& dNdx) {
  const int n = static_cast<int>(dNdx.rows()), d = static_cast<int>(dNdx.cols());
  if (d == 2) {
    Eigen::MatrixXd b = Eigen::MatrixXd::Zero(3, 2 * n);
    for (int i = 0; i < n; ++i) {
      b(0, 2 * i) = b(2, 2 * i + 1) = dNdx(i, 0);
      b(1, 2 * i + 1) = b(2, 2 * i) = dNdx(i, 1);
    }
    return b;
  }
  Eigen::MatrixXd b = Eigen::MatrixXd::Zero(6, 3 * n);
  for (int i = 0; i < n; ++i) {
    const double dx = dNdx(i, 0), dy = dNdx(i, 1), dz = dNdx(i, 2);
    const int u = 3 * i, v = u + 1, w = u + 2;
    b(0, u) = dx;
    b(1, v) = dy;
    b(2, w) = dz;
    b(3, u) = dy, b(3, v) = dx;
    b(4, v) = dz, b(4, w) = dy;
    b(5, w) = dx, b(5, u) = dz;
  }
  return b;
}

std::string describe(const Eigen::Vector3d& xi, int dimension) {
  std::ostringstream out;
  out << "xi = (";
  for (int k = 0; k < dimension; ++k) out << (k ? ", " : "") << xi[k];
  out << ")";
  return out.str();
}

}  // namespace

ContinuumElement::ContinuumElement(ContinuumFamily family, const Eigen::Matrix3Xd& nodes,
                                   const ContinuumMaterial& material, double thickness)
    : family_(family), nodes_(nodes), material_(material), thickness_(thickness) {
  const int d = dimension(), n = num_nodes();
  if (nodes.cols() != n)
    throw std::invalid_argument(std::string(ccx_type_name(family)) + " element: expected " +
                                std::to_string(n) + " nodes, got " + std::to_string(nodes.cols()));
  if (!(material.E > 0.0 && material.rho > 0.0 && material.nu > -1.0 && material.nu < 0.5))
    throw std::invalid_argument("continuum element: material needs E > 0, rho > 0 and -1 < nu < 0.5");
  if (d == 2) {
    if (!(thickness > 0.0)) throw std::invalid_argument("plane element: thickness must be positive");
    const double scale = nodes.cwiseAbs().maxCoeff();
    if ((nodes.row(2).array() - nodes(2, 0)).abs().maxCoeff() > 1e-9 * std::max(scale, 1e-300))
      throw std::invalid_argument("plane element: its nodes are not in one plane z = const");
  } else {
    thickness_ = 1.0;
  }
  // det J must be positive at the nodes as well as at the Gauss points: a
  // folded element can still be positive at every Gauss point.
  const Eigen::MatrixXd corners = family_natural_nodes(family);
  double det_j = 0.0;
  for (int i = 0; i < n; ++i) {
    Eigen::Vector3d xi = Eigen::Vector3d::Zero();
    xi.head(d) = corners.col(i);
    physical_gradient(natural_shape(family, xi), xi, det_j);
  }
  for (const NaturalPoint& point : family_row(family).quadrature(thickness_)) {
    const Eigen::Vector3d& xi = point.xi;
    const NaturalShape s = natural_shape(family, xi);
    const Eigen::MatrixXd dNdx = physical_gradient(s, xi, det_j);
    gauss_.push_back({xi, s.N, dNdx, point.weight * det_j});
  }
}

Eigen::MatrixXd ContinuumElement::physical_gradient(const NaturalShape& shape, const Eigen::Vector3d& xi,
                                                    double& det_j) const {
  const int d = dimension();
  // J_kl = d x_l / d xi_k.
  const Eigen::MatrixXd jac = shape.dN.transpose() * nodes_.topRows(d).transpose();
  det_j = jac.determinant();
  if (!(det_j > 0.0)) throw InvertedElementError(det_j, describe(xi, d));
  return shape.dN * jac.inverse().transpose();
}

const DofLayout& ContinuumElement::node_layout() const {
  return dimension() == 2 ? plane_layout() : solid_layout();
}

ShapeSample ContinuumElement::sample(const Eigen::VectorXd& N, const Eigen::MatrixXd& dNdx) const {
  const int d = dimension(), n = num_nodes();
  ShapeSample s{nodes_ * N, Eigen::MatrixXd::Zero(3, d * n), Eigen::MatrixXd::Zero(3, d * n)};
  for (int i = 0; i < n; ++i) {
    for (int a = 0; a < d; ++a) s.N(a, d * i + a) = N[i];
    // theta = curl(d) / 2: theta_z = (dv/dx - du/dy) / 2, and for solids
    // theta_x = (dw/dy - dv/dz) / 2, theta_y = (du/dz - dw/dx) / 2.
    s.Nrot(2, d * i + 1) += 0.5 * dNdx(i, 0);
    s.Nrot(2, d * i + 0) -= 0.5 * dNdx(i, 1);
    if (d == 3) {
      s.Nrot(0, 3 * i + 2) += 0.5 * dNdx(i, 1);
      s.Nrot(0, 3 * i + 1) -= 0.5 * dNdx(i, 2);
      s.Nrot(1, 3 * i + 0) += 0.5 * dNdx(i, 2);
      s.Nrot(1, 3 * i + 2) -= 0.5 * dNdx(i, 0);
    }
  }
  return s;
}

ShapeSample ContinuumElement::shape(const Eigen::Vector3d& xi) const {
  const NaturalShape s = natural_shape(family_, xi);
  double det_j = 0.0;
  return sample(s.N, physical_gradient(s, xi, det_j));
}

std::vector<MassPoint> ContinuumElement::mass_points() const {
  std::vector<MassPoint> points;
  for (const GaussSample& g : gauss_) {
    ShapeSample s = sample(g.N, g.dNdx);
    points.push_back(
        {material_.rho * g.weight, s.r, std::move(s.N), Eigen::Matrix3d::Zero(), std::move(s.Nrot)});
  }
  return points;
}

Eigen::MatrixXd ContinuumElement::stiffness() const {
  const Eigen::MatrixXd D = elasticity(dimension(), material_.E, material_.nu);
  Eigen::MatrixXd k = Eigen::MatrixXd::Zero(num_dofs(), num_dofs());
  for (const GaussSample& g : gauss_) {
    const Eigen::MatrixXd b = strain_matrix(g.dNdx);
    k.noalias() += g.weight * b.transpose() * D * b;
  }
  return 0.5 * (k + k.transpose());  // exactly symmetric
}

Eigen::MatrixXd ContinuumElement::geometric_stiffness(const Prestress& prestress) const {
  if (!prestress.stress)
    throw std::invalid_argument(std::string(ccx_type_name(family_)) +
                                " element: the prestress has no stress field (Prestress::stress)");
  const int d = dimension(), n = num_nodes();
  // The same scalar block int dN_i^T S dN_j dV couples component a of node i with
  // component a of node j, for every a: assemble it once, then spread it.
  Eigen::MatrixXd block = Eigen::MatrixXd::Zero(n, n);
  for (const GaussSample& g : gauss_) {
    const Eigen::MatrixXd s = prestress.stress(g.xi).topLeftCorner(d, d);
    block.noalias() += g.weight * g.dNdx * s * g.dNdx.transpose();
  }
  block = (0.5 * (block + block.transpose())).eval();  // eval: no aliasing
  Eigen::MatrixXd k = Eigen::MatrixXd::Zero(num_dofs(), num_dofs());
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int a = 0; a < d; ++a) k(d * i + a, d * j + a) = block(i, j);
  return k;
}

Eigen::Matrix3d ContinuumElement::stress(const Eigen::VectorXd& u_e, const Eigen::Vector3d& xi) const {
  if (u_e.size() != num_dofs())
    throw std::invalid_argument("ContinuumElement::stress: expected " + std::to_string(num_dofs()) +
                                " element dofs, got " + std::to_string(u_e.size()));
  double det_j = 0.0;
  const Eigen::MatrixXd dNdx = physical_gradient(natural_shape(family_, xi), xi, det_j);
  const Eigen::VectorXd v = elasticity(dimension(), material_.E, material_.nu) * (strain_matrix(dNdx) * u_e);
  Eigen::Matrix3d sigma = Eigen::Matrix3d::Zero();
  if (dimension() == 2) {
    sigma(0, 0) = v[0], sigma(1, 1) = v[1];
    sigma(0, 1) = sigma(1, 0) = v[2];
    return sigma;
  }
  // Voigt order of strain_matrix: xx, yy, zz, xy, yz, zx.
  sigma.diagonal() = v.head<3>();
  sigma(0, 1) = sigma(1, 0) = v[3];
  sigma(1, 2) = sigma(2, 1) = v[4];
  sigma(2, 0) = sigma(0, 2) = v[5];
  return sigma;
}

Eigen::MatrixXd ContinuumElement::quadratic_strain_forces(const Eigen::MatrixXd& u_e) const {
  if (u_e.rows() != num_dofs())
    throw std::invalid_argument("ContinuumElement::quadratic_strain_forces: expected " +
                                std::to_string(num_dofs()) + " element dofs, got " +
                                std::to_string(u_e.rows()));
  const int d = dimension(), n = static_cast<int>(u_e.cols()), nodes = num_nodes();
  const Eigen::MatrixXd D = elasticity(d, material_.E, material_.nu);
  // Voigt rows of strain_matrix: (a, b) components, shears doubled.
  static const int plane[3][2] = {{0, 0}, {1, 1}, {0, 1}};
  static const int solid[6][2] = {{0, 0}, {1, 1}, {2, 2}, {0, 1}, {1, 2}, {2, 0}};
  const int voigt = d == 2 ? 3 : 6;
  Eigen::MatrixXd g = Eigen::MatrixXd::Zero(num_dofs(), pair_count(n));
  std::vector<Eigen::MatrixXd> grad(n);
  Eigen::MatrixXd q(voigt, pair_count(n));
  for (const GaussSample& s : gauss_) {
    for (int i = 0; i < n; ++i)  // G_cb = sum_node u(node, c) dN_node/dx_b
      grad[i] = Eigen::Map<const Eigen::MatrixXd>(u_e.col(i).data(), d, nodes) * s.dNdx;
    for (int i = 0; i < n; ++i)
      for (int j = i; j < n; ++j) {
        const Eigen::MatrixXd Q = 0.5 * (grad[i].transpose() * grad[j] + grad[j].transpose() * grad[i]);
        for (int v = 0; v < voigt; ++v) {
          const int* ab = d == 2 ? plane[v] : solid[v];
          q(v, pair_index(i, j, n)) = (ab[0] == ab[1] ? 1.0 : 2.0) * Q(ab[0], ab[1]);
        }
      }
    g.noalias() += (s.weight * strain_matrix(s.dNdx).transpose() * D) * q;
  }
  return g;
}

std::vector<Eigen::Vector3d> ContinuumElement::gauss_points() const {
  std::vector<Eigen::Vector3d> points;
  for (const GaussSample& g : gauss_) points.push_back(g.xi);
  return points;
}

double ContinuumElement::volume() const {
  double v = 0.0;
  for (const GaussSample& g : gauss_) v += g.weight;
  return v;
}

}  // namespace kanegen::fem
