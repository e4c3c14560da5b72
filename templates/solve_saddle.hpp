// SPDX-License-Identifier: MIT
// This file is kanegen's output: you may use, copy, modify and distribute it under any terms you choose (docs/licensing.md).
// The saddle-point solve of a model with closed loops, copied verbatim (the
// part between the markers) into every generated model that has loops, and
// compiled on its own by tests/codegen. The range-space method:
// M = L L^T (Cholesky), Y = L^-1 C^T, S = Y^T Y = C M^-1 C^T,
// S lambda = g - Y^T L^-1 b, then udot = L^-T (L^-1 b + Y lambda). Where
// loop equations become dependent (a parallelogram's cranks in line, a dead
// point, or a loop that repeats a constraint) S loses rank; that is
// reported, not smoothed over: near such a point the loop forces grow
// without bound and the motion may leave its branch. Loops over the fixed
// sizes NS (speeds solved for) and NC (loop equations), no allocation.
#pragma once

#include <math.h>  // the emitted code uses nothing beyond it (freestanding)

namespace kanegen_templates {
// kanegen:embed-begin
// M: NS*NS (overwritten by L), b: NS (the right-hand side; udot on return),
// C: NC*NS (overwritten by Y^T), g: NC. Returns 0, k > 0 for a non-positive
// k-th pivot of M, -k when the k-th loop equation is (nearly) a combination
// of the earlier ones.
template <int NS, int NC>
int solve_saddle(double* M, double* b, double* C, const double* g, double* lambda) {
  for (int j = 0; j < NS; ++j) {
    double s = M[j * NS + j];
    for (int k = 0; k < j; ++k) s -= M[j * NS + k] * M[j * NS + k];
    if (!(s > 0.0)) return j + 1;
    const double l = sqrt(s);
    M[j * NS + j] = l;
    for (int i = j + 1; i < NS; ++i) {
      double v = M[i * NS + j];
      for (int k = 0; k < j; ++k) v -= M[i * NS + k] * M[j * NS + k];
      M[i * NS + j] = v / l;
    }
  }
  const auto forward = [M](double* x) {
    for (int i = 0; i < NS; ++i) {
      for (int k = 0; k < i; ++k) x[i] -= M[i * NS + k] * x[k];
      x[i] /= M[i * NS + i];
    }
  };
  forward(b);
  for (int c = 0; c < NC; ++c) forward(C + c * NS);
  double S[NC * NC];
  for (int c = 0; c < NC; ++c) {
    lambda[c] = g[c];
    for (int i = 0; i < NS; ++i) lambda[c] -= C[c * NS + i] * b[i];
    for (int d = 0; d <= c; ++d) {
      double v = 0.0;
      for (int i = 0; i < NS; ++i) v += C[c * NS + i] * C[d * NS + i];
      S[c * NC + d] = v;
    }
  }
  // A pivot small against the largest diagonal entry: a row that is
  // (nearly) a combination of the others, or one whose Jacobian vanishes
  // (a parallelogram's cranks in line).
  double largest = 0.0;
  for (int j = 0; j < NC; ++j)
    if (S[j * NC + j] > largest) largest = S[j * NC + j];
  for (int j = 0; j < NC; ++j) {
    double s = S[j * NC + j];
    for (int k = 0; k < j; ++k) s -= S[j * NC + k] * S[j * NC + k];
    if (!(s > 1e-6 * largest)) return -(j + 1);
    const double l = sqrt(s);
    S[j * NC + j] = l;
    for (int i = j + 1; i < NC; ++i) {
      double v = S[i * NC + j];
      for (int k = 0; k < j; ++k) v -= S[i * NC + k] * S[j * NC + k];
      S[i * NC + j] = v / l;
    }
  }
  for (int i = 0; i < NC; ++i) {
    for (int k = 0; k < i; ++k) lambda[i] -= S[i * NC + k] * lambda[k];
    lambda[i] /= S[i * NC + i];
  }
  for (int i = NC - 1; i >= 0; --i) {
    for (int k = i + 1; k < NC; ++k) lambda[i] -= S[k * NC + i] * lambda[k];
    lambda[i] /= S[i * NC + i];
  }
  for (int i = 0; i < NS; ++i)
    for (int c = 0; c < NC; ++c) b[i] += C[c * NS + i] * lambda[c];
  for (int i = NS - 1; i >= 0; --i) {
    for (int k = i + 1; k < NS; ++k) b[i] -= M[k * NS + i] * b[k];
    b[i] /= M[i * NS + i];
  }
  return 0;
}
// kanegen:embed-end
}  // namespace kanegen_templates
