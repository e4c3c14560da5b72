# SPDX-License-Identifier: GPL-2.0-or-later
# Regenerates MODEL with KANEGEN into a scratch directory and requires every
# file to be byte-identical to the checked-in copy under EXPECTED_DIR.
# Usage: cmake -DKANEGEN=... -DMODEL=... -DEXPECTED_DIR=... -DSCRATCH=... [-DOPTIONS=--jacobians]
#              -P check_generated.cmake
file(REMOVE_RECURSE ${SCRATCH})
execute_process(COMMAND ${KANEGEN} generate ${MODEL} -o ${SCRATCH} --quiet ${OPTIONS} RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "kanegen generate ${MODEL} failed (exit ${rc})")
endif()
file(GLOB produced RELATIVE ${SCRATCH} ${SCRATCH}/*)
file(GLOB expected RELATIVE ${EXPECTED_DIR} ${EXPECTED_DIR}/*)
if(NOT produced STREQUAL expected)
  message(FATAL_ERROR "files differ: produced [${produced}], checked in [${expected}]; run scripts/regenerate.sh")
endif()
foreach(f ${produced})
  execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files ${SCRATCH}/${f} ${EXPECTED_DIR}/${f} RESULT_VARIABLE diff)
  if(NOT diff EQUAL 0)
    message(FATAL_ERROR "${EXPECTED_DIR}/${f} is not what kanegen generates now; run scripts/regenerate.sh and review the diff")
  endif()
endforeach()
message(STATUS "${MODEL}: ${produced} byte-identical")
