/* SPDX-License-Identifier: MIT */
/* The least a Cortex-M4F needs before main: the vector table (initial stack
   and reset), .data copied and .bss zeroed, the FPU switched on, newlib's
   semihosting (rdimon) set up; main's return value is the exit status that
   qemu returns. No interrupts are used. */
#include <stdint.h>
#include <stdlib.h>

extern uint32_t __stack_top, __data_load, __data_start, __data_end, __bss_start, __bss_end;
extern int main(void);
extern void initialise_monitor_handles(void);
void reset_handler(void);
void fault_handler(void);

__attribute__((section(".vectors"), used)) static void (*const vectors[16])(void) = {
    (void (*)(void))(&__stack_top), reset_handler, fault_handler, fault_handler, fault_handler,
    fault_handler, fault_handler};

void fault_handler(void) {
  exit(99); /* a fault ends the run with a status the test sees */
}

void reset_handler(void) {
  const uint32_t* from = &__data_load;
  for (uint32_t* to = &__data_start; to < &__data_end;) *to++ = *from++;
  for (uint32_t* to = &__bss_start; to < &__bss_end;) *to++ = 0;
  /* CPACR: full access to the coprocessors 10 and 11, the FPU. */
  *(volatile uint32_t*)0xE000ED88 |= 0xFu << 20;
  __asm volatile("dsb\n\tisb");
  initialise_monitor_handles();
  exit(main());
}
