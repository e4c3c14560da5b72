// SPDX-License-Identifier: GPL-2.0-or-later
// Stand-in for Pinocchio's generated deprecated.hpp (see config.hpp here).
#ifndef KANEGEN_BENCH_PINOCCHIO_DEPRECATED_HPP
#define KANEGEN_BENCH_PINOCCHIO_DEPRECATED_HPP

// Deprecation and "unsupported API" markers only change diagnostics; they are
// empty here so that the bench stays warning-free.
#define PINOCCHIO_DEPRECATED
#define PINOCCHIO_DEPRECATED_MESSAGE(message)

#endif  // KANEGEN_BENCH_PINOCCHIO_DEPRECATED_HPP
