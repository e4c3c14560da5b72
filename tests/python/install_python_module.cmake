# SPDX-License-Identifier: GPL-2.0-or-later
# Installs this build to a scratch prefix and imports kanegen from there, as
# docs/python.md tells a user to (PYTHONPATH=<prefix>/<python dir>): the
# installed module, with the installed runtime, loads and calls a model.
file(REMOVE_RECURSE ${SCRATCH})
function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "failed (${rc}): ${ARGN}\n${out}\n${err}")
  endif()
  set(out "${out}" PARENT_SCOPE)
endfunction()
run(${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${SCRATCH}/prefix)
set(script [=[
import math, os, sys
import kanegen
prefix = os.path.realpath(sys.argv[1])
assert os.path.realpath(kanegen.__file__).startswith(prefix), kanegen.__file__
m = kanegen.load(sys.argv[2])
assert abs(m.forward_dynamics([0.5], [0.0])[0] + 9.81 * math.sin(0.5)) < 1e-14
print(m.library)
]=])
file(WRITE ${SCRATCH}/check.py "${script}")
# A compiler that notes its arguments, to see which runtime headers the model library is built with.
file(WRITE ${SCRATCH}/cxx "#!/bin/sh\necho \"$@\" >> ${SCRATCH}/cxx.log\nexec c++ \"$@\"\n")
file(CHMOD ${SCRATCH}/cxx PERMISSIONS OWNER_READ OWNER_WRITE OWNER_EXECUTE)
execute_process(COMMAND ${CMAKE_COMMAND} -E env PYTHONPATH=${SCRATCH}/prefix/${PYTHON_DIR}
                        KANEGEN_CACHE_DIR=${SCRATCH}/cache KANEGEN_CXX=${SCRATCH}/cxx PYTHONDONTWRITEBYTECODE=1
                        ${PYTHON} ${SCRATCH}/check.py ${SCRATCH}/prefix ${MODEL}
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "the installed module failed (${rc}):\n${out}\n${err}")
endif()
# The installed module compiled the model against the installed runtime's headers.
file(READ ${SCRATCH}/cxx.log compiled)
if(NOT compiled MATCHES "-I${SCRATCH}/prefix/include ")
  message(FATAL_ERROR "the installed module did not compile against ${SCRATCH}/prefix/include:\n${compiled}")
endif()
message(STATUS "installed Python module: imported from ${SCRATCH}/prefix/${PYTHON_DIR}, loaded ${out}")
