# SPDX-License-Identifier: GPL-2.0-or-later
# The adaptive implicit methods (--integrator radau and bdf) on real models
# generated with Jacobian kernels (tests/jacobians generates them): the
# state Jacobian against finite differences, Simeon's finite-element crank
# against the IVP test set reference, the spin-up beam against DOPRI5, and a
# closed loop kept on its constraints. The hand-written models are in
# tests/runtime/implicit_test.cpp.
add_executable(test_implicit ${CMAKE_CURRENT_LIST_DIR}/test_implicit_models.cpp)
target_include_directories(test_implicit PRIVATE ${CMAKE_CURRENT_LIST_DIR}/../regression)
target_compile_options(test_implicit PRIVATE ${KANEGEN_WARNINGS})
target_link_libraries(test_implicit PRIVATE kanegen_jacobians_simeon_crank_fe kanegen_jacobians_spin_up_beam
                                            kanegen_jacobians_slider_crank kanegen_catch_main)
catch_discover_tests(test_implicit TEST_PREFIX "implicit: ")
