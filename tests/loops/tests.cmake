# SPDX-License-Identifier: GPL-2.0-or-later
# Closed loops (issue 4): the shipped loop models simulated through the
# runtime (assembly, projection, energy, exact and reference solutions), the
# generated constraint kernels against finite differences, and the command
# line's assembly and singular-configuration errors.
kanegen_add_model(kanegen_test_slider_crank_free ${PROJECT_SOURCE_DIR}/tests/data/models/slider_crank_free.json)
# The other loop types: spherical and spatial revolute (one linkage cut two
# ways), spatial slider (a rod through a ring), planar slider (quick return).
foreach(name rsur_spherical rsur_revolute ring_slider quick_return ring_slider_flexible)
  kanegen_add_model(kanegen_test_${name} ${PROJECT_SOURCE_DIR}/tests/data/models/${name}.json)
endforeach()
add_executable(test_loops ${CMAKE_CURRENT_LIST_DIR}/test_loops.cpp
                          ${CMAKE_CURRENT_LIST_DIR}/test_loop_kernels.cpp
                          ${CMAKE_CURRENT_LIST_DIR}/test_references.cpp
                          ${CMAKE_CURRENT_LIST_DIR}/test_spatial_loops.cpp
                          ${CMAKE_CURRENT_LIST_DIR}/test_saddle_solve.cpp
                          ${CMAKE_CURRENT_LIST_DIR}/test_solid_slider_crank.cpp)
target_include_directories(test_loops PRIVATE ${CMAKE_CURRENT_LIST_DIR}/../regression ${PROJECT_SOURCE_DIR}/templates)
target_compile_options(test_loops PRIVATE ${KANEGEN_WARNINGS})
target_link_libraries(test_loops PRIVATE kanegen_model_four_bar kanegen_model_slider_crank kanegen_model_nfourbar2
                                         kanegen_model_andrews_squeezer kanegen_model_simeon_crank kanegen_model_simeon_crank_fe
                                         kanegen_test_slider_crank_free kanegen_test_rsur_spherical
                                         kanegen_test_rsur_revolute kanegen_test_ring_slider kanegen_test_quick_return
                                         kanegen_test_ring_slider_flexible kanegen_model_nfourbar40
                                         kanegen_model_spatial_slider_crank kanegen_model_solid_slider_crank
                                         kanegen_runtime kanegen_catch_main)
catch_discover_tests(test_loops TEST_PREFIX "loops: ")

add_executable(test_loop_cli ${CMAKE_CURRENT_LIST_DIR}/test_loop_cli.cpp)
target_include_directories(test_loop_cli PRIVATE ${CMAKE_CURRENT_LIST_DIR}/../support)
target_compile_options(test_loop_cli PRIVATE ${KANEGEN_WARNINGS})
target_compile_definitions(test_loop_cli PRIVATE KANEGEN_EXE="$<TARGET_FILE:kanegen>"
                                                 KANEGEN_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
                                                 KANEGEN_CACHE="${CMAKE_CURRENT_BINARY_DIR}/loops_cache"
                                                 KANEGEN_SCRATCH_DIR="${CMAKE_CURRENT_BINARY_DIR}/loops_scratch")
target_link_libraries(test_loop_cli PRIVATE kanegen_catch_main)
add_dependencies(test_loop_cli kanegen kanegen_runtime)
catch_discover_tests(test_loop_cli TEST_PREFIX "loops cli: ")

# models/nfourbar40.json is the committed output of scripts/make_nfourbar.py.
find_package(Python3 COMPONENTS Interpreter QUIET)
if(Python3_Interpreter_FOUND)
  add_test(NAME loops:nfourbar40_is_up_to_date COMMAND ${Python3_EXECUTABLE}
                                                      ${PROJECT_SOURCE_DIR}/scripts/make_nfourbar.py --check)
endif()
