# SPDX-License-Identifier: GPL-2.0-or-later
# Batched kernels (kanegen generate --batch W) lane by lane against the
# scalar kernels of the same generation (the independent reference: the
# batched code is a rewrite of their text, evaluated over W lanes): arm7 (the
# articulated-body recursion), arm7 split into parts of about 300 operations,
# double_pendulum (composite inertias: the LDL^T's pivot checks inside the
# kernel) and flexible_arm2 (a flexible tree), with the vector extension and
# with the portable lanes forced (KANEGEN_BATCH_PORTABLE), W = 4 and 8; every
# library compiled with -Werror.
# Each entry: source model, emitted name, lanes, PORTABLE or VECTOR, split threshold.
set(_kg_batch_libraries)
foreach(_kg_spec IN ITEMS "models/arm7.urdf:arm7_b4v:4:VECTOR:6000" "models/arm7.urdf:arm7_b8p:8:PORTABLE:6000"
                          "models/arm7.urdf:arm7_b8v:8:VECTOR:6000" "models/arm7.urdf:arm7_s4v:4:VECTOR:300"
                          "models/double_pendulum.json:dp_b4v:4:VECTOR:6000"
                          "models/double_pendulum.json:dp_b4p:4:PORTABLE:6000"
                          "models/flexible_arm2.json:flex_b8v:8:VECTOR:6000"
                          "models/flexible_arm2.json:flex_b4p:4:PORTABLE:6000")
  string(REPLACE ":" ";" _kg_entry "${_kg_spec}")
  list(GET _kg_entry 0 _kg_source)
  list(GET _kg_entry 1 _kg_name)
  list(GET _kg_entry 2 _kg_lanes)
  list(GET _kg_entry 3 _kg_kind)
  list(GET _kg_entry 4 _kg_split)
  get_filename_component(_kg_stem ${_kg_source} NAME_WE)
  get_filename_component(_kg_ext ${_kg_source} EXT)
  file(READ ${PROJECT_SOURCE_DIR}/${_kg_source} _kg_text)
  string(REPLACE "<robot name=\"${_kg_stem}\">" "<robot name=\"${_kg_name}\">" _kg_text "${_kg_text}")
  string(REPLACE "\"name\": \"${_kg_stem}\"" "\"name\": \"${_kg_name}\"" _kg_text "${_kg_text}")
  file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/${_kg_name}${_kg_ext} "${_kg_text}")
  kanegen_add_model(kanegen_model_${_kg_name} ${CMAKE_CURRENT_BINARY_DIR}/${_kg_name}${_kg_ext} NAME ${_kg_name}
                    BATCH ${_kg_lanes} SPLIT_THRESHOLD ${_kg_split})
  target_compile_options(kanegen_model_${_kg_name} PRIVATE ${KANEGEN_WARNINGS} -Werror)
  if(_kg_kind STREQUAL "PORTABLE")
    target_compile_definitions(kanegen_model_${_kg_name} PRIVATE KANEGEN_BATCH_PORTABLE)
  endif()
  list(APPEND _kg_batch_libraries kanegen_model_${_kg_name})
endforeach()
add_executable(test_batch ${CMAKE_CURRENT_LIST_DIR}/test_batch_kernels.cpp)
target_compile_options(test_batch PRIVATE ${KANEGEN_WARNINGS})
target_link_libraries(test_batch PRIVATE ${_kg_batch_libraries} kanegen_generator kanegen_catch_main)
catch_discover_tests(test_batch TEST_PREFIX "batch: ")
# The hostile names of tests/data/models/hostile_names.urdf in the batched
# files too: compiled with -Werror (a library of its own, linked by nothing).
kanegen_add_model(kanegen_model_hostile_names_batch ${PROJECT_SOURCE_DIR}/tests/data/models/hostile_names.urdf BATCH 4)
target_compile_options(kanegen_model_hostile_names_batch PRIVATE ${KANEGEN_WARNINGS} -Werror)
