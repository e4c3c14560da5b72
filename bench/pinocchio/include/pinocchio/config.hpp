// SPDX-License-Identifier: GPL-2.0-or-later
// Stand-in for the config.hpp that Pinocchio's CMake generates (through
// jrl-cmakemodules), for using Pinocchio as headers only in bench_pinocchio:
// no template instantiation library, no export symbols. The version is the
// pinned one of docs/benchmarks.md ("Pinocchio side by side").
#ifndef KANEGEN_BENCH_PINOCCHIO_CONFIG_HPP
#define KANEGEN_BENCH_PINOCCHIO_CONFIG_HPP

#define PINOCCHIO_VERSION "3.7.0"
#define PINOCCHIO_MAJOR_VERSION 3
#define PINOCCHIO_MINOR_VERSION 7
#define PINOCCHIO_PATCH_VERSION 0

#define PINOCCHIO_DLLAPI
#define PINOCCHIO_LOCAL
#define PINOCCHIO_EXPLICIT_INSTANTIATION_DECLARATION_DLLAPI
#define PINOCCHIO_EXPLICIT_INSTANTIATION_DEFINITION_DLLAPI

#ifndef PINOCCHIO_ENABLE_TEMPLATE_INSTANTIATION
#define PINOCCHIO_ENABLE_TEMPLATE_INSTANTIATION 0
#endif

#endif  // KANEGEN_BENCH_PINOCCHIO_CONFIG_HPP
