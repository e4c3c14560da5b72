# SPDX-License-Identifier: GPL-2.0-or-later
# bench_pinocchio (included from bench/CMakeLists.txt when KANEGEN_PINOCCHIO_DIR is set).
find_package(Boost QUIET)
find_package(Python3 QUIET COMPONENTS Interpreter)
if(NOT Boost_FOUND OR NOT Python3_FOUND)
  message(STATUS "kanegen: no bench_pinocchio (needs the Boost headers, libboost-dev, and python3)")
  return()
endif()
message(STATUS "kanegen: bench_pinocchio with Pinocchio from ${KANEGEN_PINOCCHIO_DIR}")

# The chains of 7, 50 and 100 links, written by scripts/make_chain_urdf.py at
# configure time (kanegen_add_model reads the model's name when configuring);
# chain20 is the shipped one.
set(_kg_pin_urdfs)
foreach(_kg_links 7 50 100)
  set(_kg_urdf ${CMAKE_CURRENT_BINARY_DIR}/chain${_kg_links}.urdf)
  execute_process(COMMAND ${Python3_EXECUTABLE} ${PROJECT_SOURCE_DIR}/scripts/make_chain_urdf.py --links ${_kg_links}
                          -o ${_kg_urdf} RESULT_VARIABLE _kg_rc OUTPUT_QUIET)
  if(NOT _kg_rc EQUAL 0)
    message(FATAL_ERROR "bench_pinocchio: make_chain_urdf.py --links ${_kg_links} failed")
  endif()
endforeach()

# arm7 and chain7 with the controller kernels (linearize); the longer chains
# without: their exact Jacobian kernels do not compile in reasonable time yet
# (issue 37).
kanegen_add_model(kanegen_pin_arm7 ${PROJECT_SOURCE_DIR}/models/arm7.urdf CONTROLLER)
kanegen_add_model(kanegen_pin_chain7 ${CMAKE_CURRENT_BINARY_DIR}/chain7.urdf CONTROLLER)
if(NOT TARGET kanegen_model_chain20)
  kanegen_add_model(kanegen_model_chain20 ${PROJECT_SOURCE_DIR}/models/chain20.urdf)
endif()
kanegen_add_model(kanegen_pin_chain50 ${CMAKE_CURRENT_BINARY_DIR}/chain50.urdf)
kanegen_add_model(kanegen_pin_chain100 ${CMAKE_CURRENT_BINARY_DIR}/chain100.urdf)

# Pinocchio's side in its own translation unit: its headers take minutes.
# A source tree has no config.hpp, deprecated.hpp, warning.hpp (Pinocchio's
# CMake generates them); bench/pinocchio/include has header-only stand-ins.
add_library(bench_pinocchio_peer STATIC pinocchio_peer.cpp)
if(NOT EXISTS ${KANEGEN_PINOCCHIO_DIR}/include/pinocchio/config.hpp)
  target_include_directories(bench_pinocchio_peer SYSTEM BEFORE PRIVATE ${CMAKE_CURRENT_SOURCE_DIR}/pinocchio/include)
endif()
target_include_directories(bench_pinocchio_peer SYSTEM PRIVATE ${KANEGEN_PINOCCHIO_DIR}/include ${Boost_INCLUDE_DIRS})
target_compile_options(bench_pinocchio_peer PRIVATE ${KANEGEN_WARNINGS})
target_link_libraries(bench_pinocchio_peer PUBLIC kanegen_model PRIVATE Eigen3::Eigen)

add_executable(bench_pinocchio bench_pinocchio.cpp)
target_compile_options(bench_pinocchio PRIVATE ${KANEGEN_WARNINGS})
target_compile_definitions(
  bench_pinocchio PRIVATE KANEGEN_ARM7_URDF="${PROJECT_SOURCE_DIR}/models/arm7.urdf"
                          KANEGEN_CHAIN7_URDF="${CMAKE_CURRENT_BINARY_DIR}/chain7.urdf"
                          KANEGEN_CHAIN20_URDF="${PROJECT_SOURCE_DIR}/models/chain20.urdf"
                          KANEGEN_CHAIN50_URDF="${CMAKE_CURRENT_BINARY_DIR}/chain50.urdf"
                          KANEGEN_CHAIN100_URDF="${CMAKE_CURRENT_BINARY_DIR}/chain100.urdf")
target_link_libraries(bench_pinocchio PRIVATE bench_pinocchio_peer kanegen_pin_arm7 kanegen_pin_chain7
                                              kanegen_model_chain20 kanegen_pin_chain50 kanegen_pin_chain100)
