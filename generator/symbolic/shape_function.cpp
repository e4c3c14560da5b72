// SPDX-License-Identifier: GPL-2.0-or-later
#include "symbolic/shape_function.hpp"

#include <ginac/ginac.h>

#include <cmath>

namespace kanegen::symbolic {

namespace {

double at(const GiNaC::ex& e, const GiNaC::symbol& x, double where) {
  try {
    const GiNaC::ex v = GiNaC::evalf(e.subs(x == GiNaC::numeric(where)));
    if (GiNaC::is_a<GiNaC::numeric>(v) && GiNaC::ex_to<GiNaC::numeric>(v).is_real())
      return GiNaC::ex_to<GiNaC::numeric>(v).to_double();
  } catch (const std::exception&) {
    // A pole (1/x, log(x) at 0): not finite, for the caller to report.
  }
  return NAN;
}

}  // namespace

void sample_shape(const std::string& text, const std::map<std::string, double>& parameters,
                  const std::vector<double>& x, std::vector<double>& value, std::vector<double>& slope) {
  const GiNaC::symbol coordinate("x");
  GiNaC::symtab table;
  for (const auto& [name, v] : parameters) table[name] = GiNaC::numeric(v);
  table["x"] = coordinate;
  table["pi"] = GiNaC::Pi;
  GiNaC::parser reader(table, /*strict=*/true);
  const GiNaC::ex shape = reader(text);
  const GiNaC::ex derivative = shape.diff(coordinate);
  value.resize(x.size());
  slope.resize(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) {
    value[i] = at(shape, coordinate, x[i]);
    slope[i] = at(derivative, coordinate, x[i]);
  }
}

}  // namespace kanegen::symbolic
