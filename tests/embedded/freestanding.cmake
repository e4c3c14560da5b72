# SPDX-License-Identifier: GPL-2.0-or-later
# Compiles each of SOURCES (separated by '|') with CXX as freestanding code
# (-ffreestanding -fno-exceptions -fno-rtti -nostdinc++, warnings as errors;
# for the float kernels, <name>_float.cpp, -Wdouble-promotion too: float code
# that touches a double, such as a double literal or sqrt for sqrtf, fails)
# and lists the object's undefined symbols with NM: each must be a <math.h>
# function, or one of the four that GCC and Clang may call in any
# freestanding code (memcpy, memmove, memset, memcmp). No malloc, no
# operator new, no __cxa_*, nothing from std::.
string(REPLACE "|" ";" sources "${SOURCES}")
string(REPLACE "|" ";" includes "${INCLUDES}")
set(include_flags)
foreach(dir ${includes})
  list(APPEND include_flags -I${dir})
endforeach()
file(MAKE_DIRECTORY ${SCRATCH})
set(math "sin|cos|tan|asin|acos|atan|atan2|exp|log|sqrt|pow|fabs")
foreach(source ${sources})
  get_filename_component(stem ${source} NAME_WE)
  set(object ${SCRATCH}/${stem}.o)
  set(float_flags)
  if(stem MATCHES "_float$")
    set(float_flags -Wdouble-promotion)
  endif()
  execute_process(COMMAND ${CXX} -std=c++17 -O2 -ffreestanding -fno-exceptions -fno-rtti -nostdinc++ -Wall
                          -Wextra -Wpedantic ${float_flags} -Werror ${include_flags} -c ${source} -o ${object}
                  RESULT_VARIABLE rc ERROR_VARIABLE errors)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${source} does not compile freestanding with ${CXX}:\n${errors}")
  endif()
  execute_process(COMMAND ${NM} -u ${object} OUTPUT_VARIABLE undefined RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${NM} -u ${object} failed")
  endif()
  string(REGEX MATCHALL "[^ \n]+\n" symbols "${undefined}")
  set(names)
  foreach(line ${symbols})
    string(STRIP "${line}" symbol)
    if(symbol STREQUAL "U")
      continue()
    endif()
    list(APPEND names ${symbol})
    if(NOT symbol MATCHES "^(${math})f?$" AND NOT symbol MATCHES "^mem(cpy|move|set|cmp)$")
      message(FATAL_ERROR "${source} compiled freestanding with ${CXX} needs ${symbol}, which is neither "
                          "<math.h> nor mem*: the emitted code must not use the heap, exceptions, RTTI or "
                          "the standard library")
    endif()
  endforeach()
  message(STATUS "${stem}: undefined symbols: ${names}")
endforeach()
