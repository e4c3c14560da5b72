# SPDX-License-Identifier: GPL-2.0-or-later
# kanegen fmu (docs/fmu.md): the XML escaping and the ZIP writer on their own; then FMUs read back as an
# importer reads them (tests/fmu/check_fmu.py: Python's zipfile and xml.etree, FMI's rules from the
# standards' text in fmi_rules.py, our own C importer fmu_driver.c), compared with kanegen simulate, their
# sources/ compiled alone by g++ and clang++ with -Werror, hostile names and refused input.
add_executable(test_fmu ${CMAKE_CURRENT_LIST_DIR}/test_fmu_text.cpp)
target_compile_options(test_fmu PRIVATE ${KANEGEN_WARNINGS})
target_link_libraries(test_fmu PRIVATE kanegen_fmu kanegen_catch_main)
catch_discover_tests(test_fmu TEST_PREFIX "fmu: ")

# The importer is built as an importer would be, by the system's C compiler and with none of this build's
# flags (a sanitized build's instrumentation would make it another program than the FMUs expect).
find_program(KANEGEN_FMU_CC NAMES cc gcc clang REQUIRED)
set(KANEGEN_FMU_DRIVER ${CMAKE_CURRENT_BINARY_DIR}/fmu_driver)
add_custom_command(OUTPUT ${KANEGEN_FMU_DRIVER}
                   COMMAND ${KANEGEN_FMU_CC} -std=gnu99 -O1 -Wall -Wextra -Werror ${CMAKE_CURRENT_LIST_DIR}/fmu_driver.c
                           -o ${KANEGEN_FMU_DRIVER} -ldl
                   DEPENDS ${CMAKE_CURRENT_LIST_DIR}/fmu_driver.c
                   COMMENT "Building tests/fmu/fmu_driver.c, the FMU tests' importer" VERBATIM)
add_custom_target(kanegen_fmu_driver ALL DEPENDS ${KANEGEN_FMU_DRIVER})

# name;arguments of check_fmu.py
set(KANEGEN_FMU_CASES
    "four_bar (closed loop) FMI 2 and 3 against simulate|run four_bar.json 2 3"
    "double_pendulum FMI 3 against simulate, its sources alone with g++ and clang++ -Werror|sources double_pendulum.json 3"
    "spherical top (quaternion states) FMI 2 against simulate|run ${PROJECT_SOURCE_DIR}/tests/data/models/spherical_top.json 2"
    "hostile names|hostile"
    "bad input refused, nothing written|refused")
foreach(case ${KANEGEN_FMU_CASES})
  string(FIND "${case}" "|" bar)
  string(SUBSTRING "${case}" 0 ${bar} name)
  math(EXPR bar "${bar} + 1")
  string(SUBSTRING "${case}" ${bar} -1 arguments)
  separate_arguments(arguments)
  string(MAKE_C_IDENTIFIER "${name}" folder)
  add_test(NAME "fmu: ${name}"
           COMMAND /usr/bin/python3 ${CMAKE_CURRENT_LIST_DIR}/check_fmu.py --kanegen $<TARGET_FILE:kanegen>
                   --driver ${KANEGEN_FMU_DRIVER} --source ${PROJECT_SOURCE_DIR}
                   --work ${CMAKE_CURRENT_BINARY_DIR}/fmu_work/${folder} ${arguments})
  # One cache for all: the FMU runtime every export shares is compiled once (fmu/shared_object.hpp).
  set_tests_properties("fmu: ${name}" PROPERTIES ENVIRONMENT "KANEGEN_CACHE_DIR=${CMAKE_CURRENT_BINARY_DIR}/fmu_work/cache")
endforeach()
