// SPDX-License-Identifier: GPL-2.0-or-later
// The saddle-point solve [M C^T; C 0][udot; lambda] = [b; g] of a model with
// closed loops, as an LDL^T unrolled for the structure of M and C known at
// generation time, in an elimination order that keeps the fill small.
#pragma once

#include <string>
#include <vector>

#include "codegen/scalar_type.hpp"

namespace kanegen::codegen {

/// The structure of the saddle-point matrix: ns speeds solved for, nc loop
/// equations; nonzero_m (ns*ns, row-major, symmetric) and nonzero_c (nc*ns)
/// mark the entries that are not zero by structure.
struct SaddleStructure {
  int ns = 0, nc = 0;
  std::vector<bool> nonzero_m, nonzero_c;
};

/// The order in which the unknowns are eliminated: node v < ns is speed v,
/// v >= ns is loop equation v - ns. Every speed comes before every loop
/// equation (M is positive definite, so its pivots need no pivoting and the
/// loop equations' block is then -C M^-1 C^T); within each group the one
/// whose elimination adds the fewest new entries (then the fewest
/// neighbours, then the lowest index) goes first: for a tree's M that is
/// leaves first, without fill.
std::vector<int> saddle_elimination_order(const SaddleStructure& s);

struct UnrolledSaddle {
  std::string text;     ///< statements, indented by two spaces
  long operations = 0;  ///< additions, multiplications and divisions
};

/// The solve as statements. On entry: the locals m<i>_<j> (i >= j) and
/// c<r>_<i> for the entries marked nonzero, and z[N] (N = ns + nc) holding
/// the right-hand side in elimination order: z[position[v]] with position
/// the inverse of saddle_elimination_order. On exit z holds udot and
/// lambda at the same places. Returns k from the kernel for a non-positive
/// k-th pivot of M (k counts the speeds solved for), -k when loop equation
/// k's pivot of C M^-1 C^T is below 1e-6 of that matrix's largest diagonal
/// entry, as templates/solve_saddle.hpp does.
UnrolledSaddle unrolled_saddle(const SaddleStructure& s, const std::vector<int>& order,
                               const ScalarType& scalar);

/// Operations of templates/solve_saddle.hpp for these sizes (dense in everything).
long dense_saddle_operations(int ns, int nc);

}  // namespace kanegen::codegen
