# SPDX-License-Identifier: GPL-2.0-or-later
# Compiles a generated model with CXX under -Wall -Wextra -Wpedantic -Werror:
# its kernels, and its runner, which instantiates kernel_table<ModelTable>()
# against the runtime's headers (RUNTIME_INCLUDE).
foreach(file ${NAME}.cpp ${NAME}_runner.cpp)
  execute_process(COMMAND ${CXX} -std=c++17 -O0 -Wall -Wextra -Wpedantic -Werror -fsyntax-only -I${DIR}
                          -I${RUNTIME_INCLUDE} ${DIR}/${file}
                  RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${DIR}/${file} does not compile warning-free with ${CXX}")
  endif()
endforeach()
