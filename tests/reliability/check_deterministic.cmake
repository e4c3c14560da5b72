# SPDX-License-Identifier: GPL-2.0-or-later
# Generates MODEL with KANEGEN in three separate processes and requires the
# outputs to be byte-identical:
#   1. as is (address-space randomization as the system has it, normally on);
#   2. with another heap layout and environment size (glibc malloc tunables,
#      freed memory filled with a pattern, a long extra variable): objects land
#      at other relative addresses, so any output that depends on pointer
#      order or on stale memory differs;
#   3. with address-space randomization off (setarch -R), when setarch works here.
# Usage: cmake -DKANEGEN=... -DMODEL=... -DSCRATCH=... [-DSETARCH=...] -P check_deterministic.cmake
file(REMOVE_RECURSE ${SCRATCH})
string(REPEAT "x" 4099 padding)
set(runs plain perturbed)
set(plain_command ${KANEGEN})
set(perturbed_command ${CMAKE_COMMAND} -E env "GLIBC_TUNABLES=glibc.malloc.tcache_count=0:glibc.malloc.mxfast=0"
                      MALLOC_PERTURB_=165 KANEGEN_DETERMINISM_PADDING=${padding} ${KANEGEN})
if(SETARCH)
  execute_process(COMMAND uname -m OUTPUT_VARIABLE arch OUTPUT_STRIP_TRAILING_WHITESPACE)
  execute_process(COMMAND ${SETARCH} ${arch} --addr-no-randomize true RESULT_VARIABLE setarch_rc OUTPUT_QUIET
                  ERROR_QUIET)
  if(setarch_rc EQUAL 0)
    list(APPEND runs fixed)
    set(fixed_command ${SETARCH} ${arch} --addr-no-randomize ${KANEGEN})
  else()
    message(STATUS "setarch --addr-no-randomize does not work here; comparing the other runs only")
  endif()
endif()

foreach(run ${runs})
  execute_process(COMMAND ${${run}_command} generate ${MODEL} -o ${SCRATCH}/${run} --quiet RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "kanegen generate ${MODEL} failed in the '${run}' run (exit ${rc})")
  endif()
endforeach()

file(GLOB reference RELATIVE ${SCRATCH}/plain ${SCRATCH}/plain/*)
list(LENGTH reference count)
if(count EQUAL 0)
  message(FATAL_ERROR "kanegen generate ${MODEL} wrote no file")
endif()
foreach(run ${runs})
  file(GLOB produced RELATIVE ${SCRATCH}/${run} ${SCRATCH}/${run}/*)
  if(NOT produced STREQUAL reference)
    message(FATAL_ERROR "the '${run}' run wrote [${produced}], the first run [${reference}]")
  endif()
  foreach(f ${produced})
    execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files ${SCRATCH}/plain/${f} ${SCRATCH}/${run}/${f}
                    RESULT_VARIABLE diff)
    if(NOT diff EQUAL 0)
      message(FATAL_ERROR "${f} differs between the 'plain' and the '${run}' run of kanegen generate ${MODEL}: "
                          "generation is not deterministic (diff ${SCRATCH}/plain/${f} ${SCRATCH}/${run}/${f})")
    endif()
  endforeach()
endforeach()
message(STATUS "${MODEL}: [${reference}] byte-identical in runs: ${runs}")
