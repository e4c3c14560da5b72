# SPDX-License-Identifier: GPL-2.0-or-later
# Generalized-alpha (runtime/genalpha.hpp) on generated models with Jacobian
# kernels (the kanegen_jacobians_* targets of tests/jacobians): the
# slider-crank's loops against its exact kinematics, and the spin-up beam at
# a 1 ms step against DOPRI5.
add_executable(test_genalpha_models ${CMAKE_CURRENT_LIST_DIR}/../regression/main.cpp
                                    ${CMAKE_CURRENT_LIST_DIR}/test_genalpha_models.cpp)
target_compile_options(test_genalpha_models PRIVATE ${KANEGEN_WARNINGS})
target_link_libraries(test_genalpha_models PRIVATE kanegen_jacobians_spin_up_beam kanegen_jacobians_slider_crank
                                                   Catch2::Catch2)
catch_discover_tests(test_genalpha_models TEST_PREFIX "genalpha: ")
