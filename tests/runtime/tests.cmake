# SPDX-License-Identifier: GPL-2.0-or-later
# Runtime tests: the integrators (explicit and implicit) against analytic solutions, the CSV and
# text helpers, and the runner (run_model) in-process on a hand-written model.
find_package(nlohmann_json REQUIRED)
set(KANEGEN_RUNTIME_TEST_DIR ${CMAKE_CURRENT_LIST_DIR})
add_executable(test_runtime ${KANEGEN_RUNTIME_TEST_DIR}/integrators_test.cpp
                            ${KANEGEN_RUNTIME_TEST_DIR}/text_csv_test.cpp ${KANEGEN_RUNTIME_TEST_DIR}/driver_test.cpp
                            ${KANEGEN_RUNTIME_TEST_DIR}/options_test.cpp ${KANEGEN_RUNTIME_TEST_DIR}/implicit_test.cpp
                            ${KANEGEN_RUNTIME_TEST_DIR}/envelope_lu_test.cpp
                            ${KANEGEN_RUNTIME_TEST_DIR}/methods_test.cpp)
target_compile_options(test_runtime PRIVATE ${KANEGEN_WARNINGS})
# envelope_lu_test.cpp tests a header private to the runtime library.
target_include_directories(test_runtime PRIVATE ${PROJECT_SOURCE_DIR}/runtime/src)
# The embedded RK4 header must compile without exceptions, RTTI or the C++ library.
target_sources(test_runtime PRIVATE ${KANEGEN_RUNTIME_TEST_DIR}/embedded_rk4.cpp)
set_source_files_properties(${KANEGEN_RUNTIME_TEST_DIR}/embedded_rk4.cpp PROPERTIES COMPILE_OPTIONS
                            "-fno-exceptions;-fno-rtti;-nostdinc++")
target_link_libraries(test_runtime PRIVATE kanegen::runtime kanegen_catch_main nlohmann_json::nlohmann_json)
catch_discover_tests(test_runtime TEST_PREFIX "runtime: ")

# The generalized-alpha integrator on hand-written models with exact
# Jacobians; its own executable because it replaces the global operator new
# (to count allocations in step()).
# The sanitizers' allocator cannot share the process with a replaced
# operator new (ASan: alloc-dealloc-mismatch): the allocation count is
# checked in the plain build (CI's part 1) only.
set(KANEGEN_GENALPHA_TESTS ${KANEGEN_RUNTIME_TEST_DIR}/genalpha_test.cpp)
if(NOT KANEGEN_SANITIZE)
  list(APPEND KANEGEN_GENALPHA_TESTS ${KANEGEN_RUNTIME_TEST_DIR}/genalpha_alloc_test.cpp)
endif()
add_executable(test_runtime_genalpha ${KANEGEN_GENALPHA_TESTS})
target_compile_options(test_runtime_genalpha PRIVATE ${KANEGEN_WARNINGS})
target_link_libraries(test_runtime_genalpha PRIVATE kanegen::runtime kanegen_catch_main)
catch_discover_tests(test_runtime_genalpha TEST_PREFIX "runtime: ")
