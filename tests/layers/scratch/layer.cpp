// SPDX-License-Identifier: GPL-2.0-or-later
// Any layer of the scratch project: ordinary headers compile in a GiNaC-free layer.
#include <string>
#include <vector>

int kanegen_scratch_layer() { return static_cast<int>(std::vector<std::string>{"layer"}.size()); }
