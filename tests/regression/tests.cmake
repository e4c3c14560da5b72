# SPDX-License-Identifier: GPL-2.0-or-later
# Published and analytic reference problems, run on the shipped models.
find_package(Eigen3 REQUIRED NO_MODULE)
kanegen_add_model(kanegen_test_forced_cart_pendulum ${PROJECT_SOURCE_DIR}/tests/data/models/forced_cart_pendulum.json)
add_executable(test_regression ${CMAKE_CURRENT_LIST_DIR}/test_pendulum_period.cpp
                               ${CMAKE_CURRENT_LIST_DIR}/test_energy.cpp ${CMAKE_CURRENT_LIST_DIR}/test_mass_matrix.cpp
                               ${CMAKE_CURRENT_LIST_DIR}/test_forced_cart_pendulum.cpp)
target_compile_options(test_regression PRIVATE ${KANEGEN_WARNINGS})
target_link_libraries(test_regression PRIVATE kanegen_model_simple_pendulum kanegen_model_double_pendulum
                                              kanegen_model_arm7 kanegen_model_chain20
                                              kanegen_test_forced_cart_pendulum kanegen_catch_main Eigen3::Eigen)
catch_discover_tests(test_regression TEST_PREFIX "regression: ")

# The force elements (springs, joint efforts) on their own test models, in
# their own executable so that they build without the large shipped models.
foreach(name spring_oscillator spring_pendulum effort_rotor)
  kanegen_add_model(kanegen_test_${name} ${PROJECT_SOURCE_DIR}/tests/data/models/${name}.json)
endforeach()
add_executable(test_force_elements ${CMAKE_CURRENT_LIST_DIR}/test_force_elements.cpp)
target_compile_options(test_force_elements PRIVATE ${KANEGEN_WARNINGS})
target_link_libraries(test_force_elements PRIVATE kanegen_test_spring_oscillator kanegen_test_spring_pendulum
                                                  kanegen_test_effort_rotor kanegen_catch_main)
catch_discover_tests(test_force_elements TEST_PREFIX "regression: ")

# Planar joints (a compound type: two slides and a turn, model/joint_expansion.hpp)
# against the closed form of a body in a plane.
foreach(name planar_body planar_tilted)
  kanegen_add_model(kanegen_test_${name} ${PROJECT_SOURCE_DIR}/tests/data/models/${name}.json)
endforeach()
add_executable(test_planar_joint ${CMAKE_CURRENT_LIST_DIR}/test_planar_joint.cpp)
target_compile_options(test_planar_joint PRIVATE ${KANEGEN_WARNINGS})
target_link_libraries(test_planar_joint PRIVATE kanegen_test_planar_body kanegen_test_planar_tilted kanegen_catch_main)
catch_discover_tests(test_planar_joint TEST_PREFIX "regression: ")

# A spherical joint (quaternion coordinates, q_dot = N(q) u): a heavy
# symmetric top in steady precession, against its closed form.
kanegen_add_model(kanegen_test_spherical_top ${PROJECT_SOURCE_DIR}/tests/data/models/spherical_top.json)
add_executable(test_spherical_joint ${CMAKE_CURRENT_LIST_DIR}/test_spherical_joint.cpp)
target_compile_options(test_spherical_joint PRIVATE ${KANEGEN_WARNINGS})
target_link_libraries(test_spherical_joint PRIVATE kanegen_test_spherical_top kanegen_catch_main)
catch_discover_tests(test_spherical_joint TEST_PREFIX "regression: ")
