# SPDX-License-Identifier: GPL-2.0-or-later
# Runs the arm7 tracking example on the host (HOST) and as Cortex-M4F
# firmware (FIRMWARE) under QEMU (mps2-an386, semihosting, -icount shift=0
# so that virtual time counts instructions), and checks that both print the
# same tracking error within float tolerance. Prints the firmware's .text
# (SIZE), and the instructions per controller step: SysTick ticks per step
# times the instructions per tick of the firmware's own calibration loop.
execute_process(COMMAND ${HOST} OUTPUT_VARIABLE host_out RESULT_VARIABLE rc TIMEOUT 60)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "host run failed (${rc}): ${host_out}")
endif()
execute_process(COMMAND ${QEMU} -M mps2-an386 -nographic -monitor none -serial none
                        -semihosting-config enable=on,target=native -icount shift=0 -kernel ${FIRMWARE}
                OUTPUT_VARIABLE target_out ERROR_VARIABLE target_err RESULT_VARIABLE rc TIMEOUT 120)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "qemu run failed (${rc}): ${target_out}${target_err}")
endif()
message(STATUS "host:        ${host_out}")
message(STATUS "Cortex-M4F:  ${target_out}")
set(number "([0-9.]+e[-+][0-9]+)")
foreach(run host target)
  if(NOT ${run}_out MATCHES "tracking error max ${number} rad, final rms ${number} rad, failed steps 0")
    message(FATAL_ERROR "the ${run} run did not print a tracking error with no failed step: ${${run}_out}")
  endif()
  set(${run}_max ${CMAKE_MATCH_1})
  set(${run}_rms ${CMAKE_MATCH_2})
endforeach()
# The two builds round differently (the Cortex-M4 fuses multiply-adds, its
# sinf is newlib's) over 2000 steps: 1e-3 relative is float agreement (the
# runs here differ by 0 and 4e-5), a kernel miscompiled for the target is not.
file(WRITE ${SCRATCH}/compare.txt "${host_max} ${target_max} ${host_rms} ${target_rms}\n")
execute_process(COMMAND awk "{ m = ($1 - $2) / $1; r = ($3 - $4) / $3; if (m < 0) m = -m; if (r < 0) r = -r;
                               printf \"%.2e %.2e\", m, r; exit !(m < 1e-3 && r < 1e-3) }" ${SCRATCH}/compare.txt
                OUTPUT_VARIABLE differences RESULT_VARIABLE rc)
message(STATUS "relative differences host/Cortex-M4F (max, rms): ${differences}")
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "host and Cortex-M4F tracking errors differ by more than 1e-3: ${differences}")
endif()
if(target_out MATCHES "controller: ([0-9]+) SysTick ticks over ([0-9]+) steps .*a loop of ([0-9]+) instructions: ([0-9]+) ticks")
  math(EXPR per_step "${CMAKE_MATCH_1} * ${CMAKE_MATCH_3} / ${CMAKE_MATCH_4} / ${CMAKE_MATCH_2}")
  message(STATUS "instructions per controller step (qemu -icount): ${per_step}")
endif()
execute_process(COMMAND ${SIZE} ${FIRMWARE} ${KERNELS_OBJECT} OUTPUT_VARIABLE sizes)
message(STATUS "sizes:\n${sizes}")
