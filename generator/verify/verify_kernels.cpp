// SPDX-License-Identifier: GPL-2.0-or-later
#include "verify/verify_kernels.hpp"

#include <algorithm>
#include <stdexcept>

namespace kanegen::verify {

std::vector<std::string> kernel_rows(const runtime::KernelSpec& spec) {
  std::vector<std::string> rows;
  const std::string text = spec.verify;
  for (std::size_t start = 0; start < text.size();) {
    std::size_t end = text.find(';', start);
    if (end == std::string::npos) end = text.size();
    rows.push_back(text.substr(start, end - start));
    start = end + 1;
  }
  return rows;
}

void add_uncompared_kernel_rows(std::vector<Row>& rows, bool loops, bool jacobians, bool controller) {
  const auto reported = [&rows](const std::string& quantity) {
    return std::any_of(rows.begin(), rows.end(), [&](const Row& r) { return r.quantity == quantity; });
  };
  for (const runtime::KernelSpec& spec : runtime::kernel_specs) {
    if (!runtime::kernel_present(spec.presence, loops, jacobians, controller)) continue;
    const std::vector<std::string> names = kernel_rows(spec);
    for (const std::string& name : names)
      if (!reported(name))
        throw std::logic_error(std::string("kernels.def says verify compares ") + spec.name +
                               " in the row '" + name + "', which the report lacks");
    if (!names.empty()) continue;
    rows.emplace_back(spec.name, "-", 0.0);
    rows.back().applicable = false;
    rows.back().note = "not compared (kernels.def names no check of it)";
  }
}

}  // namespace kanegen::verify
