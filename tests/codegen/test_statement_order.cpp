// SPDX-License-Identifier: GPL-2.0-or-later
// The emission order of a kernel's statements (statement_order.*): a valid
// order on random dependency graphs, fewer values live at once where the
// printer's order keeps many, the printer's order kept for a kernel that
// reads what it assigns, and a sum's terms in the order they are ready.
#include <algorithm>
#include <catch2/catch.hpp>
#include <numeric>
#include <random>
#include <string>
#include <vector>

#include "codegen/cpp_printer.hpp"
#include "codegen/expression_graph.hpp"
#include "codegen/statement_order.hpp"
#include "model/load.hpp"
#include "symbolic/program.hpp"
#include "symbolic/variables.hpp"

using namespace kanegen::codegen;

namespace {

/// The most values live at once in `order`: a value is live from its
/// statement to its last reader.
int most_live(const std::vector<OrderedStatement>& statements, const std::vector<int>& order) {
  const int n = static_cast<int>(statements.size());
  std::vector<int> position(n), last_read(n, -1);
  for (int k = 0; k < n; ++k) position[order[k]] = k;
  for (int i = 0; i < n; ++i)
    for (int r : statements[i].reads) last_read[r] = std::max(last_read[r], position[i]);
  int most = 0;
  for (int k = 0; k < n; ++k) {
    int live = 0;
    for (int i = 0; i < n; ++i)
      if (statements[i].defines && position[i] <= k && last_read[i] > k) ++live;
    most = std::max(most, live);
  }
  return most;
}

/// An expression graph with no model symbols in use (its inputs are made by name).
struct Graph {
  kanegen::model::Model model = kanegen::model::load_model(KANEGEN_SOURCE_DIR "/models/double_pendulum.json");
  kanegen::symbolic::Variables vars{model};
  kanegen::symbolic::Program program;
  ExpressionGraph graph{vars, program};
};

std::vector<int> identity_order(int n) {
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  return order;
}

}  // namespace

TEST_CASE("every statement comes once and after the statements it reads", "[order]") {
  std::mt19937 random(7);
  for (int trial = 0; trial < 50; ++trial) {
    const int n = 1 + static_cast<int>(random() % 200);
    std::vector<OrderedStatement> statements(n);
    for (int i = 1; i < n; ++i) {
      const int reads = static_cast<int>(random() % 4);
      for (int k = 0; k < reads; ++k) statements[i].reads.push_back(static_cast<int>(random() % i));
      std::sort(statements[i].reads.begin(), statements[i].reads.end());
      statements[i].reads.erase(std::unique(statements[i].reads.begin(), statements[i].reads.end()),
                                statements[i].reads.end());
    }
    for (int i = 0; i < n; ++i)
      for (int r : statements[i].reads) statements[r].defines = true;
    const std::vector<int> order = shorten_live_ranges(statements);
    REQUIRE(order.size() == statements.size());
    std::vector<int> position(n, -1);
    for (int k = 0; k < n; ++k) {
      REQUIRE(position[order[k]] < 0);
      position[order[k]] = k;
    }
    for (int i = 0; i < n; ++i)
      for (int r : statements[i].reads) CHECK(position[r] < position[i]);
    CHECK(shorten_live_ranges(statements) == order);
  }
}

TEST_CASE("values computed long before their one reader are computed just before it", "[order]") {
  // The printer's order: v0 .. v19, then out_i = f(v_i): 20 values live at
  // once. Placed by the order: each v_i just before its reader.
  const int n = 20;
  std::vector<OrderedStatement> statements(2 * n);
  for (int i = 0; i < n; ++i) {
    statements[i].defines = true;
    statements[n + i].reads = {i};
  }
  CHECK(most_live(statements, identity_order(2 * n)) == n);
  CHECK(most_live(statements, shorten_live_ranges(statements)) == 1);
}

