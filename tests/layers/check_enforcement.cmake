# SPDX-License-Identifier: GPL-2.0-or-later
# cmake/KanegenLayers.cmake must reject what it is for: the scratch project
# (tests/layers/scratch) configured once per broken rule must fail with the
# rule's message, a GiNaC include in a GiNaC-free layer must fail the build,
# and the correct layering must configure and build. check_includes.cmake
# must report a tree with bad includes. Run as cmake -DSOURCE_DIR=<source>
# -DSCRATCH=<dir> -DGENERATOR=<generator> -DCXX=<compiler> -P.
set(build ${SCRATCH}/build)
file(REMOVE_RECURSE ${SCRATCH})

function(configure case expect_success expected)
  execute_process(COMMAND ${CMAKE_COMMAND} -S ${CMAKE_CURRENT_LIST_DIR}/scratch -B ${build} -G ${GENERATOR}
                          -DCMAKE_CXX_COMPILER=${CXX} -DKANEGEN_SOURCE_DIR=${SOURCE_DIR} -DCASE=${case}
                  RESULT_VARIABLE result OUTPUT_VARIABLE out ERROR_VARIABLE err)
  string(REGEX REPLACE "[ \t\r\n]+" " " text "${out} ${err}")
  if(expect_success AND NOT result EQUAL 0)
    message(FATAL_ERROR "case ${case}: the configure step failed:\n${out}\n${err}")
  elseif(NOT expect_success AND result EQUAL 0)
    message(FATAL_ERROR "case ${case}: the configure step passed; the layering check let it through")
  endif()
  string(FIND "${text}" "${expected}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "case ${case}: the output lacks '${expected}':\n${out}\n${err}")
  endif()
  message(STATUS "case ${case}: ${expected}")
endfunction()

function(build case expect_success expected)
  execute_process(COMMAND ${CMAKE_COMMAND} --build ${build} --target kanegen_numeric
                  RESULT_VARIABLE result OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(expect_success AND NOT result EQUAL 0)
    message(FATAL_ERROR "case ${case}: the build failed:\n${out}\n${err}")
  elseif(NOT expect_success AND result EQUAL 0)
    message(FATAL_ERROR "case ${case}: the build passed; the GiNaC include went through")
  endif()
  string(FIND "${out} ${err}" "${expected}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "case ${case}: the build output lacks '${expected}':\n${out}\n${err}")
  endif()
  message(STATUS "case ${case}: build: ${expected}")
endfunction()

# The correct layering passes, and its GiNaC-free layers compile.
configure(clean TRUE "Generating done")
build(clean TRUE "kanegen_numeric")
configure(numeric_reaches_ginac FALSE
          "kanegen_numeric links GiNaC (kanegen_numeric -> bridge -> helper -> PkgConfig::GINAC)")
configure(model_links_libginac FALSE "kanegen_model links GiNaC (kanegen_model -> /usr/lib/x86_64-linux-gnu/libginac.so)")
configure(numeric_links_generator FALSE
          "kanegen_numeric links kanegen_generator, a layer above it (kanegen_numeric -> kanegen_generator)")
configure(runtime_links_a_library FALSE
          "kanegen_runtime must link the standard library and SUNDIALS::cvode only, and links kanegen_model")
configure(numeric_includes_ginac TRUE "Generating done")
build(numeric_includes_ginac FALSE "GiNaC included (ginac/ginac.h) in a GiNaC-free layer")

# The include check on a tree with a GiNaC include in model/ and a symbolic
# include in numeric/.
set(tree ${SCRATCH}/tree)
foreach(folder generator/model generator/fem generator/numeric generator/symbolic generator/kinematics generator/kane
               generator/codegen generator/pipeline runtime)
  file(WRITE ${tree}/${folder}/ok.hpp "#include <vector>\n#include \"model/model.hpp\"\n")
endforeach()
file(WRITE ${tree}/generator/model/bad.cpp "#include <vector>\n#  include <ginac/ginac.h>\n")
file(WRITE ${tree}/generator/numeric/bad.cpp "#include \"kane/equations.hpp\"\n")
execute_process(COMMAND ${CMAKE_COMMAND} -DROOT=${tree} -P ${CMAKE_CURRENT_LIST_DIR}/check_includes.cmake
                RESULT_VARIABLE result OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(result EQUAL 0)
  message(FATAL_ERROR "check_includes.cmake passed a tree with bad includes:\n${out}\n${err}")
endif()
foreach(expected "generator/model/bad.cpp: #include ginac/ginac.h" "generator/numeric/bad.cpp: #include kane/equations.hpp")
  string(FIND "${err}" "${expected}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "check_includes.cmake did not report '${expected}':\n${err}")
  endif()
endforeach()
message(STATUS "includes: the bad ones are reported")
