# SPDX-License-Identifier: MIT
# kanegen_find_mujoco(): find_package(mujoco) and repair its imported target.
# Debian's libmujoco-dev 2.2.2 lists /usr/include/libqhull_r/ as an include
# directory of mujoco::mujoco without depending on libqhull-dev; CMake refuses
# non-existent include directories of imported targets, and the public MuJoCo
# headers do not need qhull: keep the directories that exist. Sets mujoco_FOUND.
macro(kanegen_find_mujoco)
  find_package(mujoco QUIET)
  if(mujoco_FOUND AND TARGET mujoco::mujoco)
    get_target_property(_kg_mj_inc mujoco::mujoco INTERFACE_INCLUDE_DIRECTORIES)
    set(_kg_mj_inc_ok)
    foreach(_dir IN LISTS _kg_mj_inc)
      if(EXISTS "${_dir}")
        list(APPEND _kg_mj_inc_ok "${_dir}")
      endif()
    endforeach()
    set_target_properties(mujoco::mujoco PROPERTIES INTERFACE_INCLUDE_DIRECTORIES "${_kg_mj_inc_ok}")
  endif()
endmacro()
