// SPDX-License-Identifier: GPL-2.0-or-later
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

/// The C++ local that holds the given acceleration of prescribed speed
/// `speed` in the emitted dynamics ("ap<speed>").
std::string prescribed_acceleration_name(int speed);

class Variables {
 public:
  /// Creates the symbols for `model`: per moving joint (file order) one
  /// speed and input per speed, each with a coordinate of the same index (a
  /// spherical joint's quaternion x, y, z); then elastic_counts[b] elastic
  /// coordinates and speeds for each flexible body b (file order; no
  /// inputs); then the spherical joints' quaternion w (so q[i] belongs to
  /// u[i] for i < nu); and one symbol per parameter.
  explicit Variables(const model::Model& model, const std::vector<int>& elastic_counts = {});

  GiNaC::symbol t{"t"};
  std::vector<GiNaC::symbol> q, u, tau, params;
  /// One per speed: the accelerations given to inverse_dynamics ("udot[i]").
  std::vector<GiNaC::symbol> udot;
  int joint_coordinates = 0;  ///< q[0 .. joint_coordinates) belong to joints
  /// Per joint (Model::joints order): the index of its first speed, or -1 for a fixed joint.
  std::vector<int> first_speed;
  /// Per spherical joint (by index in Model::joints): the index in q of its quaternion's w.
  std::map<int, int> quaternion_w;
  std::vector<int> elastic_first;  ///< per body: index in q of its first elastic coordinate, or -1
  std::vector<int> elastic_count;  ///< per body: its number of elastic coordinates
  /// Per prescribed speed index: the symbol of its given acceleration (a
  /// local of the emitted forward dynamics, "ap<index>").
  std::map<int, GiNaC::symbol> prescribed_acceleration;

  /// The model scalar as an expression: numbers fold in, expressions over
  /// parameters stay symbolic. Throws model::ModelError on a bad expression.
  GiNaC::ex scalar(const model::Scalar& s) const;

  /// An expression in the time t and the parameters (a prescribed motion).
  GiNaC::ex time_expression(const std::string& text, const std::string& where) const;
  /// The value of an expression in t and the parameters at time t, with the parameters' defaults.
  double at_defaults(const GiNaC::ex& e, double time) const;

  /// C++ text for an input symbol ("q[0]", "p.m1", "t"), or "" if unknown.
  std::string cpp_name(const GiNaC::symbol& s) const;

 private:
  std::string source_file_;
  GiNaC::exmap defaults_;  ///< parameter symbol -> its default value
  GiNaC::symtab parameter_table_;
  std::map<GiNaC::symbol, std::string, GiNaC::ex_is_less> cpp_names_;
};

}  // namespace kanegen::symbolic
