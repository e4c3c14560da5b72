# SPDX-License-Identifier: GPL-2.0-or-later
# Flexible links (issue 3) in motion: the spin-up beam with and without
# geometric stiffening, mesh convergence and modal reduction; energy of free
# flexible models; bodies carried on beam nodes; a force and a loop on a mesh
# body's node set at rest (test_mesh_node_sets.cpp); the stiffening of mesh
# bodies (test_mesh_stiffening.cpp). Frequencies are in tests/modes.
find_package(Eigen3 REQUIRED NO_MODULE)
foreach(stem flex_tip_mass flex_tip_body flex_tip_mass_linear flex_tip_body_linear spin_up_beam_e5 spin_up_beam_e20
             spin_up_beam_modal free_strip free_strip_linear free_strip_modal spatial_arm2_stiff
             spatial_arm2_rigid slender_tip_force slender_propped spin_up_cps8 spin_up_cps8_cb
             spin_up_cps8_linear free_strip_cps8 free_strip_cps8_linear)
  kanegen_add_model(kanegen_test_${stem} ${PROJECT_SOURCE_DIR}/tests/data/models/${stem}.json)
endforeach()
# The C3D20 tubes (1,700 dofs each) are left out of a sanitized build: their generation, dense
# eigenproblems run by the sanitized kanegen, took more than 6 minutes each under AddressSanitizer, and
# their tests (test_mesh_stiffening.cpp) run in the plain build. Under the sanitizers the same element
# and reduction code runs on smaller C3D20 meshes (tests/fem) and the CPS8 strips here.
if(NOT KANEGEN_SANITIZE)
  foreach(stem spin_up_c3d20 spin_up_c3d20_cb)
    kanegen_add_model(kanegen_test_${stem} ${PROJECT_SOURCE_DIR}/tests/data/models/${stem}.json)
  endforeach()
endif()
add_executable(test_flexible ${CMAKE_CURRENT_LIST_DIR}/test_spin_up.cpp
                             ${CMAKE_CURRENT_LIST_DIR}/test_node_bodies.cpp ${CMAKE_CURRENT_LIST_DIR}/test_energy.cpp
                             ${CMAKE_CURRENT_LIST_DIR}/test_spatial_nodes.cpp
                             ${CMAKE_CURRENT_LIST_DIR}/test_mesh_node_sets.cpp
                             ${CMAKE_CURRENT_LIST_DIR}/test_mesh_stiffening.cpp)
target_include_directories(test_flexible PRIVATE ${CMAKE_CURRENT_LIST_DIR}/../regression)
target_compile_options(test_flexible PRIVATE ${KANEGEN_WARNINGS})
target_link_libraries(test_flexible PRIVATE kanegen_model_spin_up_beam kanegen_model_spin_up_beam_linear
                                            kanegen_model_flexible_arm2 kanegen_test_flex_tip_mass
                                            kanegen_test_flex_tip_body kanegen_test_flex_tip_mass_linear
                                            kanegen_test_flex_tip_body_linear kanegen_test_spin_up_beam_e5
                                            kanegen_test_spin_up_beam_e20 kanegen_test_spin_up_beam_modal
                                            kanegen_test_free_strip kanegen_test_free_strip_linear
                                            kanegen_test_free_strip_modal kanegen_test_spatial_arm2_stiff
                                            kanegen_test_spatial_arm2_rigid kanegen_model_spatial_arm2
                                            kanegen_test_slender_tip_force kanegen_test_slender_propped
                                            kanegen_test_spin_up_cps8 kanegen_test_spin_up_cps8_cb
                                            kanegen_test_spin_up_cps8_linear kanegen_test_free_strip_cps8
                                            kanegen_test_free_strip_cps8_linear
                                            kanegen_catch_main Eigen3::Eigen)
if(KANEGEN_SANITIZE)
  target_compile_definitions(test_flexible PRIVATE KANEGEN_NO_C3D20_TUBES)
else()
  target_link_libraries(test_flexible PRIVATE kanegen_test_spin_up_c3d20 kanegen_test_spin_up_c3d20_cb)
endif()
catch_discover_tests(test_flexible TEST_PREFIX "flexible: ")
