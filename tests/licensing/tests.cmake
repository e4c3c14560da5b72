# SPDX-License-Identifier: GPL-2.0-or-later
# Licensing (issue 19): every source file names its license in an SPDX line,
# MIT where users build it into their programs and GPL-2.0-or-later
# elsewhere; freshly generated code carries the MIT identifier and the
# output line; the license files exist.
add_executable(test_licensing ${CMAKE_CURRENT_LIST_DIR}/licensing_test.cpp)
target_include_directories(test_licensing PRIVATE ${CMAKE_CURRENT_LIST_DIR}/../support)
target_compile_options(test_licensing PRIVATE ${KANEGEN_WARNINGS})
target_compile_definitions(test_licensing PRIVATE KANEGEN_EXE="$<TARGET_FILE:kanegen>"
                                                  KANEGEN_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
                                                  KANEGEN_CACHE="${CMAKE_CURRENT_BINARY_DIR}/licensing_cache"
                                                  KANEGEN_SCRATCH_DIR="${CMAKE_CURRENT_BINARY_DIR}/licensing_scratch")
target_link_libraries(test_licensing PRIVATE kanegen_catch_main)
add_dependencies(test_licensing kanegen kanegen_runtime)
catch_discover_tests(test_licensing TEST_PREFIX "licensing: ")
