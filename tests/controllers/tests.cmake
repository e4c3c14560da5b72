# SPDX-License-Identifier: GPL-2.0-or-later
# The kernels for controllers (docs/controllers.md). inverse_dynamics and
# gravity, which every model has, on every shipped model; the quadratic
# kernels of --controller on a rigid spatial arm, a planar pendulum and a
# flexible arm, generated again with the option under their own targets,
# whose code must be as deterministic (golden_) and warning-free (strict_)
# as generated/'s.
add_executable(test_inverse_dynamics ${CMAKE_CURRENT_LIST_DIR}/test_inverse_dynamics.cpp)
target_compile_options(test_inverse_dynamics PRIVATE ${KANEGEN_WARNINGS})
set(KANEGEN_ALL_MODEL_TARGETS)
foreach(model ${KANEGEN_TEST_MODELS})
  get_filename_component(stem ${model} NAME_WE)
  if(stem IN_LIST KANEGEN_LARGE_MODELS)  # tests/CMakeLists.txt says why
    continue()
  endif()
  list(APPEND KANEGEN_ALL_MODEL_TARGETS kanegen_model_${stem})
endforeach()
target_link_libraries(test_inverse_dynamics PRIVATE ${KANEGEN_ALL_MODEL_TARGETS} kanegen_catch_main)
catch_discover_tests(test_inverse_dynamics TEST_PREFIX "controllers: ")

set(KANEGEN_CONTROLLER_MODELS arm7.urdf double_pendulum.json flexible_arm2.json)
find_program(KANEGEN_GXX g++)
find_program(KANEGEN_CLANGXX clang++)
set(KANEGEN_CONTROLLER_TARGETS)
foreach(file ${KANEGEN_CONTROLLER_MODELS})
  get_filename_component(stem ${file} NAME_WE)
  set(target kanegen_controller_${stem})
  set(dir ${CMAKE_CURRENT_BINARY_DIR}/kanegen_generated/${target})
  kanegen_add_model(${target} ${PROJECT_SOURCE_DIR}/models/${file} CONTROLLER)
  list(APPEND KANEGEN_CONTROLLER_TARGETS ${target})
  add_test(NAME golden_controller_${stem}
           COMMAND ${CMAKE_COMMAND} -DKANEGEN=$<TARGET_FILE:kanegen> -DMODEL=${PROJECT_SOURCE_DIR}/models/${file}
                   -DEXPECTED_DIR=${dir} -DSCRATCH=${CMAKE_CURRENT_BINARY_DIR}/golden_controller/${stem}
                   -DOPTIONS=--controller -P ${PROJECT_SOURCE_DIR}/tests/golden/check_generated.cmake)
  foreach(cxx ${KANEGEN_GXX} ${KANEGEN_CLANGXX})
    get_filename_component(cxx_name ${cxx} NAME)
    add_test(NAME strict_controller_${cxx_name}_${stem}
             COMMAND ${CMAKE_COMMAND} -DCXX=${cxx} -DDIR=${dir} -DNAME=${stem}
                     -DRUNTIME_INCLUDE=${PROJECT_SOURCE_DIR}/runtime/include
                     -P ${PROJECT_SOURCE_DIR}/tests/golden/compile_strict.cmake)
  endforeach()
endforeach()
add_executable(test_controller_kernels ${CMAKE_CURRENT_LIST_DIR}/test_controller_kernels.cpp)
target_compile_options(test_controller_kernels PRIVATE ${KANEGEN_WARNINGS})
target_link_libraries(test_controller_kernels PRIVATE ${KANEGEN_CONTROLLER_TARGETS} kanegen_catch_main)
catch_discover_tests(test_controller_kernels TEST_PREFIX "controllers: ")
