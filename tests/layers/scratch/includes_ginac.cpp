// SPDX-License-Identifier: GPL-2.0-or-later
// A numeric source that includes GiNaC: its compilation must stop.
#include <ginac/ginac.h>

int kanegen_scratch_ginac() { return 0; }
