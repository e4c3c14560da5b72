// SPDX-License-Identifier: GPL-2.0-or-later
// The elimination order of the unrolled saddle-point solve: on a tree's M it
// adds no entry to L (leaves first), and the loop equations fill only what
// C M^-1 C^T needs. The numbers of every loop model are in tests/loops.
#include <catch2/catch.hpp>
#include <string>
#include <vector>

#include "codegen/unrolled_saddle.hpp"

using kanegen::codegen::SaddleStructure;

namespace {

/// A root (0), two children (1, 2) and a grandchild under each (3 under 1, 4 under 2).
SaddleStructure branched_tree(int nc) {
  const int parent[5] = {-1, 0, 0, 1, 2};
  SaddleStructure s{5, nc, std::vector<bool>(25, false), std::vector<bool>(nc * 5, false)};
  for (int i = 0; i < 5; ++i)
    for (int a = i; a >= 0; a = parent[a]) s.nonzero_m[i * 5 + a] = s.nonzero_m[a * 5 + i] = true;
  return s;
}

int count(const std::string& text, const std::string& what) {
  int n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

}  // namespace

TEST_CASE("the saddle-point LDL^T adds no entry to a tree's M and fills only C M^-1 C^T",
          "[codegen][saddle]") {
  const kanegen::codegen::ScalarType scalar;
  SaddleStructure tree = branched_tree(1);
  tree.nonzero_c[0 * 5 + 3] = tree.nonzero_c[0 * 5 + 4] = true;  // a loop between the two grandchildren
  const std::vector<int> order = kanegen::codegen::saddle_elimination_order(tree);
  REQUIRE(order.size() == 6u);
  CHECK(order.back() == 5);  // the loop equation last
  // The root after both its children: the natural (root-first) order would fill in the branches.
  int root = -1, child1 = -1, child2 = -1;
  for (int k = 0; k < 6; ++k) {
    if (order[k] == 0) root = k;
    if (order[k] == 1) child1 = k;
    if (order[k] == 2) child2 = k;
  }
  CHECK(root > child1);
  CHECK(root > child2);
  const kanegen::codegen::UnrolledSaddle solve = kanegen::codegen::unrolled_saddle(tree, order, scalar);
  // L: the 6 entries of M below the diagonal, the 2 of C and a single new
  // one (the children first, then the grandchildren: the loop equation then
  // meets only the root), 9; eliminating the root first would fill all 10
  // pairs of speeds and the loop equation's row.
  CHECK(count(solve.text, "const double sld") == 9);
  CHECK(solve.operations < kanegen::codegen::dense_saddle_operations(5, 1));
}
