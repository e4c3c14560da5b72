// SPDX-License-Identifier: GPL-2.0-or-later
#include "numeric/shape_function.hpp"

#include <cmath>

#include "numeric/dual.hpp"
#include "numeric/time_function.hpp"

namespace kanegen::numeric {

void sample_shape(const std::string& text, const std::map<std::string, double>& parameters,
                  const std::vector<double>& x, std::vector<double>& value, std::vector<double>& slope) {
  const TimeFunction shape(text, parameters, "x");
  value.resize(x.size());
  slope.resize(x.size());
  const double middle = x.empty() ? 0.0 : (x.front() + x.back()) / 2;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const Dual<double> s = shape(Dual<double>(x[i], 1.0));
    value[i] = s.v;
    slope[i] = s.d;
    // A slope the chain rule cannot give at an end (x sqrt(x) at 0: 1*0 + 0*inf)
    // is its one-sided limit, as GiNaC's simplified derivative gives it: the
    // slope a hair inward (not a subnormal step, which x/L would round to 0).
    if (!std::isfinite(slope[i])) {
      const double inward = x[i] == 0.0 ? middle * 1e-300 : std::nextafter(x[i], middle);
      slope[i] = shape(Dual<double>(inward, 1.0)).d;
    }
  }
}

}  // namespace kanegen::numeric
