# SPDX-License-Identifier: GPL-2.0-or-later
# kanegen modes (issue 3): the shipped flexible models' natural frequencies
# through the command line, against Euler-Bernoulli, the rotating-beam table,
# CalculiX and a tip-mass frequency equation; the static tip deflection; the
# rigid path (a pendulum), unstable and singular cases, bad options. Runners
# are cached under the build tree (KANEGEN_CACHE_DIR), not in the user's cache.
find_package(nlohmann_json REQUIRED)
find_package(Eigen3 REQUIRED NO_MODULE)

add_executable(test_modes ${CMAKE_CURRENT_LIST_DIR}/modes_test.cpp)
target_compile_options(test_modes PRIVATE ${KANEGEN_WARNINGS})
target_compile_definitions(test_modes PRIVATE KANEGEN_EXE="$<TARGET_FILE:kanegen>"
                                              KANEGEN_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
                                              KANEGEN_CACHE="${CMAKE_CURRENT_BINARY_DIR}/modes_cache"
                                              KANEGEN_SCRATCH_DIR="${CMAKE_CURRENT_BINARY_DIR}/modes_scratch")
target_link_libraries(test_modes PRIVATE kanegen_catch_main nlohmann_json::nlohmann_json Eigen3::Eigen)
add_dependencies(test_modes kanegen kanegen_runtime)
catch_discover_tests(test_modes TEST_PREFIX "modes: ")

# Assumed modes (shape functions in the model file) against their
# Rayleigh-Ritz closed forms, and the convergence of the mesh they are sampled on.
add_executable(test_assumed_modes ${CMAKE_CURRENT_LIST_DIR}/assumed_modes_test.cpp)
target_compile_options(test_assumed_modes PRIVATE ${KANEGEN_WARNINGS})
target_compile_definitions(test_assumed_modes PRIVATE KANEGEN_EXE="$<TARGET_FILE:kanegen>"
                                                      KANEGEN_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
                                                      KANEGEN_CACHE="${CMAKE_CURRENT_BINARY_DIR}/modes_cache"
                                                      KANEGEN_SCRATCH_DIR="${CMAKE_CURRENT_BINARY_DIR}/assumed_scratch")
target_link_libraries(test_assumed_modes PRIVATE kanegen_catch_main nlohmann_json::nlohmann_json)
add_dependencies(test_assumed_modes kanegen kanegen_runtime)
catch_discover_tests(test_assumed_modes TEST_PREFIX "modes: ")
