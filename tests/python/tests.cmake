# SPDX-License-Identifier: GPL-2.0-or-later
# The Python module (python/, docs/python.md) with pytest, one ctest per file
# (python:<file>), the module imported from the build tree; and installed to a
# scratch prefix and imported from there (install_python_module).
if(NOT KANEGEN_PYTHON_ENABLED)
  return()
endif()
execute_process(COMMAND ${Python_EXECUTABLE} -c "import pytest" RESULT_VARIABLE kanegen_pytest_status
                OUTPUT_QUIET ERROR_QUIET)
if(NOT kanegen_pytest_status EQUAL 0)
  message(STATUS "kanegen: the Python tests are not registered: pytest not found for ${Python_EXECUTABLE} (python3-pytest)")
  return()
endif()
file(GLOB KANEGEN_PYTHON_TESTS CONFIGURE_DEPENDS ${CMAKE_CURRENT_LIST_DIR}/test_*.py)
foreach(file ${KANEGEN_PYTHON_TESTS})
  get_filename_component(stem ${file} NAME_WE)
  add_test(NAME python:${stem}
           COMMAND ${Python_EXECUTABLE} -m pytest -q -p no:cacheprovider ${file}
           WORKING_DIRECTORY ${CMAKE_CURRENT_LIST_DIR})
  set_tests_properties(python:${stem} PROPERTIES ENVIRONMENT
    "PYTHONPATH=${PROJECT_BINARY_DIR}/python;KANEGEN_CACHE_DIR=${CMAKE_CURRENT_BINARY_DIR}/python_cache;KANEGEN_EXE=$<TARGET_FILE:kanegen>;KANEGEN_MODELS_DIR=${PROJECT_SOURCE_DIR}/models;KANEGEN_BAD_MODELS_DIR=${PROJECT_SOURCE_DIR}/tests/data/bad_models;PYTHONDONTWRITEBYTECODE=1")
endforeach()

add_test(NAME install_python_module
         COMMAND ${CMAKE_COMMAND} -DBUILD_DIR=${PROJECT_BINARY_DIR} -DPYTHON=${Python_EXECUTABLE}
                 -DPYTHON_DIR=${KANEGEN_PYTHON_INSTALL_DIR} -DMODEL=${PROJECT_SOURCE_DIR}/models/simple_pendulum.json
                 -DSCRATCH=${CMAKE_CURRENT_BINARY_DIR}/install_python_test -P ${CMAKE_CURRENT_LIST_DIR}/install_python_module.cmake)
