# SPDX-License-Identifier: GPL-2.0-or-later
# The finite-element layer (generator/fem) on its own: beam elements, assembly,
# inertia invariants, modal reduction and the rotating beam, against closed
# forms, a published table and CalculiX results kept in data/. The fem sources
# are compiled in directly (Eigen only, no GiNaC), so this suite does not wait
# for the rest of the generator.
find_package(Eigen3 REQUIRED NO_MODULE)
file(GLOB KANEGEN_FEM_SOURCES CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/generator/fem/*.cpp)
# The bridge from the model file (assumed modes are GiNaC expressions) stays out.
list(FILTER KANEGEN_FEM_SOURCES EXCLUDE REGEX "/(assumed_modes|model_beam)\\.cpp$")
file(GLOB KANEGEN_FEM_TEST_SOURCES CONFIGURE_DEPENDS ${CMAKE_CURRENT_LIST_DIR}/*.cpp)
add_executable(test_fem ${KANEGEN_FEM_TEST_SOURCES} ${KANEGEN_FEM_SOURCES})
target_include_directories(test_fem PRIVATE ${PROJECT_SOURCE_DIR}/generator)
target_compile_options(test_fem PRIVATE ${KANEGEN_WARNINGS})
target_compile_definitions(test_fem PRIVATE KANEGEN_FEM_DATA_DIR="${CMAKE_CURRENT_LIST_DIR}/data")
target_link_libraries(test_fem PRIVATE Eigen3::Eigen Catch2::Catch2)
catch_discover_tests(test_fem TEST_PREFIX "fem: ")
