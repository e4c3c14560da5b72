// SPDX-License-Identifier: GPL-2.0-or-later
// Catch2's main for test_consistency (kept apart so that editing the tests
// does not recompile Catch).
#define CATCH_CONFIG_MAIN
#include <catch2/catch.hpp>
