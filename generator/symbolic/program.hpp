// SPDX-License-Identifier: GPL-2.0-or-later
// A straight-line program under construction: every intermediate quantity of
// the derivation (a rotation entry, an angular velocity component, ...) gets
// its own symbol, so expressions stay small and the emitted code grows
// polynomially with the number of bodies instead of exponentially.
#pragma once

#include <ginac/ginac.h>

#include <map>
#include <string>
#include <unordered_map>
#include <vector>

#include "symbolic/ex_hash.hpp"

namespace kanegen::symbolic {

class Program {
 public:
  /// Names `value` by a fresh intermediate symbol and returns the symbol.
  /// Numbers, symbols and zero pass through unchanged, which keeps the
  /// sparsity of joint axes and offsets visible to later stages.
  GiNaC::ex define(const GiNaC::ex& value);

  /// The definition of an intermediate, or nullptr for an input symbol.
  const GiNaC::ex* definition(const GiNaC::symbol& s) const;
  /// The same for a symbol held as an expression: no copy of the symbol.
  const GiNaC::ex* definition(const GiNaC::ex& s) const;

  std::size_t size() const { return definitions_.size(); }

 private:
  std::vector<GiNaC::symbol> symbols_;
  // On GiNaC's hash: an ordered map compared symbols through a copy of each
  // (a symbol becomes an ex to compare), a large part of generation's time.
  std::unordered_map<GiNaC::ex, GiNaC::ex, StoredExHash, GiNaC::ex_is_equal> definitions_;
};

}  // namespace kanegen::symbolic
