// SPDX-License-Identifier: GPL-2.0-or-later
#include "fem/assumed_modes.hpp"

#include <ginac/ginac.h>

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

class Sampler {
 public:
  Sampler(const model::FlexibleBeam& beam, const std::string& file, double length) : file_(file) {
    for (const auto& [name, value] : beam.shape_parameters) table_[name] = GiNaC::numeric(value);
    table_["x"] = x_;
    table_["L"] = GiNaC::numeric(length);
    table_["pi"] = GiNaC::Pi;
  }

  GiNaC::ex read(const std::string& text, const std::string& place) const {
    GiNaC::parser reader(table_, /*strict=*/true);
    try {
      return reader(text);
    } catch (const std::exception& e) {
      throw model::ModelError(file_, place, "cannot read shape function '" + text + "' (" + e.what() + ")",
                              "use numbers, x, L, parameter names, + - * / ^, parentheses and sin cos tan "
                              "sqrt exp log");
    }
  }

  GiNaC::ex slope(const GiNaC::ex& e) const { return e.diff(x_); }

  double at(const GiNaC::ex& e, double x, const std::string& place, const std::string& what) const {
    double value = NAN;
    try {
      const GiNaC::ex v = GiNaC::evalf(e.subs(x_ == GiNaC::numeric(x)));
      if (GiNaC::is_a<GiNaC::numeric>(v) && GiNaC::ex_to<GiNaC::numeric>(v).is_real())
        value = GiNaC::ex_to<GiNaC::numeric>(v).to_double();
    } catch (const std::exception&) {
      // A pole (1/x, log(x) at 0): not finite, reported below.
    }
    if (!std::isfinite(value)) {
      std::ostringstream at;
      at << x;
      throw model::ModelError(file_, place, what + " is not finite at x = " + at.str(),
                              "make the shape and its slope finite on the whole beam, 0 <= x <= L");
    }
    return value;
  }

 private:
  std::string file_;
  GiNaC::symbol x_{"x"};
  GiNaC::symtab table_;
};

}  // namespace

Eigen::MatrixXd assumed_mode_basis(const Body& body, const model::FlexibleBeam& beam,
                                   const std::string& file) {
  const int count = static_cast<int>(beam.assumed_modes.size());
  const double length = body.node_position(body.num_nodes() - 1).x();
  const Sampler sampler(beam, file, length);
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
      const GiNaC::ex shape = sampler.read(*c.text, place);
      const GiNaC::ex slope = sampler.slope(shape);
      for (int n = 0; n < body.num_nodes(); ++n) {
        const double x = body.node_position(n).x();
        basis(body.dof(n, c.value), j) = sampler.at(shape, x, place, std::string("'") + c.key + "'");
        if (c.slope_sign != 0)
          basis(body.dof(n, c.slope), j) =
              c.slope_sign * sampler.at(slope, x, place, std::string("the slope d") + c.key + "/dx");
      }
    }
  }
  return basis;
}

}  // namespace kanegen::fem
