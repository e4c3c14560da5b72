// SPDX-License-Identifier: GPL-2.0-or-later
#include "codegen/unrolled_saddle.hpp"

#include <algorithm>

namespace kanegen::codegen {
namespace {

std::string str(int i) { return std::to_string(i); }

/// Greedy minimum fill among the alive nodes in [first, last), eliminating
/// each from `adjacent` (fill edges added) and appending it to `order`.
void eliminate_group(std::vector<std::vector<char>>& adjacent, std::vector<char>& alive, int first, int last,
                     std::vector<int>& order) {
  const int n = static_cast<int>(alive.size());
  for (int step = first; step < last; ++step) {
    int best = -1;
    long best_fill = 0, best_degree = 0;
    std::vector<int> neighbours;
    for (int v = first; v < last; ++v) {
      if (!alive[v]) continue;
      neighbours.clear();
      for (int w = 0; w < n; ++w)
        if (alive[w] && w != v && adjacent[v][w]) neighbours.push_back(w);
      long fill = 0;
      for (std::size_t a = 0; a < neighbours.size(); ++a)
        for (std::size_t b = a + 1; b < neighbours.size(); ++b)
          if (!adjacent[neighbours[a]][neighbours[b]]) ++fill;
      const long degree = static_cast<long>(neighbours.size());
      if (best < 0 || fill < best_fill || (fill == best_fill && degree < best_degree)) {
        best = v;
        best_fill = fill;
        best_degree = degree;
      }
    }
    neighbours.clear();
    for (int w = 0; w < n; ++w)
      if (alive[w] && w != best && adjacent[best][w]) neighbours.push_back(w);
    for (int a : neighbours)
      for (int b : neighbours)
        if (a != b) adjacent[a][b] = 1;
    alive[best] = 0;
    order.push_back(best);
  }
}

}  // namespace

std::vector<int> saddle_elimination_order(const SaddleStructure& s) {
  const int n = s.ns + s.nc;
  std::vector<std::vector<char>> adjacent(n, std::vector<char>(n, 0));
  for (int i = 0; i < s.ns; ++i)
    for (int j = 0; j < s.ns; ++j)
      if (i != j && (s.nonzero_m[i * s.ns + j] || s.nonzero_m[j * s.ns + i])) adjacent[i][j] = 1;
  for (int r = 0; r < s.nc; ++r)
    for (int i = 0; i < s.ns; ++i)
      if (s.nonzero_c[r * s.ns + i]) adjacent[s.ns + r][i] = adjacent[i][s.ns + r] = 1;
  std::vector<char> alive(n, 1);
  std::vector<int> order;
  eliminate_group(adjacent, alive, 0, s.ns, order);
  eliminate_group(adjacent, alive, s.ns, n, order);
  return order;
}

UnrolledSaddle unrolled_saddle(const SaddleStructure& s, const std::vector<int>& order,
                               const ScalarType& scalar) {
  const int ns = s.ns, n = s.ns + s.nc;
  const std::string real = std::string("  const ") + scalar.name() + " ";
  auto l = [](int i, int j) { return "sl" + str(i) + "_" + str(j); };
  auto ld = [](int i, int j) { return "sld" + str(i) + "_" + str(j); };
  auto d = [](int j) { return "sd" + str(j); };  // sld<i>_<j> = sl<i>_<j> * sd<j>
  auto ss = [](int j) { return "ss" + str(j); };
  auto z = [](int i) { return "z[" + str(i) + "]"; };
  // The name of entry (a, b) of the permuted matrix (a > b), or "" if zero by structure.
  auto entry = [&](int a, int b) -> std::string {
    const int v = order[a], w = order[b];
    if (v >= ns && w >= ns) return "";
    if (v < ns && w < ns) {
      const int i = std::max(v, w), j = std::min(v, w);
      return s.nonzero_m[i * ns + j] ? "m" + str(i) + "_" + str(j) : "";
    }
    const int r = std::max(v, w) - ns, i = std::min(v, w);
    return s.nonzero_c[r * ns + i] ? "c" + str(r) + "_" + str(i) : "";
  };
  std::vector<bool> nz(static_cast<std::size_t>(n) * n, false);  // structure of L (a > b), row-major
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < a; ++b) nz[a * n + b] = !entry(a, b).empty();
  std::string t = "  // LDL^T of [M C^T; C 0], unrolled in the elimination order; sd<j> are the pivots.\n";
  long ops = 0;
  for (int j = 0; j < n; ++j) {
    if (j == ns) {
      // Every speed eliminated: ss<a> is the diagonal of C M^-1 C^T, the scale of its pivots.
      t += "  " + std::string(scalar.name()) + " s_largest = " + scalar.literal(0.0) + ";\n";
      for (int a = ns; a < n; ++a) {
        std::string sum;
        for (int k = 0; k < ns; ++k)
          if (nz[a * n + k]) {
            sum += (sum.empty() ? "" : " + ") + l(a, k) + "*" + ld(a, k);
            ops += 2;
          }
        t += real + ss(a) + " = " + (sum.empty() ? scalar.literal(0.0) : sum) + ";\n";
        t += "  if (" + ss(a) + " > s_largest) s_largest = " + ss(a) + ";\n";
      }
    }
    std::string pivot;
    if (j < ns) {
      const int i = order[j];
      pivot = s.nonzero_m[i * ns + i] ? "m" + str(i) + "_" + str(i) : scalar.literal(0.0);
    } else {
      pivot = "-" + ss(j);
      ops += 1;
    }
    for (int k = j < ns ? 0 : ns; k < j; ++k)
      if (nz[j * n + k]) {
        pivot += " - " + l(j, k) + "*" + ld(j, k);
        ops += 2;
      }
    t += real + d(j) + " = " + pivot + ";\n";
    if (j < ns)
      t += "  if (!(" + d(j) + " > " + scalar.literal(0.0) + ")) return " + str(order[j] + 1) + ";\n";
    else
      t += "  if (!(-" + d(j) + " > " + scalar.literal(1e-6) + " * s_largest)) return -" +
           str(order[j] - ns + 1) + ";\n";
    t += real + "inv_" + d(j) + " = " + scalar.literal(1.0) + "/" + d(j) + ";\n";
    ops += 1;
    for (int i = j + 1; i < n; ++i) {
      std::string value = entry(i, j);
      for (int k = 0; k < j; ++k)
        if (nz[i * n + k] && nz[j * n + k]) {
          value += (value.empty() ? "-" : " - ") + l(i, k) + "*" + ld(j, k);
          ops += 2;
        }
      if (value.empty()) continue;
      nz[i * n + j] = true;
      // sld<i>_<j> = l_ij d_j, the numerator: kept for the later pivots and entries.
      t += real + ld(i, j) + " = " + value + ";\n";
      t += real + l(i, j) + " = " + ld(i, j) + "*inv_" + d(j) + ";\n";
      ops += 1;
    }
  }
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < i; ++k)
      if (nz[i * n + k]) {
        t += "  " + z(i) + " -= " + l(i, k) + "*" + z(k) + ";\n";
        ops += 2;
      }
  for (int i = 0; i < n; ++i) t += "  " + z(i) + " *= inv_" + d(i) + ";\n";
  ops += n;
  for (int i = n - 1; i >= 0; --i)
    for (int k = i + 1; k < n; ++k)
      if (nz[k * n + i]) {
        t += "  " + z(i) + " -= " + l(k, i) + "*" + z(k) + ";\n";
        ops += 2;
      }
  return {t, ops};
}

long dense_saddle_operations(int ns, int nc) {
  const auto cholesky = [](long n) {
    long ops = 0;
    for (long j = 0; j < n; ++j) ops += 2 * j + 1 + (n - j - 1) * (2 * j + 1);
    return ops;
  };
  const long n = ns, c = nc;
  long ops = cholesky(n) + cholesky(c);
  ops += (1 + c) * n * n;              // L^-1 b and L^-1 C^T
  ops += c * 2 * n + c * (c + 1) * n;  // C M^-1 b and S (lower triangle)
  ops += 2 * c * c;                    // the two solves with S's factor
  ops += 2 * n * c + n * n;            // b + C^T lambda, then L^-T
  return ops;
}

}  // namespace kanegen::codegen
