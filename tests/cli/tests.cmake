# SPDX-License-Identifier: GPL-2.0-or-later
# The command line, run as a user would, in a private runner cache.
find_package(nlohmann_json REQUIRED)
add_executable(test_cli ${CMAKE_CURRENT_LIST_DIR}/test_cli.cpp ${CMAKE_CURRENT_LIST_DIR}/test_cli_methods.cpp)
target_compile_options(test_cli PRIVATE ${KANEGEN_WARNINGS})
target_compile_definitions(test_cli PRIVATE KANEGEN_EXE="$<TARGET_FILE:kanegen>"
                                            KANEGEN_MODELS_DIR="${PROJECT_SOURCE_DIR}/models"
                                            KANEGEN_BAD_MODELS_DIR="${PROJECT_SOURCE_DIR}/tests/data/bad_models"
                                            KANEGEN_SCRATCH_DIR="${CMAKE_CURRENT_BINARY_DIR}/cli_scratch")
# kanegen::runtime: the registry of integrators, to run every one (test_cli_methods.cpp).
target_link_libraries(test_cli PRIVATE kanegen_catch_main nlohmann_json::nlohmann_json kanegen::runtime)
add_dependencies(test_cli kanegen kanegen_runtime)
catch_discover_tests(test_cli TEST_PREFIX "cli: ")

# --energies and the work of non-conservative forces (nonconservative_work).
add_executable(test_energies ${CMAKE_CURRENT_LIST_DIR}/test_energies.cpp)
target_compile_options(test_energies PRIVATE ${KANEGEN_WARNINGS})
target_compile_definitions(test_energies PRIVATE KANEGEN_EXE="$<TARGET_FILE:kanegen>"
                                                 KANEGEN_MODELS_DIR="${PROJECT_SOURCE_DIR}/models"
                                                 KANEGEN_SCRATCH_DIR="${CMAKE_CURRENT_BINARY_DIR}/energies_scratch")
target_link_libraries(test_energies PRIVATE kanegen_catch_main)
add_dependencies(test_energies kanegen kanegen_runtime)
catch_discover_tests(test_energies TEST_PREFIX "energies: ")

# The runner cache: concurrent builds, entries changed after they were built,
# a cache directory others may write to.
add_executable(test_runner_cache ${CMAKE_CURRENT_LIST_DIR}/test_runner_cache.cpp)
target_compile_options(test_runner_cache PRIVATE ${KANEGEN_WARNINGS})
target_compile_definitions(test_runner_cache PRIVATE KANEGEN_EXE="$<TARGET_FILE:kanegen>"
                                                     KANEGEN_MODELS_DIR="${PROJECT_SOURCE_DIR}/models"
                                                     KANEGEN_SCRATCH_DIR="${CMAKE_CURRENT_BINARY_DIR}/cache_scratch")
target_link_libraries(test_runner_cache PRIVATE kanegen_catch_main)
add_dependencies(test_runner_cache kanegen kanegen_runtime)
catch_discover_tests(test_runner_cache TEST_PREFIX "cache: ")
