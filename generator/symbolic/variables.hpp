// The inputs of the generated kernels as GiNaC symbols: time, coordinates,
// speeds, inputs and model parameters, each with the C++ text that names it
// in the emitted code.
#pragma once

#include <ginac/ginac.h>

#include <map>
#include <string>
#include <vector>

#include "model/model.hpp"

namespace kanegen::symbolic {

/// A literal of the model as an expression; integral values stay exact.
GiNaC::ex number(double value);

class Variables {
 public:
  /// Creates the symbols for `model`: one coordinate, speed and input per
  /// moving joint (file order) and one symbol per parameter.
  explicit Variables(const model::Model& model);

  GiNaC::symbol t{"t"};
  std::vector<GiNaC::symbol> q, u, tau, params;

  /// The model scalar as an expression: numbers fold in, expressions over
  /// parameters stay symbolic. Throws model::ModelError on a bad expression.
  GiNaC::ex scalar(const model::Scalar& s) const;

  /// C++ text for an input symbol ("q[0]", "p.m1", "t"), or "" if unknown.
  std::string cpp_name(const GiNaC::symbol& s) const;

 private:
  std::string source_file_;
  GiNaC::symtab parameter_table_;
  std::map<GiNaC::symbol, std::string, GiNaC::ex_is_less> cpp_names_;
};

}  // namespace kanegen::symbolic
