// SPDX-License-Identifier: GPL-2.0-or-later
#include "fem/assumed_modes.hpp"

#include <cmath>
#include <sstream>

#include "model/model_error.hpp"

namespace kanegen::fem {

namespace {

/// One component of a mode, where its value and (bending) slope go.
struct Component {
  const std::string* text;
  const char* key;
  DofKind value;
  DofKind slope;      ///< for bending: the rotation that is the slope
  double slope_sign;  ///< theta_z = +v', theta_y = -w'; 0: no slope dof
};

/// `v`, finite, or a ModelError at `place`.
double finite(double v, double x, const std::string& file, const std::string& place,
              const std::string& what) {
  if (std::isfinite(v)) return v;
  std::ostringstream at;
  at << x;
  throw model::ModelError(file, place, what + " is not finite at x = " + at.str(),
                          "make the shape and its slope finite on the whole beam, 0 <= x <= L");
}

}  // namespace

Eigen::MatrixXd assumed_mode_basis(const Body& body, const model::ElasticPart& beam, const std::string& file,
                                   const ShapeSampler& sample) {
  const int count = static_cast<int>(beam.assumed_modes.size());
  std::map<std::string, double> parameters = beam.shape_parameters;
  parameters["L"] = body.node_position(body.num_nodes() - 1).x();
  std::vector<double> xs;
  for (int n = 0; n < body.num_nodes(); ++n) xs.push_back(body.node_position(n).x());
  Eigen::MatrixXd basis = Eigen::MatrixXd::Zero(body.num_dofs(), count);
  for (int j = 0; j < count; ++j) {
    const model::AssumedMode& mode = beam.assumed_modes[j];
    const Component components[] = {{&mode.u, "u", DofKind::kUx, DofKind::kUx, 0.0},
                                    {&mode.v, "v", DofKind::kUy, DofKind::kRz, 1.0},
                                    {&mode.w, "w", DofKind::kUz, DofKind::kRy, -1.0},
                                    {&mode.theta, "theta", DofKind::kRx, DofKind::kRx, 0.0}};
    for (const Component& c : components) {
      if (body.dof(0, c.value) < 0) continue;  // w and theta of a planar beam
      const std::string place = mode.where + "/" + c.key;
      std::vector<double> value, slope;
      try {
        sample(*c.text, parameters, xs, value, slope);
      } catch (const std::exception& e) {
        throw model::ModelError(file, place,
                                "cannot read shape function '" + *c.text + "' (" + e.what() + ")",
                                "use numbers, x, L, parameter names, + - * / ^, parentheses and sin cos tan "
                                "sqrt exp log");
      }
      for (int n = 0; n < body.num_nodes(); ++n) {
        basis(body.dof(n, c.value), j) = finite(value[n], xs[n], file, place, std::string("'") + c.key + "'");
        if (c.slope_sign != 0)
          basis(body.dof(n, c.slope), j) =
              c.slope_sign * finite(slope[n], xs[n], file, place, std::string("the slope d") + c.key + "/dx");
      }
    }
  }
  return basis;
}

}  // namespace kanegen::fem
