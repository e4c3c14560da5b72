#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0-or-later
# Regenerates generated/<model>/ for every shipped model in models/, with the
# kanegen built in BUILD_DIR (default: build). The directory is named after
# the model file, which must match the model's name.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${BUILD_DIR:-$root/build}
kanegen=$build/generator/kanegen
[ -x "$kanegen" ] || { echo "no kanegen at $kanegen; build first (cmake -S . -B build && cmake --build build)" >&2; exit 1; }
for model in "$root"/models/*.json "$root"/models/*.urdf; do
  [ -e "$model" ] || continue
  stem=$(basename "${model%.*}")
  # Over 2 MB of code: not kept in generated/ (tests/CMakeLists.txt, KANEGEN_LARGE_MODELS).
  [ "$stem" = flexible_arm10 ] && continue
  "$kanegen" generate "$model" -o "$root/generated/$stem" --quiet
  echo "generated/$stem"
done
