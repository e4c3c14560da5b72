// SPDX-License-Identifier: GPL-2.0-or-later
// Loading a URDF into MuJoCo for the benchmarks (bench_dynamics.cpp,
// scaling_driver.cpp).
#pragma once

#include <mujoco/mujoco.h>

#include <algorithm>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>

namespace kanegen_bench {

/// The URDF at `path` in MuJoCo with fusestatic="true": links on fixed joints
/// are merged into their parent, as MuJoCo would by default, so that it does
/// not carry the extra bodies the consistency tests keep. Null, with the
/// reason in `error`, if it cannot be read or loaded.
inline mjModel* load_urdf(const std::string& path, std::string& error) {
  std::ifstream in(path);
  if (!in) {
    error = "cannot read " + path;
    return nullptr;
  }
  std::stringstream ss;
  ss << in.rdbuf();
  std::string text = ss.str();
  const std::string from = "fusestatic=\"false\"", to = "fusestatic=\"true\"";
  for (auto at = text.find(from); at != std::string::npos; at = text.find(from, at))
    text.replace(at, from.size(), to);
  auto vfs = std::make_unique<mjVFS>();
  mj_defaultVFS(vfs.get());
  const char* name = "model.urdf";
  if (mj_makeEmptyFileVFS(vfs.get(), name, static_cast<int>(text.size())) != 0) {
    error = "MuJoCo's virtual file system is full";
    return nullptr;
  }
  std::copy(text.begin(), text.end(), static_cast<char*>(vfs->filedata[mj_findFileVFS(vfs.get(), name)]));
  char message[1000] = "";
  mjModel* m = mj_loadXML(name, vfs.get(), message, sizeof message);
  mj_deleteVFS(vfs.get());
  if (m == nullptr) error = path + ": " + message;
  return m;
}

}  // namespace kanegen_bench
