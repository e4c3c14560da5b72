// SPDX-License-Identifier: MIT
// Look-ups in the registry of methods (methods.hpp). Nothing here calls a
// method: the table only points at them.
#include "kanegen/runtime/methods.hpp"

namespace kanegen::runtime {

// "unknown" for a value outside the enum (a cast integer), as before the registry.
const char* method_name(Method method) {
  return static_cast<std::size_t>(method) < kMethodCount ? method_spec(method).name : "unknown";
}

Method implicit_method() { return method_spec(Method::kImplicit).alias_of; }

const MethodSpec* find_method(std::string_view name) {
  for (const MethodSpec& m : kMethods)
    if (name == m.name) return &m;
  return nullptr;
}

bool parse_method(std::string_view text, Method* method) {
  const MethodSpec* m = find_method(text);
  if (m != nullptr) *method = m->method;
  return m != nullptr;
}

std::vector<std::string> method_names() {
  std::vector<std::string> names;
  for (const MethodSpec& m : kMethods) names.emplace_back(m.name);
  return names;
}

}  // namespace kanegen::runtime
