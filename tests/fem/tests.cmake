# SPDX-License-Identifier: GPL-2.0-or-later
# The finite-element layer (generator/fem) on its own: beam elements, assembly,
# inertia invariants, modal reduction and the rotating beam, against closed
# forms, a published table and CalculiX results kept in data/. It links the
# finite-element layer alone (Eigen and the model, no GiNaC), so this suite
# does not wait for the symbolic stages.
file(GLOB KANEGEN_FEM_TEST_SOURCES CONFIGURE_DEPENDS ${CMAKE_CURRENT_LIST_DIR}/*.cpp)
add_executable(test_fem ${KANEGEN_FEM_TEST_SOURCES})
target_compile_options(test_fem PRIVATE ${KANEGEN_WARNINGS})
target_compile_definitions(test_fem PRIVATE KANEGEN_FEM_DATA_DIR="${CMAKE_CURRENT_LIST_DIR}/data"
                                            KANEGEN_MODELS_DIR="${PROJECT_SOURCE_DIR}/models")
target_link_libraries(test_fem PRIVATE kanegen_fem kanegen_catch_main)
catch_discover_tests(test_fem TEST_PREFIX "fem: ")
