// SPDX-License-Identifier: GPL-2.0-or-later
// The runtime's untyped kernel calls (kanegen/runtime/kernel_thunks.hpp),
// made from the kernel spec, under the module's names: the Python module
// binds each kernel from its spec rather than by hand.
#pragma once

#include "kanegen/runtime/kernel_thunks.hpp"

namespace kanegen::python {

using Thunk = runtime::KernelThunk;
using runtime::kernel_entries;
using runtime::KernelEntry;

}  // namespace kanegen::python
