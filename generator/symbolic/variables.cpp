#include "symbolic/variables.hpp"

#include <cmath>
#include <stdexcept>

#include "model/model_error.hpp"

namespace kanegen::symbolic {

GiNaC::ex number(double value) {
  // Integers stay exact so that 0 and 1 simplify away in products.
  if (std::abs(value) < 1e15 && value == std::floor(value)) return GiNaC::numeric(static_cast<long>(value));
  return GiNaC::numeric(value);
}

Variables::Variables(const model::Model& model) : source_file_(model.source_file) {
  cpp_names_[t] = "t";
  int index = 0;
  for (const auto& joint : model.joints) {
    if (!joint.moves()) continue;
    const std::string i = std::to_string(index++);
    q.emplace_back("q" + i);
    u.emplace_back("u" + i);
    tau.emplace_back("tau" + i);
    cpp_names_[q.back()] = "q[" + i + "]";
    cpp_names_[u.back()] = "u[" + i + "]";
    cpp_names_[tau.back()] = "tau[" + i + "]";
  }
  for (const auto& parameter : model.parameters) {
    params.emplace_back("p_" + parameter.name);
    parameter_table_[parameter.name] = params.back();
    cpp_names_[params.back()] = "p." + parameter.name;
  }
  parameter_table_["pi"] = GiNaC::Pi;
}

GiNaC::ex Variables::scalar(const model::Scalar& s) const {
  if (s.is_literal) return number(s.value);
  GiNaC::parser reader(parameter_table_, /*strict=*/true);
  try {
    return reader(s.text);
  } catch (const std::exception& e) {
    throw model::ModelError(source_file_, s.where, "cannot read expression '" + s.text + "' (" + e.what() + ")",
                            "use numbers, parameter names, + - * / ^, parentheses and sin cos tan sqrt exp log");
  }
}

std::string Variables::cpp_name(const GiNaC::symbol& s) const {
  auto it = cpp_names_.find(s);
  return it == cpp_names_.end() ? std::string() : it->second;
}

}  // namespace kanegen::symbolic
