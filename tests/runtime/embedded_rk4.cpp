// SPDX-License-Identifier: GPL-2.0-or-later
// Compiled with -fno-exceptions -fno-rtti -nostdinc++ (see tests.cmake): the
// fixed-size RK4 must work with no C++ standard library at all.
#include "kanegen/runtime/rk4.hpp"

// The harmonic oscillator q'' = -q from (1, 0) over `steps` steps of size h.
void embedded_oscillator(double h, int steps, double* q, double* v) {
  double x[2] = {1.0, 0.0};
  const auto rhs = [](double, const double* s, double* sdot) {
    sdot[0] = s[1];
    sdot[1] = -s[0];
  };
  for (int k = 0; k < steps; ++k) kanegen::runtime::rk4_step<2>(rhs, k * h, h, x);
  *q = x[0];
  *v = x[1];
}
