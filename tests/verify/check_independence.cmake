# The numeric derivation must share no code with the symbolic one: no GiNaC
# and no include of the symbolic stages. Run as cmake -DDIR=<generator> -P.
file(GLOB files ${DIR}/numeric/*.hpp ${DIR}/numeric/*.cpp ${DIR}/model/expression_eval.hpp
     ${DIR}/model/expression_eval.cpp)
if(NOT files)
  message(FATAL_ERROR "no sources found under ${DIR}/numeric")
endif()
foreach(file ${files})
  file(STRINGS ${file} lines REGEX "#include")
  foreach(line ${lines})
    if(line MATCHES "ginac|\"(symbolic|kinematics|kane|codegen|pipeline|fem)/")
      message(FATAL_ERROR "${file}: '${line}': the numeric path may use only the parsed model (model/) and Eigen")
    endif()
  endforeach()
endforeach()
