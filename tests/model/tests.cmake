# SPDX-License-Identifier: GPL-2.0-or-later
# Model-loading tests: the shipped JSON models, URDF import and one test per
# kind of bad input (tests/data/bad_models). Included from tests/CMakeLists.txt.
file(GLOB KANEGEN_MODEL_TEST_SOURCES CONFIGURE_DEPENDS ${CMAKE_CURRENT_LIST_DIR}/*.cpp)
add_executable(test_model ${KANEGEN_MODEL_TEST_SOURCES})
target_compile_options(test_model PRIVATE ${KANEGEN_WARNINGS})
target_compile_definitions(test_model PRIVATE KANEGEN_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
                                              KANEGEN_MODEL_TEST_DATA="${CMAKE_CURRENT_LIST_DIR}/data")
# kanegen_symbolic for GiNaC: expression_check_test compares its reading with GiNaC's.
target_link_libraries(test_model PRIVATE kanegen_model kanegen_symbolic kanegen_catch_main)
catch_discover_tests(test_model TEST_PREFIX "model: ")
