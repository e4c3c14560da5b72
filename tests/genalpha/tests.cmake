# SPDX-License-Identifier: GPL-2.0-or-later
# Generalized-alpha (runtime/genalpha.hpp) on generated models with Jacobian
# kernels (the kanegen_jacobians_* targets of tests/jacobians, and the N
# four-bar here): the slider-crank's loops against its exact kinematics, the
# spin-up beam at a 1 ms step against DOPRI5, and the N four-bar through its
# singular positions against the exact parallelogram motion.
kanegen_add_model(kanegen_genalpha_nfourbar2 ${PROJECT_SOURCE_DIR}/models/nfourbar2.json JACOBIANS)
add_executable(test_genalpha_models ${CMAKE_CURRENT_LIST_DIR}/test_genalpha_models.cpp)
target_compile_options(test_genalpha_models PRIVATE ${KANEGEN_WARNINGS})
target_link_libraries(test_genalpha_models PRIVATE kanegen_jacobians_spin_up_beam kanegen_jacobians_slider_crank
                                                   kanegen_genalpha_nfourbar2 kanegen_catch_main)
catch_discover_tests(test_genalpha_models TEST_PREFIX "genalpha: ")
