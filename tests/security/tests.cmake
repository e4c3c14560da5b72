# SPDX-License-Identifier: GPL-2.0-or-later
# Model text in generated code (docs/errors.md#security): URDFs whose names
# (and file names) carry newlines, comment ends, trigraphs, quotes, invalid
# UTF-8 and the like through `kanegen generate` and `simulate`. The checks on
# the generated code are the names fuzzer's (fuzz/generated_code.cpp).
add_executable(test_security_names ${CMAKE_CURRENT_LIST_DIR}/test_injection.cpp
                                   ${PROJECT_SOURCE_DIR}/fuzz/generated_code.cpp)
target_include_directories(test_security_names PRIVATE ${PROJECT_SOURCE_DIR} ${PROJECT_SOURCE_DIR}/tests)
target_compile_options(test_security_names PRIVATE ${KANEGEN_WARNINGS})
target_compile_definitions(test_security_names
                           PRIVATE KANEGEN_EXE="$<TARGET_FILE:kanegen>"
                                   KANEGEN_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
                                   KANEGEN_SCRATCH_DIR="${CMAKE_CURRENT_BINARY_DIR}/security_scratch")
# model/names (is_identifier) for the comparison of generated code.
target_link_libraries(test_security_names PRIVATE kanegen_model kanegen_catch_main)
add_dependencies(test_security_names kanegen kanegen_runtime)
catch_discover_tests(test_security_names TEST_PREFIX "security: ")
