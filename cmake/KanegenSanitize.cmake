# SPDX-License-Identifier: MIT
# Sanitizers and fuzzing instrumentation for every target defined after this
# file is included (the top-level CMakeLists.txt includes it before the
# targets).
#
# KANEGEN_SANITIZE, e.g. "address,undefined": -fsanitize=... with every
# finding fatal (-fno-sanitize-recover=all). The runners that `kanegen
# simulate` and `eval` compile at run time link the sanitized runtime, so they
# must be compiled alike: the build writes the wrapper kanegen-sanitized-cxx
# (use it as KANEGEN_CXX), and ctest sets KANEGEN_CXX to it for every test.
# The sanitizers' options and leak suppressions are compiled into every
# executable of the build (sanitizer_defaults.cpp); runners need none (every
# finding is fatal there too, and they link no library that leaks).
#
# KANEGEN_BUILD_FUZZERS: libFuzzer coverage (-fsanitize=fuzzer-no-link), clang only.
if(KANEGEN_SANITIZE)
  set(KANEGEN_SANITIZE_FLAGS -fsanitize=${KANEGEN_SANITIZE} -fno-sanitize-recover=all)
  add_compile_options(${KANEGEN_SANITIZE_FLAGS} -fno-omit-frame-pointer -g1)
  add_link_options(${KANEGEN_SANITIZE_FLAGS})

  set(KANEGEN_SANITIZED_CXX ${PROJECT_BINARY_DIR}/kanegen-sanitized-cxx)
  file(CONFIGURE OUTPUT ${KANEGEN_SANITIZED_CXX}
       CONTENT "#!/bin/sh\n# The C++ compiler with this build's sanitizers, for KANEGEN_CXX.\nexec '${CMAKE_CXX_COMPILER}' -fsanitize=${KANEGEN_SANITIZE} -fno-sanitize-recover=all -fno-omit-frame-pointer \"$@\"\n")
  file(CHMOD ${KANEGEN_SANITIZED_CXX} PERMISSIONS OWNER_READ OWNER_WRITE OWNER_EXECUTE GROUP_READ GROUP_EXECUTE
                                                   WORLD_READ WORLD_EXECUTE)

  # Every executable gets the sanitizers' default options and leak
  # suppressions compiled in (sanitizer_defaults.cpp), added once all targets exist.
  function(kanegen_add_sanitizer_defaults directory)
    get_property(targets DIRECTORY ${directory} PROPERTY BUILDSYSTEM_TARGETS)
    foreach(target ${targets})
      get_target_property(type ${target} TYPE)
      if(type STREQUAL "EXECUTABLE")
        target_sources(${target} PRIVATE ${PROJECT_SOURCE_DIR}/cmake/sanitizer_defaults.cpp)
      endif()
    endforeach()
    get_property(subdirectories DIRECTORY ${directory} PROPERTY SUBDIRECTORIES)
    foreach(subdirectory ${subdirectories})
      kanegen_add_sanitizer_defaults(${subdirectory})
    endforeach()
  endfunction()
  cmake_language(DEFER DIRECTORY ${PROJECT_SOURCE_DIR} CALL kanegen_add_sanitizer_defaults ${PROJECT_SOURCE_DIR})

  # Read by ctest before it runs the tests (TEST_INCLUDE_FILES): the runners
  # that tests have kanegen compile use the wrapper.
  set(KANEGEN_SANITIZE_ENV ${PROJECT_BINARY_DIR}/kanegen-sanitize-env.cmake)
  file(WRITE ${KANEGEN_SANITIZE_ENV} "set(ENV{KANEGEN_CXX} \"${KANEGEN_SANITIZED_CXX}\")\n")
  set_property(DIRECTORY ${PROJECT_SOURCE_DIR} APPEND PROPERTY TEST_INCLUDE_FILES ${KANEGEN_SANITIZE_ENV})
endif()

if(KANEGEN_BUILD_FUZZERS)
  if(NOT CMAKE_CXX_COMPILER_ID MATCHES "Clang")
    message(FATAL_ERROR "KANEGEN_BUILD_FUZZERS needs clang++ (libFuzzer): configure with -DCMAKE_CXX_COMPILER=clang++")
  endif()
  add_compile_options(-fsanitize=fuzzer-no-link)
endif()
