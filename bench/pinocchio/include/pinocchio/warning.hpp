// SPDX-License-Identifier: GPL-2.0-or-later
// Stand-in for Pinocchio's generated warning.hpp (see config.hpp here).
#ifndef KANEGEN_BENCH_PINOCCHIO_WARNING_HPP
#define KANEGEN_BENCH_PINOCCHIO_WARNING_HPP

#define PINOCCHIO_WARNING(message)

#endif  // KANEGEN_BENCH_PINOCCHIO_WARNING_HPP
