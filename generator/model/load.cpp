// SPDX-License-Identifier: GPL-2.0-or-later
#include "model/load.hpp"

#include <algorithm>
#include <cctype>

#include "model/json_loader.hpp"
#include "model/urdf_loader.hpp"

namespace kanegen::model {

Model load_model(const std::string& path, const LoadOptions& options) {
  const auto dot = path.rfind('.');
  const auto slash = path.find_last_of("/\\");
  std::string extension =
      dot == std::string::npos || (slash != std::string::npos && dot < slash) ? "" : path.substr(dot);
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (extension == ".json") return load_json_model(path);
  if (extension == ".urdf") return load_urdf_model(path, options);
  throw ModelError(path, "file", "unknown model file type '" + extension + "'",
                   "use a .json kanegen model (docs/model-format.md) or a .urdf robot");
}

}  // namespace kanegen::model
