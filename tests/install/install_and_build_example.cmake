# SPDX-License-Identifier: GPL-2.0-or-later
# Installs this build to a scratch prefix, then configures, builds and runs
# examples/controller against it with find_package(kanegen), as a user would.
file(REMOVE_RECURSE ${SCRATCH})
function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "failed (${rc}): ${ARGN}\n${out}\n${err}")
  endif()
endfunction()
run(${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${SCRATCH}/prefix)
# The package carries its license texts (docs/licensing.md).
foreach(file LICENSE THIRD_PARTY.md LICENSES/MIT.txt LICENSES/GPL-2.0-or-later.txt)
  if(NOT EXISTS ${SCRATCH}/prefix/share/doc/kanegen/${file})
    message(FATAL_ERROR "the installed package has no share/doc/kanegen/${file}")
  endif()
endforeach()
run(${CMAKE_COMMAND} -S ${SOURCE_DIR}/examples/controller -B ${SCRATCH}/build -DCMAKE_PREFIX_PATH=${SCRATCH}/prefix
    -DCMAKE_BUILD_TYPE=Release)
run(${CMAKE_COMMAND} --build ${SCRATCH}/build)
run(${SCRATCH}/build/computed_torque)
message(STATUS "installed kanegen: the license texts, find_package, kanegen_add_model and the example controller work")
