// SPDX-License-Identifier: GPL-2.0-or-later
// rk4.hpp instantiated in float and double, for freestanding.cmake: compiled
// with -ffreestanding -fno-exceptions -fno-rtti -nostdinc++ and its undefined
// symbols listed (there must be none beyond <math.h>).
#include "kanegen/runtime/rk4.hpp"

void oscillator_float(float h, int steps, float* x) {
  const auto rhs = [](float, const float* s, float* sdot) {
    sdot[0] = s[1];
    sdot[1] = -s[0];
  };
  for (int k = 0; k < steps; ++k) kanegen::runtime::rk4_step<2>(rhs, static_cast<float>(k) * h, h, x);
}

void oscillator_double(double h, int steps, double* x, double* work) {
  const auto rhs = [](double, const double* s, double* sdot) {
    sdot[0] = s[1];
    sdot[1] = -s[0];
  };
  for (int k = 0; k < steps; ++k) kanegen::runtime::rk4_step(rhs, k * h, h, x, 2, work);
}
