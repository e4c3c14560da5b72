// SPDX-License-Identifier: GPL-2.0-or-later
// Prints a kernel (a set of assignments `target = node`) of the expression
// graph as straight-line C++: nodes used more than once become `const double` (or float)
// temporaries named by their position, the rest are inlined. The text
// depends only on the graph's canonical structure, so it is byte-identical
// from run to run.
#pragma once

#include <string>
#include <vector>

#include "codegen/expression_graph.hpp"
#include "codegen/scalar_type.hpp"

namespace kanegen::codegen {

struct Assignment {
  std::string target;  ///< e.g. "M[3]"
  int node = -1;
};

/// One printed statement, as kernel_splitter needs it to move statements
/// into functions of their own.
struct Statement {
  int temporary = -1;               ///< the temporary it defines (x<k>), or -1 for an assignment
  std::string target;               ///< an assignment's target, e.g. "udot[3]" or "const double m0_0"
  std::string expression;           ///< the right-hand side
  std::vector<int> temporaries;     ///< the temporaries it reads, ascending, without repeats
  std::vector<std::string> inputs;  ///< the inputs it reads ("q[0]", "p.m1", "t"), without repeats
  long operations = 0;              ///< of its text (what the compiler has to work on)
};

struct PrintedKernel {
  std::string body;     ///< statements, one per line, indented
  long operations = 0;  ///< additions, multiplications, divisions and function calls
  int temporaries = 0;
  std::string temp_prefix;            ///< temporary k is named temp_prefix + k
  std::vector<Statement> statements;  ///< the statements of `body`, in order
};

/// `scalar` is the type of the temporaries and literals and picks the
/// <math.h> functions (sin or sinf).
PrintedKernel print_kernel(const ExpressionGraph& graph, const std::vector<Assignment>& assignments,
                           const ScalarType& scalar, const std::string& indent = "  ",
                           const std::string& temp_prefix = "x");

/// print_kernel's operation count without forming the text: for a kernel
/// that is only compared (the forward dynamics that loses the choice).
long count_operations(const ExpressionGraph& graph, const std::vector<Assignment>& assignments);

/// Shortest decimal text that reads back as the same double, always with a
/// '.' or an exponent so that C++ reads it as a double.
std::string format_double(double v);

}  // namespace kanegen::codegen
