#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0-or-later
# Generates every model in models/ and tests/**/data/ (.json, .urdf) with
# several option sets by two kanegen binaries and compares what they write:
# the files, and for a model a binary refuses, its message and exit status.
# For a refactoring that must not change the generated code.
#
#   scripts/compare_generated.sh BEFORE_KANEGEN AFTER_KANEGEN [WORK_DIR]
#
# Prints one line per differing case and a summary; exits 1 if any differ.
set -euo pipefail
before=$1
after=$2
work=${3:-$(mktemp -d)}
repo=$(cd "$(dirname "$0")/.." && pwd)
cd "$repo"

option_sets=(
  "default|"
  "recursive|--dynamics recursive"
  "composite|--dynamics composite"
  "jacobians|--jacobians"
  "controller|--controller"
  "float|--precision float"
  "split300|--split-threshold 300"
  "nosplit|--split-threshold 0"
)

mapfile -t models < <( (ls models/*.json models/*.urdf; find tests -path '*data*' \( -name '*.json' -o -name '*.urdf' \)) | sort)

# run BINARY OUT_DIR MODEL OPTIONS: the files in OUT_DIR/files, the message
# (without the generator's own path) and status in OUT_DIR/result.
run() {
  local binary=$1 out=$2 model=$3 options=$4
  mkdir -p "$out/files"
  local status=0
  # shellcheck disable=SC2086
  nice -n 19 "$binary" generate --quiet $options -o "$out/files" "$model" >"$out/log" 2>&1 || status=$?
  { sed "s|$binary|KANEGEN|g" "$out/log"; echo "exit $status"; } >"$out/result"
  rm "$out/log"
}

cases=0
differ=0
for model in "${models[@]}"; do
  for set in "${option_sets[@]}"; do
    name=${set%%|*}
    options=${set#*|}
    case_dir="$work/$(echo "$model" | tr '/' '_')/$name"
    run "$before" "$case_dir/before" "$model" "$options" &
    run "$after" "$case_dir/after" "$model" "$options" &
    wait
    cases=$((cases + 1))
    if ! diff -r "$case_dir/before" "$case_dir/after" >/dev/null; then
      differ=$((differ + 1))
      echo "DIFFERS: $model $options ($case_dir)"
    else
      rm -rf "$case_dir"
    fi
  done
done
echo "$cases cases compared (${#models[@]} models x ${#option_sets[@]} option sets), $differ differ"
[ "$differ" -eq 0 ]
