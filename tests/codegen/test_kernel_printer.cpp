// SPDX-License-Identifier: GPL-2.0-or-later
// The kernel table and its printer: every piece of a kernel's code made from
// its one table entry.
#include <catch2/catch.hpp>
#include <set>
#include <sstream>
#include <string>

#include "codegen/kernel_printer.hpp"
#include "codegen/kernel_table.hpp"

using namespace kanegen::codegen;

namespace {

std::size_t longest_line(const std::string& text) {
  std::istringstream in(text);
  std::size_t longest = 0;
  for (std::string line; std::getline(in, line);) longest = std::max(longest, line.size());
  return longest;
}

}  // namespace

TEST_CASE("every table entry has a distinct name, a known return type and named arguments", "[kernels]") {
  std::set<std::string> names;
  for (const KernelSignature& s : kernel_table()) {
    CHECK(names.insert(s.name).second);
    CHECK(std::set<std::string>{"void", "int", "double", "bool"}.count(s.returns) == 1);
    CHECK(&signature(s.kernel) == &s);
    for (const KernelArgument& a : arguments(s)) {
      CHECK_FALSE(a.type.empty());
      CHECK_FALSE(a.name.empty());
    }
  }
}

// The table is read from the runtime's spec (kernels.def): the printed
// signatures are those the generated code always had, and each kernel the
// runtime binds is bound in the spec.
TEST_CASE("the kernel table is the runtime's spec, arguments typed by role", "[kernels]") {
  const auto joined = [](Kernel k) {
    std::string text;
    for (const KernelArgument& a : arguments(signature(k)))
      text += (text.empty() ? "" : ", ") + a.type + " " + a.name;
    return text;
  };
  CHECK(joined(Kernel::set_parameter) == "Params& p, const char* name, double value");
  CHECK(joined(Kernel::get_parameter) == "const Params& p, int i");
  CHECK(joined(Kernel::coordinate_rates) == "const double* q, const double* u, double* qdot");
  CHECK(
      joined(Kernel::linearize) ==
      "const Params& p, double t, const double* q, const double* u, const double* tau, double* A, double* B");
  CHECK(kernel_table().size() == kanegen::runtime::kernel_count);
  CHECK_FALSE(signature(Kernel::generalized_momentum).in_runtime_table);
  CHECK(signature(Kernel::forcing_jacobian).presence == Presence::with_jacobians);
  CHECK(present(Presence::with_loops_and_jacobians, true, true));
  CHECK_FALSE(present(Presence::with_loops_and_jacobians, false, true));
}

TEST_CASE("a prototype breaks before the argument that would pass the column limit", "[kernels]") {
  const std::string text = prototype("int forward_dynamics",
                                     {"const Params& p", "double t", "const double* q", "const double* u",
                                      "const double* tau", "double* udot"},
                                     ";");
  CHECK(
      text ==
      "int forward_dynamics(const Params& p, double t, const double* q, const double* u, const double* tau,\n"
      "                     double* udot);");
  CHECK(prototype("void f", {"int a"}, " {") == "void f(int a) {");
  CHECK(prototype("void f", {}, ";") == "void f();");
}

TEST_CASE("a definition marks exactly the arguments its body never names", "[kernels]") {
  const KernelSignature& s = signature(Kernel::forcing);
  const std::string text = definition(s, "  f[0] = tau[0] - p.k*q[0];\n");
  CHECK(text.find("[[maybe_unused]] double t") != std::string::npos);
  CHECK(text.find("[[maybe_unused]] const double* u") != std::string::npos);
  CHECK(text.find("[[maybe_unused]] const Params& p") == std::string::npos);
  CHECK(text.find("[[maybe_unused]] const double* tau") == std::string::npos);
  CHECK(longest_line(text) <= 110);
}

TEST_CASE("identifiers are matched whole", "[kernels]") {
  CHECK(names_identifier("x = t;", "t"));
  CHECK_FALSE(names_identifier("const double t12 = 1;", "t"));
  CHECK_FALSE(names_identifier("udot[0] = 1;", "u"));
  CHECK(names_identifier("y = u[0];", "u"));
}

TEST_CASE("the System forwarder and the table entry call the kernel with the same arguments", "[kernels]") {
  const KernelSignature& s = signature(Kernel::forward_dynamics);
  const std::string forwarder = system_forwarder(s, "m");
  CHECK(forwarder.find("return ::kanegen_models::m::forward_dynamics(p, t, q, u, tau, udot);") !=
        std::string::npos);
  const std::string entry = table_entry(s);
  CHECK(entry.find("  table.forward_dynamics = [](const void* p, double t,") == 0);
  CHECK(entry.find("return forward_dynamics(*static_cast<const Params*>(p), t, q, u, tau, udot);") !=
        std::string::npos);
  CHECK(table_entry(signature(Kernel::set_parameter)).find("*static_cast<Params*>(p)") != std::string::npos);
  CHECK(longest_line(forwarder) <= 110);
  CHECK(longest_line(entry) <= 110);
}

// The saddle-point solve is written once, for double; a float model gets it
// through in_code, which must leave no double behind (tests/embedded compiles
// the result with -Wdouble-promotion) and touch nothing else.
TEST_CASE("in_code writes double code in float: the type, floating literals and <math.h> calls",
          "[kernels]") {
  const std::string code =
      "  double s = M[j * NS + 1];  // sqrt(1e-6) double\n"
      "  if (!(s > 1e-6 * largest) || s < 0.0) return -(j + 1);\n"
      "  const double l = sqrt(s) + fabs(2.5e+3), my_sqrt = doubled;\n";
  CHECK(ScalarType(Precision::single_precision).in_code(code) ==
        "  float s = M[j * NS + 1];  // sqrt(1e-6) double\n"
        "  if (!(s > 1e-06f * largest) || s < 0.0f) return -(j + 1);\n"
        "  const float l = sqrtf(s) + fabsf(2.5e+03f), my_sqrt = doubled;\n");
  CHECK(ScalarType().in_code(code) == code);
  // What it would get wrong, it refuses, naming the line.
  const ScalarType single(Precision::single_precision);
  for (const char* unhandled :
       {"x = .5;", "x = 0x1p3;", "x = std::sqrt(y);", "x = M_PI;", "s = \"1.0\";", "c = '1';", "/* 1.0 */"})
    CHECK_THROWS_WITH(single.in_code(std::string("a = 1.0;\n") + unhandled), Catch::Contains("on line 2"));
  CHECK_NOTHROW(single.in_code("x1 = a.b + v0.x;  // \"quoted\" in a comment, std::sqrt, 0x1, .5\n"));
}
