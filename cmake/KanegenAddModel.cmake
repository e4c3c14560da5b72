# SPDX-License-Identifier: MIT
# kanegen_add_model(<target> <model file> [NAME <model name>] [RUNNER] [JACOBIANS] [CONTROLLER] [PRECISION float]
#                   [DYNAMICS recursive|composite|auto] [SPLIT_THRESHOLD N] [BATCH 4|8])
#
# Generates the model's kernels at build time (again whenever the model file
# or the kanegen generator changes) and makes <target> a static library with
# them: include "<model name>.hpp" and call kanegen_models::<model name>::...
# With RUNNER, also builds <target>_runner, the simulate/eval/info program.
# With JACOBIANS, the model also has the Jacobian kernels of implicit
# integration (kanegen generate --jacobians); with CONTROLLER, the quadratic
# kernels for controllers too (kanegen generate --controller). With PRECISION float, the
# kernels are float (kanegen generate --precision float): include
# "<model name>_float.hpp" and call kanegen_models::<model name>_float::...;
# such a model has no runner (docs/embedded.md). DYNAMICS picks how
# forward_dynamics solves (kanegen generate --dynamics; default auto).
# SPLIT_THRESHOLD: kernels of more operations become several functions
# (kanegen generate --split-threshold; 0: never). BATCH W: the library also has
# the batched kernels, W states per call (kanegen generate --batch W): include
# "<model name>_batch<W>.hpp"; define KANEGEN_BATCH_PORTABLE on <target> for
# the portable lanes instead of the vector extension.
#
# The model name is read from the file (JSON "name", URDF <robot name>, made
# a C++ identifier as kanegen does); NAME overrides it if your file is unusual.
function(kanegen_add_model target model)
  cmake_parse_arguments(ARG "RUNNER;JACOBIANS;CONTROLLER" "NAME;PRECISION;DYNAMICS;SPLIT_THRESHOLD;BATCH" "" ${ARGN})
  get_filename_component(model_path ${model} ABSOLUTE)
  if(NOT EXISTS ${model_path})
    message(FATAL_ERROR "kanegen_add_model(${target}): model file ${model_path} does not exist")
  endif()
  set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${model_path})
  set(name ${ARG_NAME})
  if(NOT name)
    file(READ ${model_path} content)
    if(model_path MATCHES "\\.json$")
      string(JSON name ERROR_VARIABLE json_error GET "${content}" name)
      if(json_error)
        message(FATAL_ERROR "kanegen_add_model(${target}): ${model_path}: no top-level \"name\" (${json_error})")
      endif()
    else()
      string(REGEX MATCH "<robot[^>]*name[ \t]*=[ \t]*[\"']([^\"']*)[\"']" match "${content}")
      set(name ${CMAKE_MATCH_1})
      string(REGEX REPLACE "[^A-Za-z0-9_]" "_" name "${name}")
      if(name MATCHES "^[0-9]")
        set(name "_${name}")
      endif()
    endif()
  endif()
  if(NOT name)
    message(FATAL_ERROR "kanegen_add_model(${target}): cannot read the model name from ${model_path}; pass NAME")
  endif()

  set(out ${CMAKE_CURRENT_BINARY_DIR}/kanegen_generated/${target})
  set(options)
  if(ARG_JACOBIANS)
    list(APPEND options --jacobians)
  endif()
  if(ARG_CONTROLLER)
    list(APPEND options --controller)
  endif()
  if(ARG_DYNAMICS)
    if(NOT ARG_DYNAMICS MATCHES "^(recursive|composite|auto)$")
      message(FATAL_ERROR "kanegen_add_model(${target}): DYNAMICS is recursive, composite or auto, not ${ARG_DYNAMICS}")
    endif()
    list(APPEND options --dynamics ${ARG_DYNAMICS})
  endif()
  if(DEFINED ARG_SPLIT_THRESHOLD)
    if(NOT ARG_SPLIT_THRESHOLD MATCHES "^[0-9]+$")
      message(FATAL_ERROR "kanegen_add_model(${target}): SPLIT_THRESHOLD is a number of operations, not ${ARG_SPLIT_THRESHOLD}")
    endif()
    list(APPEND options --split-threshold ${ARG_SPLIT_THRESHOLD})
  endif()
  set(batch_sources)
  if(DEFINED ARG_BATCH)
    if(NOT ARG_BATCH MATCHES "^(4|8)$")
      message(FATAL_ERROR "kanegen_add_model(${target}): BATCH is 4 or 8, not ${ARG_BATCH}")
    endif()
    list(APPEND options --batch ${ARG_BATCH})
    set(batch_sources ${out}/${name}_batch${ARG_BATCH}.cpp ${out}/${name}_batch${ARG_BATCH}.hpp)
  endif()
  set(runner_source ${out}/${name}_runner.cpp)
  if(ARG_PRECISION STREQUAL "float")
    list(APPEND options --precision float)
    set(name ${name}_float)
    set(runner_source)
    if(ARG_RUNNER)
      message(FATAL_ERROR "kanegen_add_model(${target}): a PRECISION float model has no RUNNER (the runtime is double)")
    endif()
  elseif(ARG_PRECISION AND NOT ARG_PRECISION STREQUAL "double")
    message(FATAL_ERROR "kanegen_add_model(${target}): PRECISION is double or float, not ${ARG_PRECISION}")
  endif()
  add_custom_command(
    OUTPUT ${out}/${name}.hpp ${out}/${name}.cpp ${runner_source} ${batch_sources}
    COMMAND ${KANEGEN_EXECUTABLE} generate ${model_path} -o ${out} --quiet ${options}
    DEPENDS ${model_path} ${KANEGEN_EXECUTABLE}
    COMMENT "kanegen: generating ${name} from ${model}"
    VERBATIM)
  add_library(${target} STATIC ${out}/${name}.cpp ${out}/${name}.hpp ${batch_sources})
  target_include_directories(${target} PUBLIC ${out})
  target_link_libraries(${target} PUBLIC kanegen::runtime)
  set_target_properties(${target} PROPERTIES POSITION_INDEPENDENT_CODE ON)
  if(ARG_RUNNER)
    add_executable(${target}_runner ${out}/${name}_runner.cpp)
    target_link_libraries(${target}_runner PRIVATE ${target})
  endif()
endfunction()
