# SPDX-License-Identifier: GPL-2.0-or-later
# Compiles a generated model with CXX under -Wall -Wextra -Wpedantic -Werror.
execute_process(COMMAND ${CXX} -std=c++17 -O0 -Wall -Wextra -Wpedantic -Werror -fsyntax-only -I${DIR} ${DIR}/${NAME}.cpp
                RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "${DIR}/${NAME}.cpp does not compile warning-free with ${CXX}")
endif()
