// SPDX-License-Identifier: GPL-2.0-or-later
// Catch2's main, compiled once into kanegen_catch_main for every test
// executable: it is the slowest file of the suite to compile (about 20 s at
// -O3), and each executable used to compile its own copy.
#define CATCH_CONFIG_MAIN
#include <catch2/catch.hpp>
