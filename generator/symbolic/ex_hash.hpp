// SPDX-License-Identifier: GPL-2.0-or-later
// The hash for unordered maps keyed on GiNaC expressions.
#pragma once

#include <ginac/ginac.h>

#include <cstddef>

namespace kanegen::symbolic {

/// GiNaC's own hash, as std::hash<GiNaC::ex> gives it, but not noexcept:
/// that makes libstdc++ keep each key's hash in its map node, so that a
/// lookup compares stored hashes instead of reaching into the expression of
/// every entry in its bucket (a cache miss each, in maps of 10^5 entries).
struct StoredExHash {
  std::size_t operator()(const GiNaC::ex& e) const { return e.gethash(); }
};

}  // namespace kanegen::symbolic
