# SPDX-License-Identifier: GPL-2.0-or-later
# MuJoCo consistency tests: the generated kernels of the shipped URDF models
# against MuJoCo (libmujoco-dev), plus checks of the MuJoCo reference itself
# against closed forms. Included from tests/CMakeLists.txt (Catch2 is found).
if(KANEGEN_WITH_MUJOCO)
  include(${PROJECT_SOURCE_DIR}/cmake/KanegenFindMujoco.cmake)
  kanegen_find_mujoco()
  if(NOT mujoco_FOUND)
    message(STATUS "kanegen: MuJoCo not found, no consistency tests (install libmujoco-dev)")
  else()
    find_package(Eigen3 REQUIRED NO_MODULE)
    find_package(PkgConfig REQUIRED)
    pkg_check_modules(KANEGEN_CONSISTENCY_TINYXML2 REQUIRED IMPORTED_TARGET tinyxml2)

    set(_kg_cons_dir ${CMAKE_CURRENT_LIST_DIR})
    add_executable(test_consistency ${_kg_cons_dir}/test_mujoco.cpp
                                    ${_kg_cons_dir}/test_mujoco_spherical.cpp
                                    ${_kg_cons_dir}/mujoco_reference.cpp)
    target_include_directories(test_consistency PRIVATE ${_kg_cons_dir})
    target_compile_options(test_consistency PRIVATE ${KANEGEN_WARNINGS})
    target_compile_definitions(test_consistency PRIVATE
      KANEGEN_ARM7_URDF="${PROJECT_SOURCE_DIR}/models/arm7.urdf"
      KANEGEN_CHAIN20_URDF="${PROJECT_SOURCE_DIR}/models/chain20.urdf"
      KANEGEN_MIXED_TREE_URDF="${_kg_cons_dir}/data/mixed_tree.urdf"
      KANEGEN_CONSISTENCY_DATA_DIR="${_kg_cons_dir}/data")
    target_link_libraries(test_consistency PRIVATE mujoco::mujoco kanegen_catch_main Eigen3::Eigen
                                                   PkgConfig::KANEGEN_CONSISTENCY_TINYXML2)

    if(COMMAND kanegen_add_model)
      # kanegen_model_<stem> of every shipped model is defined in tests/CMakeLists.txt.
      foreach(_kg_model arm7 chain20)
        if(NOT TARGET kanegen_model_${_kg_model})
          kanegen_add_model(kanegen_model_${_kg_model} ${PROJECT_SOURCE_DIR}/models/${_kg_model}.urdf)
        endif()
      endforeach()
      # A branched tree with slides and turned frames, by the articulated-body recursion.
      kanegen_add_model(kanegen_model_mixed_tree ${_kg_cons_dir}/data/mixed_tree.urdf DYNAMICS recursive)
      # Spherical and free joints (quaternions), with their MJCF twins.
      kanegen_add_model(kanegen_model_ball_chain ${_kg_cons_dir}/data/ball_chain.json)
      kanegen_add_model(kanegen_model_free_body ${_kg_cons_dir}/data/free_body.json)
      target_link_libraries(test_consistency PRIVATE kanegen_model_arm7 kanegen_model_chain20
                                                     kanegen_model_mixed_tree kanegen_model_ball_chain
                                                     kanegen_model_free_body)
      target_compile_definitions(test_consistency PRIVATE KANEGEN_HAVE_GENERATED_MODELS=1)
    else()
      message(WARNING "kanegen: kanegen_add_model() is not defined; test_consistency checks MuJoCo only")
      target_compile_definitions(test_consistency PRIVATE KANEGEN_HAVE_GENERATED_MODELS=0)
    endif()

    catch_discover_tests(test_consistency TEST_PREFIX "consistency/")
  endif()
endif()

# models/chain20.urdf is the committed output of scripts/make_chain_urdf.py.
find_package(Python3 COMPONENTS Interpreter QUIET)
if(Python3_Interpreter_FOUND)
  add_test(NAME consistency/chain20_urdf_is_up_to_date
           COMMAND ${Python3_EXECUTABLE} ${PROJECT_SOURCE_DIR}/scripts/make_chain_urdf.py --check
                   -o ${PROJECT_SOURCE_DIR}/models/chain20.urdf)
endif()
