// SPDX-License-Identifier: GPL-2.0-or-later
#include "codegen/unrolled_ldlt.hpp"

namespace kanegen::codegen {

namespace {

/// The factorization's statements in `text` (with_text) and its count: the
/// count alone, for a solve that is compared but not printed, skips the text
/// (n^3 / 6 strings at n = 100).
UnrolledLdlt factor(const std::vector<bool>& nonzero_m, const std::vector<int>& solved,
                    const ScalarType& scalar, bool with_text) {
  const std::string real = std::string("  const ") + scalar.name() + " ";
  const int n = static_cast<int>(solved.size());
  auto u = [&](int i) { return "udot[" + std::to_string(solved[i]) + "]"; };
  std::vector<bool> nz(nonzero_m);  // structure of L, lower triangle, row-major
  auto m = [](int i, int j) { return "m" + std::to_string(i) + "_" + std::to_string(j); };
  auto l = [](int i, int j) { return "l" + std::to_string(i) + "_" + std::to_string(j); };
  auto d = [](int j) { return "d" + std::to_string(j); };
  auto ld = [](int j, int k) { return "ld" + std::to_string(j) + "_" + std::to_string(k); };
  std::string s = with_text ? "  // LDL^T of M, unrolled; d<j> are the pivots.\n" : "";
  long ops = 0;
  for (int j = 0; j < n; ++j) {
    std::string pivot = m(j, j);
    for (int k = 0; k < j; ++k)
      if (nz[j * n + k]) {
        if (with_text) {
          s += real + ld(j, k) + " = " + l(j, k) + "*" + d(k) + ";\n";
          pivot += " - " + l(j, k) + "*" + ld(j, k);
        }
        ops += 3;
      }
    if (with_text) {
      s += real + d(j) + " = " + pivot + ";\n";
      s += "  if (!(" + d(j) + " > " + scalar.literal(0.0) + ")) return " + std::to_string(j + 1) + ";\n";
      s += real + "inv_" + d(j) + " = " + scalar.literal(1.0) + "/" + d(j) + ";\n";
    }
    ops += 1;
    for (int i = j + 1; i < n; ++i) {
      bool any = nonzero_m[i * n + j];
      std::string entry = any && with_text ? m(i, j) : "";
      for (int k = 0; k < j; ++k)
        if (nz[i * n + k] && nz[j * n + k]) {
          if (with_text) entry += (entry.empty() ? "-" : " - ") + l(i, k) + "*" + ld(j, k);
          any = true;
          ops += 2;
        }
      if (!any) continue;
      nz[i * n + j] = true;
      if (with_text) s += real + l(i, j) + " = (" + entry + ")*inv_" + d(j) + ";\n";
      ops += 1;
    }
  }
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < i; ++k)
      if (nz[i * n + k]) {
        if (with_text) s += "  " + u(i) + " -= " + l(i, k) + "*" + u(k) + ";\n";
        ops += 2;
      }
  for (int i = 0; i < n && with_text; ++i) s += "  " + u(i) + " *= inv_" + d(i) + ";\n";
  ops += n;
  for (int i = n - 1; i >= 0; --i)
    for (int k = i + 1; k < n; ++k)
      if (nz[k * n + i]) {
        if (with_text) s += "  " + u(i) + " -= " + l(k, i) + "*" + u(k) + ";\n";
        ops += 2;
      }
  return {s, ops};
}

}  // namespace

UnrolledLdlt unrolled_ldlt(const std::vector<bool>& nonzero_m, const std::vector<int>& solved,
                           const ScalarType& scalar) {
  return factor(nonzero_m, solved, scalar, true);
}

long unrolled_ldlt_operations(const std::vector<bool>& nonzero_m, const std::vector<int>& solved) {
  return factor(nonzero_m, solved, ScalarType(), false).operations;
}

}  // namespace kanegen::codegen
