// SPDX-License-Identifier: GPL-2.0-or-later
// The bodies each coordinate moves, as the generated metadata lists them for
// the run-time message of a mass matrix that is not positive definite; the
// expected lists are read off the model files by hand.
#include <catch2/catch.hpp>
#include <string>
#include <vector>

#include "flexible_arm2.hpp"
#include "four_bar.hpp"

namespace {

template <int NQ>
std::vector<std::string> moved(const int (&first)[NQ + 1], const char* const* bodies, int i) {
  return std::vector<std::string>(bodies + first[i], bodies + first[i + 1]);
}

using Names = std::vector<std::string>;

}  // namespace

TEST_CASE("each coordinate names its joint and the bodies it moves", "[kernels]") {
  SECTION("flexible_arm2: a joint moves its child's subtree, an elastic coordinate its body's") {
    namespace m = kanegen_models::flexible_arm2;
    // shoulder: ground -> link1 (flexible), motor fixed on link1's tip, elbow: motor -> link2.
    CHECK(std::string(m::coordinate_joints[0]) == "shoulder");
    CHECK(moved<m::NQ>(m::moved_bodies_first, m::moved_bodies, 0) == Names{"link1", "motor", "link2"});
    CHECK(std::string(m::coordinate_joints[1]) == "elbow");
    CHECK(moved<m::NQ>(m::moved_bodies_first, m::moved_bodies, 1) == Names{"link2"});
    for (int i = 2; i < m::NQ; ++i) {
      INFO(m::coordinate_names[i]);
      CHECK(std::string(m::coordinate_joints[i]).empty());
      const Names expected = std::string(m::coordinate_names[i]).rfind("link1.", 0) == 0
                                 ? Names{"link1", "motor", "link2"}
                                 : Names{"link2"};
      CHECK(moved<m::NQ>(m::moved_bodies_first, m::moved_bodies, i) == expected);
    }
  }
  SECTION("four_bar: the loop-closing joint does not join the tree") {
    namespace m = kanegen_models::four_bar;
    CHECK(moved<m::NQ>(m::moved_bodies_first, m::moved_bodies, 0) == Names{"crank", "coupler"});
    CHECK(moved<m::NQ>(m::moved_bodies_first, m::moved_bodies, 1) == Names{"coupler"});
    CHECK(moved<m::NQ>(m::moved_bodies_first, m::moved_bodies, 2) == Names{"rocker"});
  }
}
