// SPDX-License-Identifier: GPL-2.0-or-later
// pinocchio_peer: Pinocchio's ABA, RNEA, CRBA and computeABADerivatives on a
// model built from kanegen's own parsed model (kanegen::model::load_model),
// for bench_pinocchio. Pinocchio's headers stay in pinocchio_peer.cpp (they
// take minutes to compile); this interface is plain C++.
//
// Every vector and matrix here is in kanegen's coordinate order (the order of
// coordinate_names: URDF file order); Pinocchio's own order (depth-first
// joint ids, idx_v) is mapped by joint name inside. The timed calls (the
// *_state functions) work on states stored in Pinocchio's order beforehand,
// so that no permutation is timed.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "model/model.hpp"

namespace kanegen_bench {

class PinocchioPeer {
 public:
  /// Builds the Pinocchio model: revolute, continuous and prismatic joints
  /// (bounded revolute, nq = 1; axis-aligned joints as RX/RY/RZ or PX/PY/PZ
  /// like Pinocchio's URDF parser, other axes unaligned), fixed joints merged
  /// into their parent joint, the bodies' inertia about the COM, kanegen's
  /// gravity. coordinates: kanegen's coordinate names (= joint names).
  /// Throws std::runtime_error on anything it does not model (springs,
  /// dampers, other joint types, loops, flexible bodies, expressions).
  PinocchioPeer(const kanegen::model::Model& model, const std::vector<std::string>& coordinates);
  ~PinocchioPeer();
  PinocchioPeer(const PinocchioPeer&) = delete;
  PinocchioPeer& operator=(const PinocchioPeer&) = delete;

  int nv() const;

  // Values, in kanegen's order (n = nv()).
  void aba(const double* q, const double* v, const double* tau, double* ddq);
  void rnea(const double* q, const double* v, const double* a, double* tau);
  /// M (n*n, row-major), crba's upper triangle mirrored.
  void crba(const double* q, double* M);
  /// ddq_dq, ddq_dv, Minv (n*n each, row-major; Minv symmetrized).
  void aba_derivatives(const double* q, const double* v, const double* tau, double* ddq_dq, double* ddq_dv,
                       double* Minv);

  // Timing: the states (count x n each, kanegen order) are stored in
  // Pinocchio's order; the calls below evaluate state k.
  void store_states(int count, const double* q, const double* v, const double* a, const double* tau);
  void aba_state(int k);
  void rnea_state(int k);
  void crba_state(int k);
  void aba_derivatives_state(int k);
  /// A value of the last result, so the calls cannot be optimized out.
  double sink() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace kanegen_bench
