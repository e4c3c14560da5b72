# SPDX-License-Identifier: GPL-2.0-or-later
# The code generator's parts on their own: the helper code that generated
# models include verbatim (templates/solve_saddle.hpp), compiled and solved
# against Eigen, the kernel table's printer, generalized_momentum, the
# expression graph's derivatives (the Jacobian kernels'), the lazy derivation
# context (kane::DerivationContext), the emission order of
# statements, and the counts of the forward_dynamics that is counted but not
# printed.
find_package(Eigen3 REQUIRED NO_MODULE)
add_executable(test_codegen ${CMAKE_CURRENT_LIST_DIR}/test_solve_saddle.cpp
                            ${CMAKE_CURRENT_LIST_DIR}/test_kernel_printer.cpp
                            ${CMAKE_CURRENT_LIST_DIR}/test_generalized_momentum.cpp
                            ${CMAKE_CURRENT_LIST_DIR}/test_moved_bodies.cpp
                            ${CMAKE_CURRENT_LIST_DIR}/test_graph_derivative.cpp
                            ${CMAKE_CURRENT_LIST_DIR}/test_recursive_dynamics.cpp
                            ${CMAKE_CURRENT_LIST_DIR}/test_derivation_context.cpp
                            ${CMAKE_CURRENT_LIST_DIR}/test_unrolled_saddle.cpp
                            ${CMAKE_CURRENT_LIST_DIR}/test_dynamics_choice.cpp
                            ${CMAKE_CURRENT_LIST_DIR}/test_split_kernels.cpp
                            ${CMAKE_CURRENT_LIST_DIR}/test_statement_order.cpp
                            ${CMAKE_CURRENT_LIST_DIR}/test_hostile_names.cpp)
target_include_directories(test_codegen PRIVATE ${PROJECT_SOURCE_DIR}/templates)
target_compile_definitions(test_codegen PRIVATE KANEGEN_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
target_compile_options(test_codegen PRIVATE ${KANEGEN_WARNINGS})
# arm7 again, renamed arm7_split and with its kernels split into parts of
# about 300 operations (in double and float), against the unsplit arm7.
file(READ ${PROJECT_SOURCE_DIR}/models/arm7.urdf _kg_arm7)
string(REPLACE "<robot name=\"arm7\">" "<robot name=\"arm7_split\">" _kg_arm7_split "${_kg_arm7}")
file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/arm7_split.urdf "${_kg_arm7_split}")
kanegen_add_model(kanegen_model_arm7_split ${CMAKE_CURRENT_BINARY_DIR}/arm7_split.urdf SPLIT_THRESHOLD 300)
kanegen_add_model(kanegen_model_arm7_split_float ${CMAKE_CURRENT_BINARY_DIR}/arm7_split.urdf SPLIT_THRESHOLD 300
                  PRECISION float)
target_compile_options(kanegen_model_arm7_split PRIVATE ${KANEGEN_WARNINGS} -Werror)
target_compile_options(kanegen_model_arm7_split_float PRIVATE ${KANEGEN_WARNINGS} -Werror)
# Names with backslashes, quotes, trigraph starts, comment ends, directives and
# UTF-8 in every text field (test_hostile_names.cpp), compiled with -Werror.
kanegen_add_model(kanegen_model_hostile_names ${PROJECT_SOURCE_DIR}/tests/data/models/hostile_names.urdf)
target_compile_options(kanegen_model_hostile_names PRIVATE ${KANEGEN_WARNINGS} -Werror)
target_compile_definitions(test_codegen PRIVATE
                           ARM7_SPLIT_HEADER="${CMAKE_CURRENT_BINARY_DIR}/kanegen_generated/kanegen_model_arm7_split/arm7_split.hpp")
target_link_libraries(test_codegen PRIVATE kanegen_generator kanegen_model_arm7 kanegen_model_chain20 kanegen_model_flexible_arm2
                                           kanegen_model_four_bar kanegen_model_arm7_split
                                           kanegen_model_arm7_split_float kanegen_model_hostile_names Eigen3::Eigen
                                           kanegen_catch_main)
catch_discover_tests(test_codegen TEST_PREFIX "codegen: ")
