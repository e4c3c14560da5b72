#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0-or-later
# Runs the libFuzzer targets for a bounded time each, from a corpus of the
# shipped and test models, with a fixed seed. Exits non-zero on the first
# target that finds a crash, a hang, a leak, a sanitizer report or a harness
# failure, naming the reproducer to keep under tests/data/fuzz_regressions/.
#
# Usage: fuzz/run.sh BUILD_DIR [SECONDS_PER_TARGET [TARGET...]]
#   BUILD_DIR: configured with -DCMAKE_CXX_COMPILER=clang++ -DKANEGEN_BUILD_FUZZERS=ON
#              -DKANEGEN_SANITIZE=address,undefined and the fuzz_* targets built
#   TARGET:    json_model, urdf_model, expression, names (default: all four;
#              names runs g++ -E on each accepted input, so g++ must be on PATH)
# Inputs found are kept in BUILD_DIR/fuzz-work/TARGET/corpus for the next run.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=$(cd "${1:?usage: fuzz/run.sh BUILD_DIR [SECONDS [TARGET...]]}" && pwd)
seconds=${2:-60}
shift $(($# < 2 ? $# : 2))
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(json_model urdf_model expression names)

# Every finding is fatal and leaks count (also compiled in: cmake/sanitizer_defaults.cpp).
export ASAN_OPTIONS=${ASAN_OPTIONS:-halt_on_error=1:detect_leaks=1:abort_on_error=0}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-halt_on_error=1:print_stacktrace=1}

# Seeds: the models kept in the repository and the regression inputs.
seed_files() {
  case $1 in
    json_model) find "$root/models" "$root/tests" -name '*.json' -type f ;;
    urdf_model) find "$root/models" "$root/tests" -name '*.urdf' -type f ;;
    expression) ;;  # made from the JSON models below
    names) ;;       # written below
  esac
  find "$root/tests/data/fuzz_regressions/${1%_model}" -type f ! -name '.*' 2>/dev/null || true
}

# Expression seeds: "parameter names\nexpression" for every string of every
# JSON model (names among them are fine seeds too).
expression_seeds() {
  python3 - "$1" "$root" <<'EOF'
import json, os, sys
out, root = sys.argv[1], sys.argv[2]
n = 0
for top in ("models", "tests"):
    for d, _, files in os.walk(os.path.join(root, top)):
        for f in sorted(files):
            if not f.endswith(".json"):
                continue
            try:
                doc = json.load(open(os.path.join(d, f)))
            except Exception:
                continue
            params = doc.get("parameters") if isinstance(doc, dict) else None
            names = " ".join(params) if isinstance(params, dict) else ""
            def walk(x):
                global n
                if isinstance(x, dict):
                    for v in x.values(): walk(v)
                elif isinstance(x, list):
                    for v in x: walk(v)
                elif isinstance(x, str):
                    n += 1
                    open(os.path.join(out, "seed%04d" % n), "w").write(names + "\n" + x)
            walk(doc)
EOF
}

# Names seeds (fuzz/names_fuzzer.cpp): a format byte, then the fields
# separated by the byte 0xfe; plain names, odd ones that must stay text, and
# the injection of the security issue.
names_seeds() {
  python3 - "$1" <<'EOF'
import os, sys
out = sys.argv[1]
urdf = [b"robot", b"ground", b"link1", b"link2", b"j1", b"j2", b"model"]
odd = [b"my robot", b"base link", "\u00e9l\u00e9ment".encode(), "\u8155".encode(), b'j"1\\', b"j*/2??=", b"m*/"]
injection = [b"r\n#define x", b"ground", b"l1", b"l2", b"j1\n#include </etc/shadow>", b"j2*/", b"f\n#error"]
json = [b"m", b"a model", b"b1", b"b2", b"j1", b"j2", b"p1", b"p2", b"o1", b"o2", b"model"]
bad_json = [b"m", b"caf\xc3\xa9 \xff", b"b1", b"b\n2", b"j1", b"j2", b"p1", b"p2", b"o1", b"o2", b"m\n#x"]
seeds = [(0, urdf), (1, urdf), (0, odd), (1, odd), (0, injection), (1, injection), (2, json), (3, json),
         (2, bad_json), (3, bad_json)]
for n, (mode, fields) in enumerate(seeds):
    with open(os.path.join(out, "seed%02d" % n), "wb") as f:
        f.write(bytes([mode]) + b"\xfe".join(fields))
EOF
}

# One target: its seeds, its run, its verdict (a report on stdout; exit 1 on a finding).
fuzz_target() {
  local target=$1 exe=$build/fuzz/fuzz_$1 work=$build/fuzz-work/$1 start a
  rm -rf "$work/seeds" "$work/artifacts"
  mkdir -p "$work/seeds" "$work/corpus" "$work/artifacts"
  seed_files "$target" | while read -r f; do cp "$f" "$work/seeds/$(basename "$(dirname "$f")")_$(basename "$f")"; done
  [ "$target" != expression ] || expression_seeds "$work/seeds"
  [ "$target" != names ] || names_seeds "$work/seeds"
  echo "fuzz_$target: ${seconds} s from $(ls "$work/seeds" | wc -l) seeds and $(ls "$work/corpus" | wc -l) kept inputs"
  start=$(date +%s)
  if "$exe" -seed=1 -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
      -dict="$root/fuzz/$target.dict" -artifact_prefix="$work/artifacts/" \
      "$work/corpus" "$work/seeds" >"$work/log.txt" 2>&1; then
    grep -E '^stat::(number_of_executed_units|new_units_added|peak_rss_mb)' "$work/log.txt" | tr '\n' ' '
    echo "($(($(date +%s) - start)) s, no finding)"
  else
    tail -n 60 "$work/log.txt"
    for a in "$work"/artifacts/*; do
      [ -e "$a" ] || continue
      echo "fuzz_$target: reproducer $a"
      echo "  replay: $exe $a"
      echo "  after the fix, keep it: cp $a $root/tests/data/fuzz_regressions/${target%_model}/"
    done
    echo "fuzz_$target: FAILED (full log: $work/log.txt)"
    return 1
  fi
}

for target in "${targets[@]}"; do
  [ -x "$build/fuzz/fuzz_$target" ] || { echo "fuzz/run.sh: $build/fuzz/fuzz_$target is missing; build the fuzz_$target target" >&2; exit 2; }
done

# The targets run side by side, as many at once as there are cores
# (KANEGEN_FUZZ_JOBS overrides): each is single-threaded, and CI's 2 cores
# would otherwise idle through half of the fuzzing time. Reports are printed
# in the targets' order once all have ended.
jobs=${KANEGEN_FUZZ_JOBS:-$(nproc)}
running=0
for target in "${targets[@]}"; do
  if [ "$running" -ge "$jobs" ]; then
    wait -n || true
    running=$((running - 1))
  fi
  mkdir -p "$build/fuzz-work/$target"
  (if fuzz_target "$target" >"$build/fuzz-work/$target/report.txt" 2>&1; then echo 0; else echo 1; fi \
    >"$build/fuzz-work/$target/status") &
  running=$((running + 1))
done
wait
status=0
for target in "${targets[@]}"; do
  cat "$build/fuzz-work/$target/report.txt"
  [ "$(cat "$build/fuzz-work/$target/status")" = 0 ] || status=1
done
exit $status
