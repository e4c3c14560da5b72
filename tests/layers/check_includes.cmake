# SPDX-License-Identifier: GPL-2.0-or-later
# No #include crosses a layer the wrong way: model, fem, numeric and the
# runtime include no GiNaC (or CLN); none of them includes a layer above it;
# the symbolic side includes nothing of the numeric path (its independence,
# docs/verify.md); runner/, verify/ and fmu/ include nothing of the command
# line, runner/ nothing of verify/ or fmu/, and fmu/ (beside verify/, on the
# runner) nothing of verify/ or the numeric path (generator/CMakeLists.txt
# orders the layers).
# tests/verify/check_independence.cmake holds the numeric path to its one use
# of fem. Run as cmake -DROOT=<source tree> -P.
set(ginac "^(ginac|cln)/")
set(symbolic_side "symbolic|kinematics|kane|codegen|pipeline|runner|verify|cli")
set(above_pipeline "runner|verify|cli")
# folder;forbidden include pattern (matched against the included path)
set(rules
    "generator/model|${ginac}|^(fem|numeric|${symbolic_side})/"
    "generator/fem|${ginac}|^(numeric|${symbolic_side})/"
    "generator/numeric|${ginac}|^(${symbolic_side})/"
    "runtime|${ginac}|^(model|fem|numeric|${symbolic_side})/"
    "generator/symbolic|^(numeric|pipeline|${above_pipeline})/"
    "generator/kinematics|^(numeric|pipeline|${above_pipeline})/"
    "generator/kane|^(numeric|pipeline|${above_pipeline})/"
    "generator/codegen|^(numeric|pipeline|${above_pipeline})/"
    "generator/pipeline|^(numeric|${above_pipeline})/"
    "generator/runner|^(numeric|verify|fmu|cli)/"
    "generator/verify|^(fmu|cli)/"
    "generator/fmu|^(numeric|verify|cli)/")
set(problems "")
foreach(rule ${rules})
  string(FIND "${rule}" "|" bar)
  string(SUBSTRING "${rule}" 0 ${bar} folder)
  math(EXPR bar "${bar} + 1")
  string(SUBSTRING "${rule}" ${bar} -1 forbidden)
  file(GLOB_RECURSE files ${ROOT}/${folder}/*.hpp ${ROOT}/${folder}/*.cpp ${ROOT}/${folder}/*.h ${ROOT}/${folder}/*.cc)
  if(NOT files)
    string(APPEND problems "\n  ${folder}: no sources (moved? update tests/layers/check_includes.cmake)")
  endif()
  foreach(file ${files})
    file(STRINGS ${file} lines REGEX "^[ \t]*#[ \t]*include[ \t]*[<\"]")
    foreach(line ${lines})
      string(REGEX REPLACE "^[ \t]*#[ \t]*include[ \t]*[<\"]([^>\"]*)[>\"].*" "\\1" included "${line}")
      if(included MATCHES "${forbidden}")
        file(RELATIVE_PATH name ${ROOT} ${file})
        string(APPEND problems "\n  ${name}: #include ${included}")
      endif()
    endforeach()
  endforeach()
endforeach()
if(problems)
  message(FATAL_ERROR "includes that cross the layers (docs/architecture.md):${problems}")
endif()
message(STATUS "includes: every layer stays within its dependencies")
