// SPDX-License-Identifier: GPL-2.0-or-later
// 64-bit FNV-1a: a stable hash of bytes, the same on every machine. The
// model hash in generated files and the codegen's node keys both use it, so
// changing it changes generated code.
#pragma once

#include <cstdint>
#include <string>

namespace kanegen::model {

inline constexpr std::uint64_t kFnv1aOffset = 0xcbf29ce484222325ULL;
inline constexpr std::uint64_t kFnv1aPrime = 0x100000001b3ULL;

inline std::uint64_t fnv1a(const std::string& bytes) {
  std::uint64_t h = kFnv1aOffset;
  for (unsigned char c : bytes) h = (h ^ c) * kFnv1aPrime;
  return h;
}

}  // namespace kanegen::model
