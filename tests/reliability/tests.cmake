# SPDX-License-Identifier: GPL-2.0-or-later
# Reliability (issue 6): fuzzing regression inputs replayed without libFuzzer,
# every bad model and every run-time failure ending in one clear message, and
# regeneration that is byte-identical across processes. Included from
# tests/CMakeLists.txt.

# tests/data/fuzz_regressions/ through the fuzz targets' checks
# (fuzz/harness.cpp), and the bad inputs added here, through the loaders.
add_executable(test_reliability_model ${CMAKE_CURRENT_LIST_DIR}/fuzz_regressions_test.cpp
                                      ${CMAKE_CURRENT_LIST_DIR}/bad_inputs_test.cpp ${PROJECT_SOURCE_DIR}/fuzz/harness.cpp)
target_include_directories(test_reliability_model PRIVATE ${PROJECT_SOURCE_DIR} ${PROJECT_SOURCE_DIR}/tests/model)
target_compile_options(test_reliability_model PRIVATE ${KANEGEN_WARNINGS})
target_compile_definitions(test_reliability_model
                           PRIVATE KANEGEN_FUZZ_REGRESSIONS="${PROJECT_SOURCE_DIR}/tests/data/fuzz_regressions"
                                   KANEGEN_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
                                   KANEGEN_MODEL_TEST_DATA="${PROJECT_SOURCE_DIR}/tests/model/data")
# The harness names parameters as the symbolic stage does (symbolic/variables.hpp).
target_link_libraries(test_reliability_model PRIVATE kanegen_model kanegen_symbolic kanegen_catch_main)
catch_discover_tests(test_reliability_model TEST_PREFIX "reliability: ")

# The command line on bad models and on runs that fail, as a user sees it.
add_executable(test_reliability_cli ${CMAKE_CURRENT_LIST_DIR}/cli_failures_test.cpp)
target_compile_options(test_reliability_cli PRIVATE ${KANEGEN_WARNINGS})
target_compile_definitions(test_reliability_cli
                           PRIVATE KANEGEN_EXE="$<TARGET_FILE:kanegen>"
                                   KANEGEN_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
                                   KANEGEN_SCRATCH_DIR="${CMAKE_CURRENT_BINARY_DIR}/reliability_scratch")
target_link_libraries(test_reliability_cli PRIVATE kanegen_catch_main)
add_dependencies(test_reliability_cli kanegen kanegen_runtime)
catch_discover_tests(test_reliability_cli TEST_PREFIX "reliability: ")

# Every shipped and test model regenerated in separate processes, byte for byte.
file(GLOB KANEGEN_DETERMINISM_MODELS CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/models/*.json
     ${PROJECT_SOURCE_DIR}/models/*.urdf ${PROJECT_SOURCE_DIR}/tests/data/models/*.json)
find_program(KANEGEN_SETARCH setarch)
foreach(model ${KANEGEN_DETERMINISM_MODELS})
  get_filename_component(stem ${model} NAME_WE)
  if(stem IN_LIST KANEGEN_LARGE_MODELS)  # tests/CMakeLists.txt says why
    continue()
  endif()
  add_test(NAME reliability_deterministic_${stem}
           COMMAND ${CMAKE_COMMAND} -DKANEGEN=$<TARGET_FILE:kanegen> -DMODEL=${model}
                   -DSCRATCH=${CMAKE_CURRENT_BINARY_DIR}/determinism/${stem}
                   -DSETARCH=${KANEGEN_SETARCH} -P ${CMAKE_CURRENT_LIST_DIR}/check_deterministic.cmake)
endforeach()
# The C3D20 tubes and the stiffened solid rod take a minute or more (the run with malloc's caches off is
# slow on GiNaC's many small objects): ctest -j starts them first rather than last.
foreach(stem spin_up_c3d20_cb spin_up_c3d20 solid_slider_crank_stiff solid_slider_crank)
  if(TEST reliability_deterministic_${stem})
    set_tests_properties(reliability_deterministic_${stem} PROPERTIES COST 100)
  endif()
endforeach()
