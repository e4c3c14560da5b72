# SPDX-License-Identifier: GPL-2.0-or-later
# The code generator's parts on their own: the helper code that generated
# models include verbatim (templates/solve_saddle.hpp), compiled and solved
# against Eigen, the kernel table's printer, generalized_momentum, and the
# expression graph's derivatives (the Jacobian kernels'), and the counts of the
# forward_dynamics that is counted but not printed.
find_package(Eigen3 REQUIRED NO_MODULE)
add_executable(test_codegen ${CMAKE_CURRENT_LIST_DIR}/test_solve_saddle.cpp
                            ${CMAKE_CURRENT_LIST_DIR}/test_kernel_printer.cpp
                            ${CMAKE_CURRENT_LIST_DIR}/test_generalized_momentum.cpp
                            ${CMAKE_CURRENT_LIST_DIR}/test_moved_bodies.cpp
                            ${CMAKE_CURRENT_LIST_DIR}/test_graph_derivative.cpp
                            ${CMAKE_CURRENT_LIST_DIR}/test_recursive_dynamics.cpp
                            ${CMAKE_CURRENT_LIST_DIR}/test_unrolled_saddle.cpp
                            ${CMAKE_CURRENT_LIST_DIR}/test_dynamics_choice.cpp)
target_include_directories(test_codegen PRIVATE ${PROJECT_SOURCE_DIR}/templates)
target_compile_definitions(test_codegen PRIVATE KANEGEN_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
target_compile_options(test_codegen PRIVATE ${KANEGEN_WARNINGS})
target_link_libraries(test_codegen PRIVATE kanegen_generator kanegen_model_arm7 kanegen_model_flexible_arm2
                                           kanegen_model_four_bar Eigen3::Eigen kanegen_catch_main)
catch_discover_tests(test_codegen TEST_PREFIX "codegen: ")
