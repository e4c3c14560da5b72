// SPDX-License-Identifier: GPL-2.0-or-later
// The files of templates/, compiled into the generator (cmake/EmbedText.cmake)
// so that an installed kanegen needs no data files.
#pragma once

#include <array>

namespace kanegen::embedded {

extern const char* const model_hpp_template;     ///< templates/model.hpp.in
extern const char* const model_cpp_template;     ///< templates/model.cpp.in
extern const char* const runner_cpp_template;    ///< templates/runner.cpp.in
extern const char* const loop_parts_template;    ///< templates/loop_parts.in
extern const char* const solve_saddle_template;  ///< templates/solve_saddle.hpp
extern const char* const runtime_face_template;  ///< templates/runtime_face.in

/// All of them, for the digest that keys the runner cache.
inline std::array<const char*, 6> all_templates() {
  return {model_hpp_template, model_cpp_template, runner_cpp_template, loop_parts_template,
          solve_saddle_template, runtime_face_template};
}

}  // namespace kanegen::embedded
