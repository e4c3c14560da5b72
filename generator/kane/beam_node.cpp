// SPDX-License-Identifier: GPL-2.0-or-later
#include "kane/beam_node.hpp"

#include "kane/flexible_body.hpp"
#include "symbolic/variables.hpp"

namespace kanegen::kane {

NodePoint node_point(const fem::ElasticModel& beam, int node, const std::vector<GiNaC::ex>& eta,
                     symbolic::Program* program) {
  const auto define = [&](const GiNaC::ex& e) { return program ? program->define(e) : e; };
  const auto named = [&](const symbolic::Vec3& v) { return program ? symbolic::named(*program, v) : v; };
  // A beam's node, or a mesh body's interface (its averaged motion).
  const Eigen::MatrixXd t = beam.point_translation(node);
  const Eigen::Vector3d r = beam.point_position(node);
  const std::size_t n = eta.size();
  NodePoint out;
  out.partial.assign(n, symbolic::zero_vec());
  for (int a = 0; a < 3; ++a) {
    out.displacement[a] = linear_combination(t.row(a).transpose(), eta);
    for (std::size_t k = 0; k < n; ++k)
      out.partial[k][a] = symbolic::number(t(a, static_cast<Eigen::Index>(k)));
  }
  const Eigen::MatrixXd c = beam.point_rotation(node);
  for (int a = 0; a < 3; ++a) out.rotation[a] = define(linear_combination(c.row(a).transpose(), eta));
  if (beam.foreshortening)
    for (int a = 0; a < 3; ++a) {
      const Eigen::MatrixXd h = cleaned(beam.foreshortening->node[node][a]);
      for (Eigen::Index k = 0; k < h.rows(); ++k) {
        if (h.row(k).cwiseAbs().maxCoeff() == 0.0) continue;
        const GiNaC::ex h_eta = define(linear_combination(h.row(k).transpose(), eta));
        out.partial[k][a] -= h_eta;
        out.displacement[a] -= eta[k] * h_eta / 2;
      }
    }
  out.displacement = named(out.displacement);
  for (int a = 0; a < 3; ++a) out.position[a] = symbolic::number(r[a]) + out.displacement[a];
  out.position = named(out.position);
  for (auto& p : out.partial) p = named(p);
  return out;
}

}  // namespace kanegen::kane