TEST_CASE("a statement that reads a value for the last time comes before one that starts a new value",
          "[order]") {
  // 0 and 1 are values; 2 reads 0 and 1 for the last time; 3 starts a new
  // value read by 4. The printer put 3 first; ending two ranges comes first.
  std::vector<OrderedStatement> statements(5);
  statements[0].defines = statements[1].defines = statements[3].defines = true;
  statements[2].reads = {0, 1};
  statements[4].reads = {3};
  // Printed order 0 1 3 2 4 is what the printer would emit if 3 came first.
  const std::vector<int> order = shorten_live_ranges(statements);
  CHECK(order == std::vector<int>{0, 1, 2, 3, 4});
  CHECK(most_live(statements, order) == 2);
}

TEST_CASE("a kernel that reads what it assigns keeps the printer's order", "[order]") {
  Graph g;
  ExpressionGraph& graph = g.graph;
  const int x = graph.input("x[0]");
  const int y0 = graph.input("y[0]");
  // y[0] = s s + s with s = x + 2 (a temporary); y[1] = 3 y[0] + y[0]^2 reads
  // the y[0] just assigned. Ordered by live ranges, y[1] would come first:
  // it starts no value, where s does.
  const int s = graph.sum({x, graph.constant(2.0)});
  const int first = graph.sum({graph.product({s, s}), s});
  const int second = graph.sum({graph.product({graph.constant(3.0), y0}), graph.product({y0, y0})});
  const PrintedKernel kernel = print_kernel(graph, {{"y[0]", first}, {"y[1]", second}}, ScalarType());
  std::vector<std::string> targets;
  for (const Statement& statement : kernel.statements)
    if (statement.temporary < 0) targets.push_back(statement.target);
  CHECK(targets == std::vector<std::string>{"y[0]", "y[1]"});
}

TEST_CASE("printed statements define each temporary before the statements that read it", "[order]") {
  Graph g;
  ExpressionGraph& graph = g.graph;
  std::vector<int> inputs;
  for (int i = 0; i < 6; ++i) inputs.push_back(graph.input("a[" + std::to_string(i) + "]"));
  std::vector<Assignment> assignments;
  std::vector<int> shared;
  for (int i = 0; i < 6; ++i) shared.push_back(graph.product({inputs[i], inputs[(i + 1) % 6]}));
  for (int i = 0; i < 6; ++i)
    assignments.push_back(
        {"b[" + std::to_string(i) + "]",
         graph.sum({shared[i], shared[(i + 2) % 6], graph.product({shared[i], inputs[i]})})});
  const PrintedKernel kernel = print_kernel(graph, assignments, ScalarType());
  std::vector<bool> defined(kernel.temporaries, false);
  for (const Statement& s : kernel.statements) {
    for (int t : s.temporaries) CHECK(defined[t]);
    if (s.temporary >= 0) defined[s.temporary] = true;
  }
}

TEST_CASE("a sum adds the term that is ready last at its end", "[order]") {
  // z[k] = a[k] + b[k] + c[k] + sin(x) y[k]: the product waits for the
  // library call, the inputs do not. In the graph's canonical order the
  // product would come last in about one sum of four; here in all ten.
  Graph g;
  ExpressionGraph& graph = g.graph;
  const int late = graph.apply(Op::sin, graph.input("x[0]"));
  std::vector<Assignment> assignments;
  for (int k = 0; k < 10; ++k) {
    const std::string i = "[" + std::to_string(k) + "]";
    assignments.push_back(
        {"z" + i, graph.sum({graph.input("a" + i), graph.input("b" + i), graph.input("c" + i),
                             graph.product({late, graph.input("y" + i)})})});
  }
  const PrintedKernel kernel = print_kernel(graph, assignments, ScalarType());
  int sums = 0;
  for (const Statement& s : kernel.statements) {
    if (s.temporary >= 0) continue;
    INFO(s.target << " = " << s.expression);
    const std::size_t last_term = s.expression.find_last_of("+-");
    REQUIRE(last_term != std::string::npos);
    CHECK(s.expression.find("y[", last_term) != std::string::npos);
    ++sums;
  }
  CHECK(sums == 10);
}

