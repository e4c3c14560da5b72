#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0-or-later
# Installs the Debian packages kanegen needs to build, test and benchmark.
# Run as root on Debian 12 (bookworm) or later.
set -euo pipefail
packages=(
  g++ clang cmake make pkg-config git python3
  libginac-dev libeigen3-dev libspectra-dev nlohmann-json3-dev catch2 libcli11-dev
  liburdfdom-dev libtinyxml2-dev libvalijson-dev
  libsundials-dev libomp-dev
  libmujoco-dev libbenchmark-dev
  libclang-rt-dev llvm
  gnuplot-nox
  pybind11-dev python3-dev python3-numpy python3-pytest
  gcc-arm-none-eabi libnewlib-arm-none-eabi qemu-system-arm
  python3-vtk9
  nodejs chromium chromium-driver python3-selenium libjs-three
)
# libspectra-dev: Spectra (header-only), the shift-invert Lanczos eigensolver
# of large meshes' modal reduction (generator/fem/sparse_modal.cpp).
# libsundials-dev: CVODE, the runtime's adaptive implicit integrator
# (--integrator implicit); libomp-dev: clang's OpenMP, which SUNDIALS's CMake
# package looks for (its OpenMP vectors) and fails without under clang++. libclang-rt-dev: clang's sanitizer and libFuzzer runtimes (only recommended
# by clang, so not pulled in with --no-install-recommends), for the
# KANEGEN_SANITIZE and KANEGEN_BUILD_FUZZERS builds that CI runs; llvm: its
# llvm-symbolizer, which the sanitizers call to name frames (and to match the
# leak suppressions by library). gnuplot-nox: gnuplot without X11, which
# `kanegen plot` and `simulate --plot` run to draw PNGs. pybind11-dev,
# python3-dev, python3-numpy: the Python module kanegen (python/,
# docs/python.md; skipped with a status line without them), python3-pytest its
# tests (python:*). gcc-arm-none-eabi,
# libnewlib-arm-none-eabi, qemu-system-arm: the Cortex-M4F build of
# examples/embedded and its run under QEMU (test embedded_arm7_cortex_m4,
# skipped without them; docs/embedded.md). They add about 920 MB installed
# (the compiler 436 MB, newlib 369 MB for every ARM multilib, QEMU 51 MB),
# 97 MB downloaded; 90 s to install here. python3-vtk9: VTK's Python
# bindings, with which tests/animate reads back what `kanegen animate`
# writes (VTK's own reader, not ours); 47 MB installed, with its libraries.
# nodejs and npm: `kanegen animate --format html` inlines three.js, which
# `npm ci` puts in viewer/node_modules (the version viewer/package-lock.json
# pins; CMake finds it there and installs it with kanegen); npm is installed
# only if no npm came with nodejs: NodeSource's nodejs carries its own and
# conflicts with Debian's. libjs-three: Debian's three.js (r111), which
# kanegen inlines instead where npm's is missing (a machine that reaches
# Debian's archive but not the npm registry). chromium, chromium-driver and
# python3-selenium: the browser test (tests/animate/check_html.py) opens the
# pages in headless chromium driven through WebDriver. Installed:
# libjs-three 10 MB, chromium-driver 25 MB, python3-selenium 0.6 MB.
# kanegen fmu needs no package of its own (its ZIP writer and FMI declarations
# are kanegen's); tests/fmu builds each FMU's sources/ with g++ and clang++
# (listed above) and reads the FMUs back with python3's zipfile and xml.etree.
if [ "$(id -u)" -ne 0 ]; then
  echo "install-deps.sh: run as root (apt-get needs it), e.g. sudo bash scripts/install-deps.sh" >&2
  exit 1
fi
export DEBIAN_FRONTEND=noninteractive
apt-get update -q
apt-get install -y -q --no-install-recommends "${packages[@]}"
command -v npm >/dev/null || apt-get install -y -q --no-install-recommends npm
# A machine that reaches Debian's archive but not the npm registry (or not
# its certificate) builds and tests everything too: --format html then
# inlines Debian's libjs-three.
if ! (cd "$(dirname "$0")/../viewer" && npm ci --no-audit --no-fund); then
  echo "install-deps.sh: note: npm ci in viewer/ failed (is the npm registry reachable, and its" \
    "certificate trusted?); kanegen animate --format html inlines Debian's three.js r111 (libjs-three)" \
    "instead of npm's r185" >&2
fi
