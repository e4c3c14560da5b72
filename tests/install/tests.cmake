# SPDX-License-Identifier: GPL-2.0-or-later
# find_package(kanegen) from an installed tree, with the example project.
add_test(NAME install_and_build_example
         COMMAND ${CMAKE_COMMAND} -DBUILD_DIR=${PROJECT_BINARY_DIR} -DSOURCE_DIR=${PROJECT_SOURCE_DIR}
                 -DSCRATCH=${CMAKE_CURRENT_BINARY_DIR}/install_test -P ${CMAKE_CURRENT_LIST_DIR}/install_and_build_example.cmake)
