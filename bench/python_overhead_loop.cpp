// SPDX-License-Identifier: GPL-2.0-or-later
// The C++ side of bench/python_overhead.py: forward_dynamics over the same
// states as the Python batch, called in a plain loop through the same model
// library (kernels.so, dlopen) and ModelTable as the Python module, without
// Python. Usage: python_overhead_loop KERNELS_SO STATES_FILE N REPEATS
// (STATES_FILE: N rows of q, u, tau as float64). Prints the best time per
// state in ns over REPEATS loops, and a checksum of udot.
#include <dlfcn.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "kanegen/runtime/model_table.hpp"

int main(int argc, char** argv) {
  if (argc != 5) {
    std::fprintf(stderr, "usage: %s KERNELS_SO STATES_FILE N REPEATS\n", argv[0]);
    return 2;
  }
  void* handle = dlopen(argv[1], RTLD_NOW | RTLD_LOCAL);
  if (!handle) {
    std::fprintf(stderr, "%s\n", dlerror());
    return 1;
  }
  using Export = int (*)(kanegen::runtime::ModelTable*, std::size_t);
  const auto fill = reinterpret_cast<Export>(dlsym(handle, "kanegen_model_table"));
  kanegen::runtime::ModelTable table;
  if (!fill || fill(&table, sizeof table) != 0) return 1;
  std::vector<double> params(table.parameters_size / sizeof(double) + 1);
  table.default_parameters(params.data());

  const long n = std::atol(argv[3]), repeats = std::atol(argv[4]);
  const int nq = table.nq, nu = table.nu, ntau = table.ntau, row = nq + nu + ntau;
  std::vector<double> states(static_cast<std::size_t>(n * row)), udot(static_cast<std::size_t>(n * nu));
  std::FILE* in = std::fopen(argv[2], "rb");
  if (!in || std::fread(states.data(), sizeof(double), states.size(), in) != states.size()) return 1;
  std::fclose(in);

  double best = 1e300;
  for (long r = 0; r < repeats; ++r) {
    const auto start = std::chrono::steady_clock::now();
    for (long i = 0; i < n; ++i) {
      const double* s = states.data() + i * row;
      table.forward_dynamics(params.data(), 0.0, s, s + nq, s + nq + nu, udot.data() + i * nu);
    }
    const double ns =
        std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - start).count();
    if (ns < best) best = ns;
  }
  double checksum = 0;
  for (double x : udot) checksum += x;
  std::printf("%.3f %.17g\n", best / static_cast<double>(n), checksum);
  return 0;
}
