# SPDX-License-Identifier: GPL-2.0-or-later
# Golden files: generated/<model>/ must be exactly what kanegen generates now
# from models/, and compile warning-free under g++ and clang++.
file(GLOB KANEGEN_SHIPPED_MODELS CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/models/*.json ${PROJECT_SOURCE_DIR}/models/*.urdf)
find_program(KANEGEN_GXX g++)
find_program(KANEGEN_CLANGXX clang++)
foreach(model ${KANEGEN_SHIPPED_MODELS})
  get_filename_component(stem ${model} NAME_WE)
  if(stem IN_LIST KANEGEN_LARGE_MODELS)  # tests/CMakeLists.txt says why
    continue()
  endif()
  add_test(NAME golden_${stem}
           COMMAND ${CMAKE_COMMAND} -DKANEGEN=$<TARGET_FILE:kanegen> -DMODEL=${model}
                   -DEXPECTED_DIR=${PROJECT_SOURCE_DIR}/generated/${stem}
                   -DSCRATCH=${CMAKE_CURRENT_BINARY_DIR}/golden/${stem} -P ${CMAKE_CURRENT_LIST_DIR}/check_generated.cmake)
  foreach(cxx ${KANEGEN_GXX} ${KANEGEN_CLANGXX})
    get_filename_component(cxx_name ${cxx} NAME)
    add_test(NAME strict_${cxx_name}_${stem}
             COMMAND ${CMAKE_COMMAND} -DCXX=${cxx} -DDIR=${PROJECT_SOURCE_DIR}/generated/${stem} -DNAME=${stem}
                     -DRUNTIME_INCLUDE=${PROJECT_SOURCE_DIR}/runtime/include
                     -P ${CMAKE_CURRENT_LIST_DIR}/compile_strict.cmake)
  endforeach()
endforeach()
