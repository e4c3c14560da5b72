# SPDX-License-Identifier: GPL-2.0-or-later
# Embedded use (docs/embedded.md): float kernels against double, the emitted
# code and rk4.hpp compiled freestanding, and the arm7 controller of
# examples/embedded on the host and, when the toolchain is installed, as
# Cortex-M4F firmware under QEMU.
set(KANEGEN_EMBEDDED_DIR ${CMAKE_CURRENT_LIST_DIR})
set(KANEGEN_EXAMPLE_DIR ${PROJECT_SOURCE_DIR}/examples/embedded)

# Every shipped rigid model in float, the open trees and those with loops.
set(KANEGEN_RIGID_MODELS simple_pendulum.json double_pendulum.json arm7.urdf chain20.urdf four_bar.json
                         slider_crank.json nfourbar2.json nfourbar40.json andrews_squeezer.json)
add_executable(test_float_accuracy ${KANEGEN_EMBEDDED_DIR}/float_accuracy_test.cpp)
target_compile_options(test_float_accuracy PRIVATE ${KANEGEN_WARNINGS})
target_include_directories(test_float_accuracy PRIVATE ${PROJECT_SOURCE_DIR}/runtime/include)
foreach(file ${KANEGEN_RIGID_MODELS})
  get_filename_component(stem ${file} NAME_WE)
  kanegen_add_model(kanegen_model_${stem}_float ${PROJECT_SOURCE_DIR}/models/${file} PRECISION float)
  target_link_libraries(test_float_accuracy PRIVATE kanegen_model_${stem} kanegen_model_${stem}_float)
endforeach()
target_link_libraries(test_float_accuracy PRIVATE kanegen_catch_main)
# nfourbar40's 80 loop equations make a 680 kB source that g++ -O3 takes
# minutes over; unoptimized it compiles in seconds and rounds the same (SSE
# arithmetic, no contraction into FMA on x86-64's baseline), and the test
# evaluates it only a few hundred times.
target_compile_options(kanegen_model_nfourbar40_float PRIVATE -O0)
add_test(NAME embedded_float_accuracy COMMAND test_float_accuracy)

# Freestanding: shipped double models (an open tree; one with parameters;
# one with loops and loop-force outputs), the float arm7 and slider_crank
# (loops, loop-force outputs and a prescribed motion), arm7 with its kernels
# split into functions (tests/codegen: arm7_split, double and float), and rk4.hpp.
set(KANEGEN_ARM7_FLOAT_DIR ${CMAKE_CURRENT_BINARY_DIR}/kanegen_generated/kanegen_model_arm7_float)
set(KANEGEN_ARM7_SPLIT_DIR ${CMAKE_CURRENT_BINARY_DIR}/kanegen_generated/kanegen_model_arm7_split)
set(KANEGEN_ARM7_SPLIT_FLOAT_DIR ${CMAKE_CURRENT_BINARY_DIR}/kanegen_generated/kanegen_model_arm7_split_float)
set(KANEGEN_SLIDER_CRANK_FLOAT_DIR ${CMAKE_CURRENT_BINARY_DIR}/kanegen_generated/kanegen_model_slider_crank_float)
find_program(KANEGEN_GXX g++)
find_program(KANEGEN_CLANGXX clang++)
find_program(KANEGEN_NM nm)
foreach(cxx ${KANEGEN_GXX} ${KANEGEN_CLANGXX})
  get_filename_component(cxx_name ${cxx} NAME)
  add_test(NAME embedded_freestanding_${cxx_name}
           COMMAND ${CMAKE_COMMAND} -DCXX=${cxx} -DNM=${KANEGEN_NM}
                   "-DSOURCES=${PROJECT_SOURCE_DIR}/generated/arm7/arm7.cpp|${PROJECT_SOURCE_DIR}/generated/double_pendulum/double_pendulum.cpp|${PROJECT_SOURCE_DIR}/generated/slider_crank/slider_crank.cpp|${KANEGEN_ARM7_FLOAT_DIR}/arm7_float.cpp|${KANEGEN_SLIDER_CRANK_FLOAT_DIR}/slider_crank_float.cpp|${KANEGEN_ARM7_SPLIT_DIR}/arm7_split.cpp|${KANEGEN_ARM7_SPLIT_FLOAT_DIR}/arm7_split_float.cpp|${KANEGEN_EMBEDDED_DIR}/freestanding_rk4.cpp"
                   "-DINCLUDES=${PROJECT_SOURCE_DIR}/generated/arm7|${PROJECT_SOURCE_DIR}/generated/double_pendulum|${PROJECT_SOURCE_DIR}/generated/slider_crank|${KANEGEN_ARM7_FLOAT_DIR}|${KANEGEN_SLIDER_CRANK_FLOAT_DIR}|${KANEGEN_ARM7_SPLIT_DIR}|${KANEGEN_ARM7_SPLIT_FLOAT_DIR}|${PROJECT_SOURCE_DIR}/runtime/include"
                   -DSCRATCH=${CMAKE_CURRENT_BINARY_DIR}/freestanding/${cxx_name}
                   -P ${KANEGEN_EMBEDDED_DIR}/freestanding.cmake)
  set_tests_properties(embedded_freestanding_${cxx_name} PROPERTIES DEPENDS
                       "kanegen_model_arm7_float;kanegen_model_slider_crank_float;kanegen_model_arm7_split;kanegen_model_arm7_split_float")
endforeach()

