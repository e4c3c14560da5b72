# SPDX-License-Identifier: MIT
# The Python module (python/, docs/python.md), built when KANEGEN_BUILD_PYTHON
# is ON and pybind11, the Python headers and NumPy are found; otherwise a
# status line says what is missing. Sets KANEGEN_PYTHON_ENABLED.
set(KANEGEN_PYTHON_ENABLED OFF)
if(KANEGEN_BUILD_PYTHON)
  set(PYBIND11_FINDPYTHON ON)
  find_package(Python 3 COMPONENTS Interpreter Development.Module QUIET)
  find_package(pybind11 CONFIG QUIET)
  set(kanegen_python_missing "")
  if(NOT Python_FOUND)
    set(kanegen_python_missing "the Python 3 headers (python3-dev)")
  elseif(NOT pybind11_FOUND)
    set(kanegen_python_missing "pybind11 (pybind11-dev)")
  else()
    execute_process(COMMAND ${Python_EXECUTABLE} -c "import numpy" RESULT_VARIABLE kanegen_numpy_status
                    OUTPUT_QUIET ERROR_QUIET)
    if(NOT kanegen_numpy_status EQUAL 0)
      set(kanegen_python_missing "NumPy for ${Python_EXECUTABLE} (python3-numpy; or -DPython_EXECUTABLE=/usr/bin/python3)")
    endif()
  endif()
  if(kanegen_python_missing)
    message(STATUS "kanegen: the Python module is not built: ${kanegen_python_missing} not found "
                   "(scripts/install-deps.sh installs it; -DKANEGEN_BUILD_PYTHON=OFF silences this)")
  else()
    message(STATUS "kanegen: the Python module is built for ${Python_EXECUTABLE} (${Python_VERSION}, pybind11 ${pybind11_VERSION})")
    set(KANEGEN_PYTHON_ENABLED ON)
    add_subdirectory(python)
  endif()
endif()
