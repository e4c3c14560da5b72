# SPDX-License-Identifier: GPL-2.0-or-later
# kanegen animate: the VTK files read back by VTK's own reader (Debian's
# python3-vtk9, run by the system python3) and compared with the generated
# kernels' outputs that kanegen simulate wrote (tests/animate/check_vtk.py).
add_test(NAME "animate: vtk frames against the run's outputs"
         COMMAND /usr/bin/python3 ${CMAKE_CURRENT_LIST_DIR}/check_vtk.py --kanegen $<TARGET_FILE:kanegen>
                 --source ${PROJECT_SOURCE_DIR} --work ${CMAKE_CURRENT_BINARY_DIR}/animate_work)
set_tests_properties("animate: vtk frames against the run's outputs" PROPERTIES SKIP_RETURN_CODE 77
                     ENVIRONMENT "KANEGEN_CACHE_DIR=${CMAKE_CURRENT_BINARY_DIR}/animate_cache")
