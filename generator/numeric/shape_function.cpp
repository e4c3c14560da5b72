// SPDX-License-Identifier: GPL-2.0-or-later
#include "numeric/shape_function.hpp"

#include "numeric/dual.hpp"
#include "numeric/time_function.hpp"

namespace kanegen::numeric {

void sample_shape(const std::string& text, const std::map<std::string, double>& parameters,
                  const std::vector<double>& x, std::vector<double>& value, std::vector<double>& slope) {
  const TimeFunction shape(text, parameters, "x");
  value.resize(x.size());
  slope.resize(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) {
    const Dual<double> s = shape(Dual<double>(x[i], 1.0));
    value[i] = s.v;
    slope[i] = s.d;
  }
}

}  // namespace kanegen::numeric
