# SPDX-License-Identifier: GPL-2.0-or-later
# kanegen verify: the numeric derivation against closed forms, the runner's
# batch protocol, the command line (JSON report, corruption tests), and
# verify itself on every shipped model. Runners are cached under the build
# tree (KANEGEN_CACHE_DIR), not in the user's cache.
find_package(nlohmann_json REQUIRED)
set(KANEGEN_VERIFY_CACHE ${CMAKE_CURRENT_BINARY_DIR}/verify_cache)

add_executable(test_verify_unit ${CMAKE_CURRENT_LIST_DIR}/numeric_test.cpp
                                ${CMAKE_CURRENT_LIST_DIR}/numeric_flexible_test.cpp
                                ${CMAKE_CURRENT_LIST_DIR}/batch_test.cpp)
target_compile_options(test_verify_unit PRIVATE ${KANEGEN_WARNINGS})
target_compile_definitions(test_verify_unit PRIVATE KANEGEN_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
target_link_libraries(test_verify_unit PRIVATE kanegen_numeric kanegen_model_simple_pendulum kanegen_catch_main
                                               nlohmann_json::nlohmann_json)
catch_discover_tests(test_verify_unit TEST_PREFIX "verify: ")

add_executable(test_verify_cli ${CMAKE_CURRENT_LIST_DIR}/verify_cli_test.cpp)
target_compile_options(test_verify_cli PRIVATE ${KANEGEN_WARNINGS})
target_compile_definitions(test_verify_cli PRIVATE KANEGEN_EXE="$<TARGET_FILE:kanegen>"
                                                   KANEGEN_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
                                                   KANEGEN_CACHE="${KANEGEN_VERIFY_CACHE}"
                                                   KANEGEN_SCRATCH_DIR="${CMAKE_CURRENT_BINARY_DIR}/verify_scratch")
target_link_libraries(test_verify_cli PRIVATE kanegen_catch_main nlohmann_json::nlohmann_json)
add_dependencies(test_verify_cli kanegen kanegen_runtime)
catch_discover_tests(test_verify_cli TEST_PREFIX "verify: ")

# kanegen verify on every shipped model, on the forced cart pendulum
# (prismatic joint, spring, damper, world and body forces) and on the
# flexible test models: a planar strip on a hub (nodal; modal with modal
# damping), a spatial beam on a gimbal, a prescribed hub with a free pendulum,
# a body on a beam tip node (its pull in the geometric stiffness); the force
# elements: springs between links and to the ground, joint efforts in t, on a
# rigid chain and on a beam (a spring on its tip body pulls on the node);
# assumed modes on a planar hub arm with a pendulum on its tip and on the
# spatial gimbal; the loop types the shipped linkages do not use (spherical,
# spatial revolute, spatial and planar slider); geometric stiffening in free
# motion (issue 12): the free pendulum in nodal and modal coordinates, an
# L-shaped nodal beam, a modal column under an axial node force; loops on the
# nodes of spatial beams (a spatial revolute, a slider); loops, forces and
# outputs on the node sets of mesh bodies (a CPS4 four-bar with a planar
# revolute and slider, a C3D8 bar with a spatial revolute, slider and
# spherical joint, a C3D10 bar with an arm on its tip face; the tip-force
# case of tests/flexible. Its propped twin, slender_propped, is left out: a stiff bar pinned at both ends, whose small
# prop force in random states is the difference of elastic forces 1e3 times
# larger, so that lambda agrees only to about 2e-9); planar joints (a body
# across z, one on an oblique, turned plane, a pendulum on a planar cart); a
# top on a spherical joint.
file(GLOB KANEGEN_VERIFY_MODELS CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/models/*.json ${PROJECT_SOURCE_DIR}/models/*.urdf)
foreach(name forced_cart_pendulum flex_hub_planar flex_hub_modal flex_spatial_hub flex_prescribed_hub flex_tip_body
             force_elements flex_spring assumed_hub assumed_spatial_hub rsur_spherical rsur_revolute ring_slider
             quick_return free_strip free_strip_modal l_beam_stiffened euler_column_modal
             rsur_revolute_flexible ring_slider_flexible plate_tip_pendulum
             plate_tip_cb plate_node_set_loops tip_bar_loops tip_bar_c3d10 slender_tip_force solid_slider_crank_stiff
             matrix_bar_hub
             planar_body planar_tilted planar_pendulum spherical_top)
  list(APPEND KANEGEN_VERIFY_MODELS ${PROJECT_SOURCE_DIR}/tests/data/models/${name}.json)
endforeach()
# Spherical and free joints (quaternions; the numeric path's rotation vectors
# from a random base quaternion, numeric/spherical.hpp), the twins of MuJoCo's
# ball and free joints in tests/consistency.
foreach(name ball_chain free_body)
  list(APPEND KANEGEN_VERIFY_MODELS ${PROJECT_SOURCE_DIR}/tests/consistency/data/${name}.json)
endforeach()
# Fewer samples where the numeric path's quadrature is slow: the solid rod's 28 C3D20 elements take
# 0.5 s per sample (100 samples and 3 trajectories: 70 s on 2 loaded cores; 30 and 1: about 25 s).
set(KANEGEN_VERIFY_OPTIONS_solid_slider_crank --samples 30 --trajectories 1)
# The same rod with stiffening, its elastic mass to second order (docs/flexible-bodies.md): M against
# the numeric path's own second-order terms and positive definite. Its kernels take about 60 s to
# compile, and a power-balance trajectory 90 s more (it passes, 1.9e-11; the free CPS8 pendulum of
# tests/flexible checks T + V of a Craig-Bampton body with stiffening), so none here.
set(KANEGEN_VERIFY_OPTIONS_solid_slider_crank_stiff --samples 30 --trajectories 0)
foreach(model ${KANEGEN_VERIFY_MODELS})
  get_filename_component(stem ${model} NAME_WE)
  if(stem IN_LIST KANEGEN_LARGE_MODELS)  # tests/CMakeLists.txt says why
    continue()
  endif()
  add_test(NAME "verify: model ${stem}" COMMAND kanegen verify ${model} ${KANEGEN_VERIFY_OPTIONS_${stem}})
  set_tests_properties("verify: model ${stem}" PROPERTIES ENVIRONMENT "KANEGEN_CACHE_DIR=${KANEGEN_VERIFY_CACHE}")
endforeach()
# The longest (a minute or more on 2 cores, mostly compiling their runners) start first under ctest -j,
# so that none of them is left running alone at the end (ctest runs the costliest first).
foreach(stem nfourbar40 l_frame solid_slider_crank solid_slider_crank_stiff chain20 spatial_arm2)
  if(TEST "verify: model ${stem}")
    set_tests_properties("verify: model ${stem}" PROPERTIES COST 60)
  endif()
endforeach()

# The planar joints' steps (a slide, a slide and a turn, with massless frames
# between them) by the articulated-body recursion, which auto does not pick
# for these small models.
add_test(NAME "verify: model planar_pendulum --dynamics recursive"
         COMMAND kanegen verify ${PROJECT_SOURCE_DIR}/tests/data/models/planar_pendulum.json --dynamics recursive)

# The controller kernels of a rigid tree from the recursion (docs/controllers.md):
# forcing_jacobian, d(M a)/dq where smaller, coriolis_matrix from the part of the
# inverse dynamics even in u (which the chain's dampers must not reach), linearize.
add_test(NAME "verify: model damped_chain8 --controller"
         COMMAND kanegen verify ${PROJECT_SOURCE_DIR}/tests/data/models/damped_chain8.urdf --controller)
set_tests_properties("verify: model damped_chain8 --controller"
                     PROPERTIES ENVIRONMENT "KANEGEN_CACHE_DIR=${KANEGEN_VERIFY_CACHE}")

# The recursive forward_dynamics (auto keeps the composite solve on this
# small model): a slide, hinges, springs between points, efforts, a point force.
add_test(NAME "verify: model force_elements --dynamics recursive"
         COMMAND kanegen verify ${PROJECT_SOURCE_DIR}/tests/data/models/force_elements.json --dynamics recursive)
set_tests_properties("verify: model force_elements --dynamics recursive"
                     PROPERTIES ENVIRONMENT "KANEGEN_CACHE_DIR=${KANEGEN_VERIFY_CACHE}")

add_test(NAME "verify: the numeric path shares no code with the symbolic one"
         COMMAND ${CMAKE_COMMAND} -DDIR=${PROJECT_SOURCE_DIR}/generator -P ${CMAKE_CURRENT_LIST_DIR}/check_independence.cmake)
