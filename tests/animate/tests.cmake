# SPDX-License-Identifier: GPL-2.0-or-later
# kanegen animate: the VTK files read back by VTK's own reader (Debian's
# python3-vtk9, run by the system python3) and compared with the generated
# kernels' outputs that kanegen simulate wrote (tests/animate/check_vtk.py).
add_test(NAME "animate: vtk frames against the run's outputs"
         COMMAND /usr/bin/python3 ${CMAKE_CURRENT_LIST_DIR}/check_vtk.py --kanegen $<TARGET_FILE:kanegen>
                 --source ${PROJECT_SOURCE_DIR} --work ${CMAKE_CURRENT_BINARY_DIR}/animate_work)
set_tests_properties("animate: vtk frames against the run's outputs" PROPERTIES SKIP_RETURN_CODE 77
                     ENVIRONMENT "KANEGEN_CACHE_DIR=${CMAKE_CURRENT_BINARY_DIR}/animate_cache")

# --format html: the escaping of names and the mesh surface (Catch2), then
# the page in headless Chromium (Debian's chromium driven through WebDriver:
# chromium-driver and python3-selenium) against the run's outputs, hostile
# names and the frame rate (tests/animate/check_html.py), with npm's three.js
# or else Debian's libjs-three. It skips without them, unless
# KANEGEN_REQUIRE_BROWSER is set (.ci/run).
add_executable(test_animate ${CMAKE_CURRENT_LIST_DIR}/script_text_test.cpp ${CMAKE_CURRENT_LIST_DIR}/surface_test.cpp
                            ${CMAKE_CURRENT_LIST_DIR}/three_js_test.cpp ${CMAKE_CURRENT_LIST_DIR}/every_model_test.cpp)
target_compile_options(test_animate PRIVATE ${KANEGEN_WARNINGS})
target_compile_definitions(test_animate PRIVATE KANEGEN_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
target_link_libraries(test_animate PRIVATE kanegen_animate kanegen_model kanegen_catch_main)
catch_discover_tests(test_animate TEST_PREFIX "animate: " TEST_SPEC "~[every_model]")
# Both formats for every shipped model, one test each (every_model_test.cpp).
file(GLOB KANEGEN_ANIMATE_MODELS CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/models/*.json ${PROJECT_SOURCE_DIR}/models/*.urdf)
foreach(model ${KANEGEN_ANIMATE_MODELS})
  get_filename_component(name ${model} NAME)
  add_test(NAME "animate: both formats of ${name}" COMMAND test_animate "[every_model]")
  set_tests_properties("animate: both formats of ${name}" PROPERTIES ENVIRONMENT "KANEGEN_ANIMATE_MODEL=${model}")
endforeach()
add_test(NAME "animate: html page in headless Chromium against the run's outputs"
         COMMAND /usr/bin/python3 ${CMAKE_CURRENT_LIST_DIR}/check_html.py --kanegen $<TARGET_FILE:kanegen>
                 --source ${PROJECT_SOURCE_DIR} --work ${CMAKE_CURRENT_BINARY_DIR}/animate_html_work)
# RUN_SERIAL: the page's frame rate (>= 30 fps for flexible_arm10, issue 35)
# is wall-clock playback in a software-rendered Chromium; beside another test
# on the 2 cores it fell to 26.5 fps under the sanitizers' part of CI.
set_tests_properties("animate: html page in headless Chromium against the run's outputs" PROPERTIES
                     SKIP_RETURN_CODE 77 TIMEOUT 300 RUN_SERIAL TRUE
                     ENVIRONMENT "KANEGEN_CACHE_DIR=${CMAKE_CURRENT_BINARY_DIR}/animate_cache")
