# SPDX-License-Identifier: GPL-2.0-or-later
# Writes the model JSON Schema into a C++ source as a raw string literal, so
# an installed kanegen needs no data files. Run as
#   cmake -DINPUT=<schema.json> -DOUTPUT=<schema_text.cpp> -P embed_schema.cmake
file(READ "${INPUT}" schema)
set(delimiter "kanegen_schema")
string(FIND "${schema}" ")${delimiter}\"" clash)
if(NOT clash EQUAL -1)
  message(FATAL_ERROR "${INPUT} contains the raw string delimiter )${delimiter}\"")
endif()
file(WRITE "${OUTPUT}"
  "// Generated from ${INPUT} by embed_schema.cmake; edit the .json file instead.\n"
  "namespace kanegen::model::detail {\n"
  "extern const char* const kModelSchemaJson;\n"
  "const char* const kModelSchemaJson = R\"${delimiter}(${schema})${delimiter}\";\n"
  "}  // namespace kanegen::model::detail\n")
