# SPDX-License-Identifier: GPL-2.0-or-later
# The numeric derivation must share no code with the symbolic one: no GiNaC
# and no include of the symbolic stages. One exception, a choice of
# coordinates rather than a derivation (docs/verify.md): numeric/instance.cpp
# may include fem/elastic_model.hpp, and use from it only the basis of the
# elastic coordinates and, for a mesh body with geometric stiffening, the
# second-order fields that go with it (the result of fem::build_elastic_model,
# named `built`: built.reduced.basis and built.second_order); and, for a
# mesh body, fem/model_mesh.hpp for the mesh file as read (nodes, elements
# with their CalculiX type name, fem::ccx_type_name, node sets: a file format) and the order of the body's nodes and elements
# that the basis's rows follow (fem::build_model_mesh_body(...)'s node_ids,
# node_of and element_ids), never its matrices.
# Run as cmake -DDIR=<generator> -P.

# Every member read of the object named `name` in `text` must match `allowed`.
function(only_members name allowed what)
  string(REGEX MATCHALL "${name}[.][A-Za-z_.]+" member_uses "${text}")
  foreach(use ${member_uses})
    if(NOT use MATCHES "^${name}[.](${allowed})$")
      message(FATAL_ERROR "${file}: reads ${use}: the numeric path takes ${what}, not the finite-element layer's "
                          "matrices")
    endif()
  endforeach()
endfunction()

file(GLOB files ${DIR}/numeric/*.hpp ${DIR}/numeric/*.cpp ${DIR}/model/expression.hpp ${DIR}/model/expression.cpp
     ${DIR}/model/expression_eval.hpp ${DIR}/model/expression_eval.cpp)
if(NOT files)
  message(FATAL_ERROR "no sources found under ${DIR}/numeric")
endif()
foreach(file ${files})
  get_filename_component(name ${file} NAME)
  file(STRINGS ${file} lines REGEX "#include")
  foreach(line ${lines})
    if(name STREQUAL "instance.cpp" AND line MATCHES "^#include \"fem/(elastic_model|model_mesh).hpp\"$")
      continue()
    endif()
    if(line MATCHES "ginac|\"(symbolic|kinematics|kane|codegen|pipeline|fem)/")
      message(FATAL_ERROR "${file}: '${line}': the numeric path may use only the parsed model (model/) and Eigen "
                          "(and the basis of the elastic coordinates, in instance.cpp)")
    endif()
  endforeach()
  # Every use of the finite-element layer is the basis and nothing else.
  file(READ ${file} text)
  string(REGEX MATCHALL "fem::[A-Za-z_]+" uses "${text}")
  string(REGEX MATCHALL "fem::build_elastic_model\\([^;]*\\)" allowed "${text}")
  string(REGEX MATCHALL "fem::(read_model_mesh|build_model_mesh_body|InpMesh|MeshBody|MeshElement|ContinuumFamily|ccx_type_name)[^A-Za-z_]"
               mesh_input "${text}")
  # The mesh body built by the layer (named `layout`) gives its order only.
  only_members(layout "(node_ids|node_of|element_ids)([.]at)?"
               "the mesh body's node and element order (node_ids, node_of, element_ids)")
  # The reduced body built by the layer (named `built`) gives its coordinates only.
  only_members(built "reduced[.]basis|second_order"
               "the elastic coordinates (reduced.basis) and the second-order fields (second_order) of the reduced body")
  list(LENGTH uses used)
  list(LENGTH allowed allowed_count)
  list(LENGTH mesh_input mesh_count)
  math(EXPR allowed_count "${allowed_count} + ${mesh_count}")
  if(NOT used EQUAL allowed_count OR (used GREATER 0 AND NOT name STREQUAL "instance.cpp"))
    message(FATAL_ERROR "${file}: uses ${uses} of the finite-element layer; the numeric path may take only "
                        "fem::build_elastic_model(...)'s reduced.basis and second_order and a mesh body's file and node order "
                        "(in instance.cpp)")
  endif()
endforeach()
