# SPDX-License-Identifier: GPL-2.0-or-later
# The Jacobian kernels (kanegen generate --jacobians) against central
# differences of the kernels they differentiate, on rigid trees, a flexible
# body with geometric stiffening on a prescribed hub, and closed loops (one
# flexible and prescribed). The models are generated again with the option,
# under their own targets; their code must be as deterministic (golden_) and
# warning-free (strict_) as generated/'s.
set(KANEGEN_JACOBIAN_MODELS double_pendulum.json arm7.urdf spin_up_beam.json slider_crank.json simeon_crank_fe.json)
find_program(KANEGEN_GXX g++)
find_program(KANEGEN_CLANGXX clang++)
set(KANEGEN_JACOBIAN_TARGETS)
foreach(file ${KANEGEN_JACOBIAN_MODELS})
  get_filename_component(stem ${file} NAME_WE)  # each file's stem is its model's name
  set(target kanegen_jacobians_${stem})
  set(dir ${CMAKE_CURRENT_BINARY_DIR}/kanegen_generated/${target})
  kanegen_add_model(${target} ${PROJECT_SOURCE_DIR}/models/${file} JACOBIANS)
  list(APPEND KANEGEN_JACOBIAN_TARGETS ${target})
  add_test(NAME golden_jacobians_${stem}
           COMMAND ${CMAKE_COMMAND} -DKANEGEN=$<TARGET_FILE:kanegen> -DMODEL=${PROJECT_SOURCE_DIR}/models/${file}
                   -DEXPECTED_DIR=${dir} -DSCRATCH=${CMAKE_CURRENT_BINARY_DIR}/golden_jacobians/${stem}
                   -DOPTIONS=--jacobians -P ${PROJECT_SOURCE_DIR}/tests/golden/check_generated.cmake)
  foreach(cxx ${KANEGEN_GXX} ${KANEGEN_CLANGXX})
    get_filename_component(cxx_name ${cxx} NAME)
    add_test(NAME strict_jacobians_${cxx_name}_${stem}
             COMMAND ${CMAKE_COMMAND} -DCXX=${cxx} -DDIR=${dir} -DNAME=${stem}
                     -DRUNTIME_INCLUDE=${PROJECT_SOURCE_DIR}/runtime/include
                     -P ${PROJECT_SOURCE_DIR}/tests/golden/compile_strict.cmake)
  endforeach()
endforeach()
add_executable(test_jacobians ${CMAKE_CURRENT_LIST_DIR}/test_jacobians.cpp)
target_compile_options(test_jacobians PRIVATE ${KANEGEN_WARNINGS})
target_link_libraries(test_jacobians PRIVATE ${KANEGEN_JACOBIAN_TARGETS} kanegen_model_four_bar kanegen_catch_main)
catch_discover_tests(test_jacobians TEST_PREFIX "jacobians: ")
