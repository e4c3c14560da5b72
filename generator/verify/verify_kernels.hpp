// SPDX-License-Identifier: GPL-2.0-or-later
// Which rows of the report compare which kernel, as the kernel spec lists
// them (the `verify` field of kanegen/runtime/kernels.def): a kernel the
// model has that no row compares gets a row of its own saying so, and a row
// the spec names that the report lacks is an error of kanegen, so that the
// spec and verify cannot drift apart.
#pragma once

#include <string>
#include <vector>

#include "kanegen/runtime/kernel_spec.hpp"
#include "verify/verify_report.hpp"

namespace kanegen::verify {

/// The row names of a kernel's spec ("" gives none).
std::vector<std::string> kernel_rows(const runtime::KernelSpec& spec);

/// For every kernel a model of this kind has (closed loops or not, kernels
/// generated with Jacobians or controller kernels or not): checks that
/// `rows` holds each row its spec names (std::logic_error otherwise) and
/// adds an n/a row, named after the kernel, for one the spec names no row for.
void add_uncompared_kernel_rows(std::vector<Row>& rows, bool loops, bool jacobians, bool controller);

}  // namespace kanegen::verify
