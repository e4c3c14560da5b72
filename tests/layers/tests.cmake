# SPDX-License-Identifier: GPL-2.0-or-later
# The layering of docs/architecture.md (cmake/KanegenLayers.cmake): the
# includes of the tree, the link closures of the real GiNaC-free targets, and
# the enforcement itself, which must fail scratch projects that break a rule,
# with its message. Included from tests/CMakeLists.txt.
add_test(NAME "layers: includes stay within their layer"
         COMMAND ${CMAKE_COMMAND} -DROOT=${PROJECT_SOURCE_DIR} -P ${CMAKE_CURRENT_LIST_DIR}/check_includes.cmake)
add_test(NAME "layers: runtime, model, fem and numeric link no GiNaC"
         COMMAND ${CMAKE_COMMAND} -DREPORT=${PROJECT_BINARY_DIR}/kanegen-layers.txt
                 -P ${CMAKE_CURRENT_LIST_DIR}/check_closures.cmake)
add_test(NAME "layers: a violation fails the configure or the build"
         COMMAND ${CMAKE_COMMAND} -DSOURCE_DIR=${PROJECT_SOURCE_DIR} -DSCRATCH=${CMAKE_CURRENT_BINARY_DIR}/layers_scratch
                 -DGENERATOR=${CMAKE_GENERATOR} -DCXX=${CMAKE_CXX_COMPILER}
                 -P ${CMAKE_CURRENT_LIST_DIR}/check_enforcement.cmake)
