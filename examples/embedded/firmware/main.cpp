// SPDX-License-Identifier: MIT
// The tracking run on a Cortex-M4F, printed over semihosting, with the
// controller steps timed by SysTick on the core clock.
#include <stdint.h>
#include <stdio.h>

#include "../arm7_tracking.hpp"
#include "../report.hpp"

namespace {

// SysTick (ARMv7-M): a 24-bit down-counter on the core clock.
volatile uint32_t& syst_csr = *reinterpret_cast<volatile uint32_t*>(0xE000E010);
volatile uint32_t& syst_rvr = *reinterpret_cast<volatile uint32_t*>(0xE000E014);
volatile uint32_t& syst_cvr = *reinterpret_cast<volatile uint32_t*>(0xE000E018);

uint32_t started = 0;
uint64_t control_ticks = 0;

void before_control() { started = syst_cvr; }
void after_control() { control_ticks += (started - syst_cvr) & 0xFFFFFFu; }

/// SysTick ticks of a loop of exactly 2 n instructions (subs, bne): under
/// qemu -icount, where time counts instructions, it converts ticks into
/// instructions; on a real chip, cycles per instruction of this loop.
uint32_t calibration_ticks(uint32_t n) {
  const uint32_t start = syst_cvr;
  __asm volatile("1: subs %0, %0, #1\n\tbne 1b" : "+r"(n) : : "cc");
  return (start - syst_cvr) & 0xFFFFFFu;
}

}  // namespace

int main() {
  syst_rvr = 0xFFFFFFu;
  syst_cvr = 0;
  syst_csr = 5;  // enabled, core clock, no interrupt
  arm7_tracking::Hooks hooks;
  hooks.before_control = before_control;
  hooks.after_control = after_control;
  const arm7_tracking::Result r = arm7_tracking::run(arm7_tracking::kSteps, arm7_tracking::kStep, hooks);
  arm7_tracking::print(r);
  constexpr uint32_t loop = 100000;
  printf(
      "controller: %llu SysTick ticks over %d steps (%.2f per step); a loop of %lu instructions: %lu ticks\n",
      static_cast<unsigned long long>(control_ticks), r.steps, static_cast<double>(control_ticks) / r.steps,
      static_cast<unsigned long>(2 * loop), static_cast<unsigned long>(calibration_ticks(loop)));
  return r.failed_steps == 0 ? 0 : 1;
}
