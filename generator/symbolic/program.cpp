// SPDX-License-Identifier: GPL-2.0-or-later
#include "symbolic/program.hpp"

namespace kanegen::symbolic {

GiNaC::ex Program::define(const GiNaC::ex& value) {
  if (GiNaC::is_a<GiNaC::numeric>(value) || GiNaC::is_a<GiNaC::symbol>(value) ||
      GiNaC::is_a<GiNaC::constant>(value)) {
    return value;
  }
  // A negated symbol is as cheap to use as the symbol itself.
  if (GiNaC::is_a<GiNaC::mul>(value) && value.nops() == 2 && GiNaC::is_a<GiNaC::symbol>(value.op(0)) &&
      value.op(1).is_equal(-1)) {
    return value;
  }
  GiNaC::symbol s("w" + std::to_string(symbols_.size()));
  symbols_.push_back(s);
  definitions_.emplace(s, value);
  return s;
}

const GiNaC::ex* Program::definition(const GiNaC::symbol& s) const { return definition(GiNaC::ex(s)); }

const GiNaC::ex* Program::definition(const GiNaC::ex& s) const {
  auto it = definitions_.find(s);
  return it == definitions_.end() ? nullptr : &it->second;
}

}  // namespace kanegen::symbolic