# The example on the host (built always) ...
add_executable(embedded_arm7_host ${KANEGEN_EXAMPLE_DIR}/host_main.cpp ${KANEGEN_EXAMPLE_DIR}/arm7_tracking.cpp)
target_compile_options(embedded_arm7_host PRIVATE ${KANEGEN_WARNINGS} -Wdouble-promotion)
target_link_libraries(embedded_arm7_host PRIVATE kanegen_model_arm7_float)
target_include_directories(embedded_arm7_host PRIVATE ${PROJECT_SOURCE_DIR}/runtime/include)
add_test(NAME embedded_arm7_host COMMAND embedded_arm7_host)
set_tests_properties(embedded_arm7_host PROPERTIES PASS_REGULAR_EXPRESSION "tracking error max .* failed steps 0")

# ... and on a Cortex-M4F (gcc-arm-none-eabi, libnewlib-arm-none-eabi,
# qemu-system-arm), skipped (not passed) where they are missing.
find_program(KANEGEN_ARM_GCC arm-none-eabi-gcc)
find_program(KANEGEN_ARM_GXX arm-none-eabi-g++)
find_program(KANEGEN_ARM_SIZE arm-none-eabi-size)
find_program(KANEGEN_QEMU_ARM qemu-system-arm)
set(KANEGEN_ARM_NEWLIB OFF)
if(KANEGEN_ARM_GCC)
  execute_process(COMMAND ${KANEGEN_ARM_GCC} -print-file-name=rdimon.specs OUTPUT_VARIABLE specs
                  OUTPUT_STRIP_TRAILING_WHITESPACE)
  if(IS_ABSOLUTE "${specs}" AND EXISTS "${specs}")
    set(KANEGEN_ARM_NEWLIB ON)
  endif()
endif()
if(KANEGEN_ARM_GCC AND KANEGEN_ARM_GXX AND KANEGEN_ARM_SIZE AND KANEGEN_ARM_NEWLIB AND KANEGEN_QEMU_ARM)
  set(fw ${CMAKE_CURRENT_BINARY_DIR}/embedded_firmware)
  set(arm_flags -mcpu=cortex-m4 -mthumb -mfpu=fpv4-sp-d16 -mfloat-abi=hard -O2 -ffunction-sections
                -fdata-sections -Wall -Wextra -Werror -Wdouble-promotion)
  set(arm_cxx ${KANEGEN_ARM_GXX} ${arm_flags} -std=c++17 -Wpedantic -fno-exceptions -fno-rtti
              -I${KANEGEN_ARM7_FLOAT_DIR} -I${PROJECT_SOURCE_DIR}/runtime/include)
  add_custom_command(
    OUTPUT ${fw}/arm7_tracking.elf ${fw}/arm7_float.o
    COMMAND ${CMAKE_COMMAND} -E make_directory ${fw}
    COMMAND ${arm_cxx} -c ${KANEGEN_ARM7_FLOAT_DIR}/arm7_float.cpp -o ${fw}/arm7_float.o
    COMMAND ${arm_cxx} -c ${KANEGEN_EXAMPLE_DIR}/arm7_tracking.cpp -o ${fw}/arm7_tracking.o
    COMMAND ${arm_cxx} -c ${KANEGEN_EXAMPLE_DIR}/firmware/main.cpp -o ${fw}/main.o
    COMMAND ${KANEGEN_ARM_GCC} ${arm_flags} -c ${KANEGEN_EXAMPLE_DIR}/firmware/startup.c -o ${fw}/startup.o
    COMMAND ${KANEGEN_ARM_GCC} ${arm_flags} -nostartfiles --specs=rdimon.specs
            -T ${KANEGEN_EXAMPLE_DIR}/firmware/mps2_an386.ld -Wl,--gc-sections ${fw}/startup.o ${fw}/main.o
            ${fw}/arm7_tracking.o ${fw}/arm7_float.o -lm -o ${fw}/arm7_tracking.elf
    DEPENDS ${KANEGEN_ARM7_FLOAT_DIR}/arm7_float.cpp ${KANEGEN_ARM7_FLOAT_DIR}/arm7_float.hpp
            ${KANEGEN_EXAMPLE_DIR}/arm7_tracking.cpp ${KANEGEN_EXAMPLE_DIR}/arm7_tracking.hpp
            ${KANEGEN_EXAMPLE_DIR}/report.hpp ${KANEGEN_EXAMPLE_DIR}/firmware/main.cpp
            ${KANEGEN_EXAMPLE_DIR}/firmware/startup.c ${KANEGEN_EXAMPLE_DIR}/firmware/mps2_an386.ld
            ${PROJECT_SOURCE_DIR}/runtime/include/kanegen/runtime/rk4.hpp
    COMMENT "arm-none-eabi: the arm7 tracking firmware for a Cortex-M4F"
    VERBATIM)
  add_custom_target(embedded_arm7_firmware ALL DEPENDS ${fw}/arm7_tracking.elf)
  add_test(NAME embedded_arm7_cortex_m4
           COMMAND ${CMAKE_COMMAND} -DHOST=$<TARGET_FILE:embedded_arm7_host> -DQEMU=${KANEGEN_QEMU_ARM}
                   -DFIRMWARE=${fw}/arm7_tracking.elf -DKERNELS_OBJECT=${fw}/arm7_float.o -DSIZE=${KANEGEN_ARM_SIZE}
                   -DSCRATCH=${fw} -P ${KANEGEN_EMBEDDED_DIR}/compare_runs.cmake)
else()
  add_test(NAME embedded_arm7_cortex_m4
           COMMAND ${CMAKE_COMMAND} -E echo
                   "skipped: needs arm-none-eabi-gcc/g++ with newlib (rdimon.specs) and qemu-system-arm (scripts/install-deps.sh)")
  set_tests_properties(embedded_arm7_cortex_m4 PROPERTIES SKIP_REGULAR_EXPRESSION "skipped: ")
endif()
