// SPDX-License-Identifier: MIT
// A generated System behind a virtual interface, so that everything in the
// runner that does not depend on the particular model is compiled once in
// the runtime library instead of in every model's executable.
#pragma once

#include <type_traits>
#include <utility>

#include "kanegen/runtime/system.hpp"

namespace kanegen::runtime {

/// Sizes, names and initial state of a model (pointers into generated code).
struct ModelInfo {
  const char* name;
  int nq, nu, ntau, ny, np;
  const char* const* coordinate_names;
  const char* const* speed_names;
  const char* const* input_names;
  const char* const* output_names;
  const char* const* parameter_names;
  const double* q0;
  const double* u0;
  /// Closed loops (0 and null for an open tree).
  int nc = 0;
  const char* const* constraint_names = nullptr;
  const int* coordinate_roles = nullptr;  ///< nq: 0 free, 1 marked independent, 2 prescribed
};

/// A model together with one set of parameter values. The functions are
/// those of system.hpp with the parameters bound.
class Model {
 public:
  explicit Model(const ModelInfo& info) : info_(info) {}
  virtual ~Model() = default;
  const ModelInfo& info() const { return info_; }

  virtual bool set_parameter(const char* name, double value) = 0;  ///< false if unknown
  virtual double parameter(int index) const = 0;
  virtual void mass_matrix(const double* q, double* M) const = 0;
  virtual void forcing(double t, const double* q, const double* u, const double* tau, double* f) const = 0;
  /// 0 on success, k > 0 if the k-th pivot of the mass matrix was not positive.
  virtual int forward_dynamics(double t, const double* q, const double* u, const double* tau,
                               double* udot) const = 0;
  virtual void coordinate_rates(const double* q, const double* u, double* qdot) const = 0;
  virtual double kinetic_energy(const double* q, const double* u) const = 0;
  virtual double potential_energy(const double* q) const = 0;
  virtual void outputs(double t, const double* q, const double* u, double* y) const = 0;
  /// The initial state for the current parameters (a prescribed coordinate
  /// starts where its motion does); info().q0, u0 hold it for the defaults.
  virtual void initial_state(double* q, double* u) const = 0;

  // Closed loops (info().nc > 0; no-ops for an open tree).
  /// phi: nc, the loop-closure residuals.
  virtual void constraints(const double* q, double* phi) const = 0;
  /// C: nc*nu, row-major, dPhi/dq.
  virtual void constraint_jacobian(const double* q, double* C) const = 0;
  /// gamma: nc, the acceleration-level right-hand side, C udot = gamma = -(dC/dt) u.
  virtual void constraint_bias(const double* q, const double* u, double* gamma) const = 0;
  /// udot: nu, lambda: nc; as forward_dynamics, and -k for a singular configuration (nearly dependent loop
  /// equations).
  virtual int constrained_dynamics(double t, const double* q, const double* u, const double* tau,
                                   double* udot, double* lambda) const = 0;

 private:
  ModelInfo info_;
};

/// The Model of a generated System, with its default parameters.
template <class System>
class SystemModel final : public Model {
 public:
  SystemModel()
      : Model(ModelInfo{System::name, System::nq, System::nu, System::ntau, System::ny, System::np,
                        System::coordinate_names(), System::speed_names(), System::input_names(),
                        System::output_names(), System::parameter_names(), System::q0(), System::u0(),
                        loops<System>::nc, loops<System>::names(), loops<System>::roles()}) {}

  bool set_parameter(const char* name, double value) override {
    return System::set_parameter(params_, name, value);
  }
  double parameter(int index) const override { return System::get_parameter(params_, index); }
  void mass_matrix(const double* q, double* M) const override { System::mass_matrix(params_, q, M); }
  void forcing(double t, const double* q, const double* u, const double* tau, double* f) const override {
    System::forcing(params_, t, q, u, tau, f);
  }
  int forward_dynamics(double t, const double* q, const double* u, const double* tau,
                       double* udot) const override {
    return System::forward_dynamics(params_, t, q, u, tau, udot);
  }
  void coordinate_rates(const double* q, const double* u, double* qdot) const override {
    System::coordinate_rates(q, u, qdot);
  }
  double kinetic_energy(const double* q, const double* u) const override {
    return System::kinetic_energy(params_, q, u);
  }
  double potential_energy(const double* q) const override { return System::potential_energy(params_, q); }
  void outputs(double t, const double* q, const double* u, double* y) const override {
    System::outputs(params_, t, q, u, y);
  }
  void initial_state(double* q, double* u) const override { initial_state_of<System>(0, q, u); }
  void constraints(const double* q, double* phi) const override {
    loops<System>::constraints(params_, q, phi);
  }
  void constraint_jacobian(const double* q, double* C) const override {
    loops<System>::jacobian(params_, q, C);
  }
  void constraint_bias(const double* q, const double* u, double* gamma) const override {
    loops<System>::bias(params_, q, u, gamma);
  }
  int constrained_dynamics(double t, const double* q, const double* u, const double* tau, double* udot,
                           double* lambda) const override {
    return loops<System>::dynamics(params_, t, q, u, tau, udot, lambda);
  }

 private:
  // The loop functions of a System that has closed loops (S::nc), else
  // those of an open tree.
  template <class S, class = void>
  struct loops {
    static constexpr int nc = 0;
    static const char* const* names() { return nullptr; }
    static const int* roles() { return nullptr; }
    static void constraints(const typename S::Params&, const double*, double*) {}
    static void jacobian(const typename S::Params&, const double*, double*) {}
    static void bias(const typename S::Params&, const double*, const double*, double*) {}
    static int dynamics(const typename S::Params& p, double t, const double* q, const double* u,
                        const double* tau, double* udot, double*) {
      return S::forward_dynamics(p, t, q, u, tau, udot);
    }
  };
  template <class S>
  struct loops<S, std::void_t<decltype(S::nc)>> {
    static constexpr int nc = S::nc;
    static const char* const* names() { return S::constraint_names(); }
    static const int* roles() { return S::coordinate_roles(); }
    static void constraints(const typename S::Params& p, const double* q, double* phi) {
      S::constraints(p, q, phi);
    }
    static void jacobian(const typename S::Params& p, const double* q, double* C) {
      S::constraint_jacobian(p, q, C);
    }
    static void bias(const typename S::Params& p, const double* q, const double* u, double* gamma) {
      S::constraint_bias(p, q, u, gamma);
    }
    static int dynamics(const typename S::Params& p, double t, const double* q, const double* u,
                        const double* tau, double* udot, double* lambda) {
      return S::constrained_dynamics(p, t, q, u, tau, udot, lambda);
    }
  };

  // System::initial_state(p, q, u) if the System has it (generated ones do),
  // else the constant q0 and u0.
  template <class S>
  auto initial_state_of(int, double* q, double* u) const
      -> decltype(S::initial_state(std::declval<const typename S::Params&>(), q, u)) {
    return S::initial_state(params_, q, u);
  }
  template <class S>
  void initial_state_of(long, double* q, double* u) const {
    for (int i = 0; i < S::nq; ++i) q[i] = S::q0()[i];
    for (int i = 0; i < S::nu; ++i) u[i] = S::u0()[i];
  }

  typename System::Params params_{};
};

}  // namespace kanegen::runtime