TEST_CASE("minus a sum is printed as the sum with its signs flipped", "[order]") {
  // angle = -(0.4 - q[0]) with its sin and cos: printed -(0.4 - q[0]),
  // g++ folds cos(-x) into cos(0.4 - q[0]) but keeps sin's argument, and the
  // two calls no longer become one sincos. Flipping the signs is exact.
  Graph g;
  ExpressionGraph& graph = g.graph;
  const int q = graph.input("q[0]"), y = graph.input("y[0]");
  const int angle = graph.product(
      {graph.constant(-1), graph.sum({graph.constant(0.4), graph.product({graph.constant(-1), q})})});
  const int nested = graph.product(
      {graph.constant(-1),
       graph.sum({y, graph.sum({graph.constant(0.5), graph.product({graph.constant(-2), q})})})});
  const std::vector<Assignment> assignments{
      {"s", graph.apply(Op::sin, angle)}, {"c", graph.apply(Op::cos, angle)}, {"z", nested}};
  const PrintedKernel kernel = print_kernel(graph, assignments, ScalarType());
  int angles = 0;
  for (const Statement& s : kernel.statements) {
    INFO(s.target << " = " << s.expression);
    CHECK(s.expression.find("-(") == std::string::npos);
    CHECK(s.expression.find("--") == std::string::npos);
    if (s.temporary >= 0) {
      CHECK(s.expression == "-0.4 + q[0]");
      ++angles;
    }
    if (s.target == "z") CHECK(s.expression == "-y[0] - 0.5 + 2.0*q[0]");
  }
  CHECK(angles == 1);
}

TEST_CASE("terms of a sum with the same coefficient share one multiplication", "[order]") {
  // z = 0.3 a - 0.3 b + 0.7 c + 0.7 d + 0.5 e + 2 y: 0.3 and 0.7 are each
  // printed once, as 0.3*(a - b) and 0.7*(c + d); 0.5 e alone keeps its own.
  Graph g;
  ExpressionGraph& graph = g.graph;
  auto term = [&](double c, const char* name) {
    return graph.product({graph.constant(c), graph.input(name)});
  };
  const int z = graph.sum({term(0.3, "a[0]"), term(-0.3, "b[0]"), term(0.7, "c[0]"), term(0.7, "d[0]"),
                           term(0.5, "e[0]"),
                           graph.product({graph.constant(2), graph.input("y[0]"), graph.input("a[0]")})});
  const PrintedKernel kernel = print_kernel(graph, {{"z", z}}, ScalarType());
  REQUIRE(kernel.statements.size() == 1);
  const std::string& text = kernel.statements[0].expression;
  INFO("z = " << text);
  CHECK((text.find("+ 0.3*(a[0] - b[0])") != std::string::npos || text.rfind("0.3*(a[0] - b[0])", 0) == 0 ||
         text.find("- 0.3*(b[0] - a[0])") != std::string::npos));
  CHECK((text.find("0.7*(c[0] + d[0])") != std::string::npos ||
         text.find("0.7*(d[0] + c[0])") != std::string::npos));
  CHECK(text.find("0.5*e[0]") != std::string::npos);
  CHECK(text.find("2.0*") != std::string::npos);
  for (const char* c : {"0.3", "0.7", "0.5", "2.0"}) {
    const std::size_t first = text.find(c);
    CHECK(text.find(c, first + 1) == std::string::npos);
  }
  // Counted as printed: 2 + 2 for the shared ones, 1 for 0.5 e, 2 for 2 y a,
  // 3 to add the four; the count without printing agrees.
  CHECK(kernel.statements[0].operations == 10);
  CHECK(count_operations(graph, {{"z", z}}) == 10);
}
