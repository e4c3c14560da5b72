// SPDX-License-Identifier: MIT
// The adaptive implicit method: SUNDIALS CVODE's variable-order BDF (orders
// 1 to opt.max_order, 2 by default for the undamped fast modes of elastic
// links: integrators.hpp), Newton's iteration with a dense LU of I - gamma J
// and the caller's exact Jacobian. Closed loops are projected by CVODE's own
// projection hook (CVodeSetProjFn) after each converged step and before its
// error test, so that the Nordsieck history CVODE extrapolates from holds the
// projected state: projecting CVODE's output from outside would leave the
// history off the constraints. One step at a time (CV_ONE_STEP, stopping at
// t_end), so that max_steps, the observer and every failure are handled as
// for the explicit methods.
#include <cvode/cvode.h>
#include <cvode/cvode_ls.h>
#include <cvode/cvode_proj.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

#include <algorithm>
#include <cstdlib>
#include <string>
#include <vector>

#include "integration_run.hpp"
#include "kanegen/runtime/methods.hpp"

namespace kanegen::runtime::detail {
namespace {

class Cvode {
 public:
  Cvode(Run& run, const Jacobian& jacobian, double* x) : run_(run), jacobian_(jacobian), x_(x), n_(run.n()) {
    J_.assign(static_cast<size_t>(n_) * n_, 0.0);
    work_.assign(static_cast<size_t>(n_), 0.0);
  }
  ~Cvode() {
    if (mem_) CVodeFree(&mem_);
    if (solver_) SUNLinSolFree(solver_);
    if (matrix_) SUNMatDestroy(matrix_);
    if (out_) N_VDestroy(out_);
    if (y_) N_VDestroy(y_);
    if (context_) SUNContext_Free(&context_);
  }
  Cvode(const Cvode&) = delete;
  Cvode& operator=(const Cvode&) = delete;

  // Returns the time of the state left in x.
  double integrate(double t0) {
    const IntegrationOptions& opt = run_.opt();
    const OutputGrid grid(t0, opt.dt, opt.t_end);
    if (!run_.emit(t0, x_) || grid.intervals() == 0) return t0;
    if (!setup(t0)) return t0;
    double t = t0;
    long next = 1;         // index of the next output time
    long steps_taken = 0;  // for opt.on_step (the statistics come from CVODE at the end)
    while (true) {
      if (attempted_steps() >= opt.max_steps) {
        run_.fail(Status::kMaxSteps, max_steps_message(opt), t, x_);
        return t;
      }
      double t_step = t;
      const int flag = CVode(mem_, opt.t_end, y_, &t_step, CV_ONE_STEP);
      if (flag < 0) {
        fail(flag, t_step);
        return t;
      }
      // Output times inside the step from CVODE's interpolant; one at its
      // end from the (projected) step itself.
      for (; next <= grid.intervals() && grid.time(next) < t_step; ++next) {
        if (CVodeGetDky(mem_, grid.time(next), 0, out_) != CV_SUCCESS) {
          run_.fail(Status::kSolverFailed, "CVODE could not interpolate at t=" + number(grid.time(next)), t,
                    x_);
          return t;
        }
        if (!run_.emit(grid.time(next), N_VGetArrayPointer(out_))) return t;
      }
      std::copy(N_VGetArrayPointer(y_), N_VGetArrayPointer(y_) + n_, x_);
      t = t_step;
      if (opt.on_step) opt.on_step(t, ++steps_taken);
      const bool done = flag == CV_TSTOP_RETURN || t >= opt.t_end;
      if (next <= grid.intervals() && (grid.time(next) == t || done)) {
        if (!run_.emit(grid.time(next), x_)) return t;
        ++next;
      }
      if (done) return t;
    }
  }

  // The counters of CVODE, in the run's statistics.
  void record_stats() {
    if (!mem_) return;
    StepStats& s = run_.stats();
    long v = 0;
    if (CVodeGetNumSteps(mem_, &v) == CV_SUCCESS) s.accepted = v;
    if (CVodeGetNumErrTestFails(mem_, &v) == CV_SUCCESS) s.rejected = v;
    if (CVodeGetNumNonlinSolvIters(mem_, &v) == CV_SUCCESS) s.newton_iterations = v;
    if (CVodeGetNumNonlinSolvConvFails(mem_, &v) == CV_SUCCESS) s.newton_failures = v;
    if (CVodeGetNumJacEvals(mem_, &v) == CV_SUCCESS) s.jacobian_evaluations = v;
    // Every setup of the dense direct solver factors I - gamma J anew.
    if (CVodeGetNumLinSolvSetups(mem_, &v) == CV_SUCCESS) s.factorizations = v;
    if (run_.opt().project && CVodeGetNumProjEvals(mem_, &v) == CV_SUCCESS) s.projections = v;
  }

 private:
  // Creates the solver at (t0, x); false (and a failure recorded) if CVODE refuses.
  bool setup(double t0) {
    const IntegrationOptions& opt = run_.opt();
    const auto check = [&](int flag, const char* what) {
      if (flag == CV_SUCCESS) return true;
      run_.fail(Status::kInvalidArgument,
                std::string("CVODE: ") + what + " failed (" + flag_name(flag) + ")" +
                    (message_.empty() ? "" : ": " + message_),
                t0, x_);
      return false;
    };
    if (SUNContext_Create(nullptr, &context_) != 0) return check(CV_MEM_FAIL, "SUNContext_Create");
    y_ = N_VNew_Serial(n_, context_);
    out_ = N_VNew_Serial(n_, context_);
    matrix_ = SUNDenseMatrix(n_, n_, context_);
    if (!y_ || !out_ || !matrix_) return check(CV_MEM_FAIL, "allocation");
    std::copy(x_, x_ + n_, N_VGetArrayPointer(y_));
    solver_ = SUNLinSol_Dense(y_, matrix_, context_);
    mem_ = CVodeCreate(CV_BDF, context_);
    if (!solver_ || !mem_) return check(CV_MEM_FAIL, "allocation");
    // Messages go into the failure, not to stderr.
    if (!check(CVodeSetErrHandlerFn(mem_, &Cvode::on_error, this), "CVodeSetErrHandlerFn") ||
        !check(CVodeInit(mem_, &Cvode::rhs, t0, y_), "CVodeInit") || !check(tolerances(), "tolerances") ||
        !check(CVodeSetUserData(mem_, this), "CVodeSetUserData") ||
        !check(CVodeSetLinearSolver(mem_, solver_, matrix_), "CVodeSetLinearSolver") ||
        !check(CVodeSetJacFn(mem_, &Cvode::jacobian), "CVodeSetJacFn") ||
        !check(CVodeSetStopTime(mem_, opt.t_end), "CVodeSetStopTime") ||
        // With max_order above 2: BDF3-5 are unstable near the imaginary
        // axis; the detection lowers the order when it sees it (it does not
        // for the spin-up beam, hence the default of 2, integrators.hpp).
        !check(CVodeSetStabLimDet(mem_, SUNTRUE), "CVodeSetStabLimDet") ||
        !check(CVodeSetMaxHnilWarns(mem_, -1), "CVodeSetMaxHnilWarns"))
      return false;
    if (!check(CVodeSetMaxOrd(mem_, opt.max_order), "CVodeSetMaxOrd")) return false;
    if (opt.h0 > 0 && !check(CVodeSetInitStep(mem_, opt.h0), "CVodeSetInitStep")) return false;
    if (opt.h_min > 0 && !check(CVodeSetMinStep(mem_, opt.h_min), "CVodeSetMinStep")) return false;
    if (opt.h_max > 0 && !check(CVodeSetMaxStep(mem_, opt.h_max), "CVodeSetMaxStep")) return false;
    if (opt.project) {
      // The error estimate is left unprojected: its part normal to the
      // constraints only makes the error test a little stricter.
      if (!check(CVodeSetProjFn(mem_, &Cvode::project), "CVodeSetProjFn") ||
          !check(CVodeSetProjErrEst(mem_, SUNFALSE), "CVodeSetProjErrEst"))
        return false;
    }
    return true;
  }

  int tolerances() {
    const IntegrationOptions& opt = run_.opt();
    if (opt.atol_per_component.empty()) return CVodeSStolerances(mem_, opt.rtol, opt.atol);
    N_Vector atol = N_VNew_Serial(n_, context_);
    if (!atol) return CV_MEM_FAIL;
    std::copy(opt.atol_per_component.begin(), opt.atol_per_component.end(), N_VGetArrayPointer(atol));
    const int flag = CVodeSVtolerances(mem_, opt.rtol, atol);  // CVODE keeps a copy
    N_VDestroy(atol);
    return flag;
  }

  long attempted_steps() const {
    long steps = 0, error_fails = 0, newton_fails = 0;
    CVodeGetNumSteps(mem_, &steps);
    CVodeGetNumErrTestFails(mem_, &error_fails);
    CVodeGetNumNonlinSolvConvFails(mem_, &newton_fails);
    return steps + error_fails + newton_fails;
  }

  static std::string flag_name(int flag) {
    char* name = CVodeGetReturnFlagName(flag);
    std::string text = name ? name : std::to_string(flag);
    std::free(name);  // CVODE allocates the name
    return text;
  }

  // Records the failure of a step from time t (CVODE left the last accepted
  // state in y).
  void fail(int flag, double t) {
    std::copy(N_VGetArrayPointer(y_), N_VGetArrayPointer(y_) + n_, x_);
    double h = 0.0;
    CVodeGetCurrentStep(mem_, &h);
    const std::string step = " (step size " + number(h) + ")";
    const std::string tol = "rtol " + number(run_.opt().rtol) + ", atol " + number(run_.opt().atol);
    switch (flag) {
      case CV_TOO_MUCH_ACC:
        return run_.fail(Status::kStepSizeTooSmall,
                         "the tolerances (" + tol + ") are too tight for double precision", t, x_);
      case CV_ERR_FAILURE:
        return run_.fail(
            Status::kStepSizeTooSmall,
            "step size " + number(h) + " fell to its minimum: the error test failed repeatedly (" + tol + ")",
            t, x_);
      case CV_CONV_FAILURE:
      case CV_NLS_FAIL:
        return run_.fail(Status::kSolverFailed,
                         "Newton's iteration diverged repeatedly" + step + with_reason(), t, x_);
      case CV_LSETUP_FAIL:
        return run_.fail(
            Status::kSolverFailed,
            "the Jacobian or the LU factorization of the iteration matrix failed" + step + with_reason(), t,
            x_);
      case CV_RHSFUNC_FAIL:  // the Run has recorded why
        return run_.fail(Status::kRhsFailed, "right-hand side failed", t, x_);
      case CV_FIRST_RHSFUNC_ERR:
      case CV_REPTD_RHSFUNC_ERR:
      case CV_UNREC_RHSFUNC_ERR:
        return run_.fail(Status::kNonFinite,
                         (non_finite_.empty() ? std::string("right-hand side not finite") : non_finite_) +
                             ", also with smaller steps" + step + "; last accepted state",
                         t, x_);
      case CV_PROJFUNC_FAIL:
      case CV_REPTD_PROJFUNC_ERR:
        return run_.fail(Status::kRhsFailed, "projection onto the constraints failed: " + projection_failure_,
                         t, x_);
      default:
        return run_.fail(Status::kSolverFailed, "CVODE failed (" + flag_name(flag) + ")" + with_reason(), t,
                         x_);
    }
  }

  std::string with_reason() const {
    std::string why;
    if (!jacobian_failure_.empty()) why = jacobian_failure_;
    if (!non_finite_.empty()) why += (why.empty() ? "" : "; ") + non_finite_;
    if (why.empty() && !message_.empty()) why = "CVODE: " + message_;
    return why.empty() ? "" : " (" + why + ")";
  }

  static Cvode& self(void* data) { return *static_cast<Cvode*>(data); }

  // 0, 1 (non-finite: recoverable, CVODE retries smaller) or -1 (failed, or a stop request).
  static int rhs(sunrealtype t, N_Vector y, N_Vector ydot, void* data) {
    Cvode& c = self(data);
    return c.run_.eval_recoverable(t, N_VGetArrayPointer(y), N_VGetArrayPointer(ydot), &c.non_finite_);
  }

  static int jacobian(sunrealtype t, N_Vector y, N_Vector, SUNMatrix J, void* data, N_Vector, N_Vector,
                      N_Vector) {
    Cvode& c = self(data);
    bool ok = false;
    try {
      ok = c.jacobian_(t, N_VGetArrayPointer(y), c.J_.data());
    } catch (const std::exception& e) {
      c.jacobian_failure_ = std::string("the Jacobian threw: ") + e.what();
      return -1;
    }
    if (!ok || !all_finite(c.J_.data(), c.n_ * c.n_)) {
      c.jacobian_failure_ = "the Jacobian could not be evaluated at t=" + number(t);
      return 1;  // recoverable: CVODE retries with a smaller step
    }
    // Row-major in, column-major dense SUNMatrix out.
    const int n = c.n_;
    for (int j = 0; j < n; ++j) {
      double* column = SUNDenseMatrix_Column(J, j);
      for (int i = 0; i < n; ++i) column[i] = c.J_[static_cast<size_t>(i) * n + j];
    }
    return 0;
  }

  static int project(sunrealtype t, N_Vector ycur, N_Vector corr, sunrealtype, N_Vector, void* data) {
    Cvode& c = self(data);
    const double* y = N_VGetArrayPointer(ycur);
    std::copy(y, y + c.n_, c.work_.begin());
    std::string why;
    bool ok = false;
    try {
      ok = c.run_.opt().project(t, c.work_.data(), &why);
    } catch (const std::exception& e) {
      why = e.what();
    }
    if (!ok) {
      c.projection_failure_ = why + " at t=" + number(t);
      return 1;  // recoverable: a smaller step may stay nearer the constraints
    }
    double* dy = N_VGetArrayPointer(corr);
    for (int i = 0; i < c.n_; ++i) dy[i] = c.work_[i] - y[i];
    return 0;
  }

  static void on_error(int code, const char*, const char* function, char* msg, void* data) {
    if (code == CV_WARNING) return;
    self(data).message_ = std::string(function ? function : "") + ": " + (msg ? msg : "");
  }

  Run& run_;
  const Jacobian& jacobian_;
  double* x_;
  int n_;
  std::vector<double> J_, work_;
  std::string message_, non_finite_, jacobian_failure_, projection_failure_;
  SUNContext context_ = nullptr;
  N_Vector y_ = nullptr, out_ = nullptr;
  SUNMatrix matrix_ = nullptr;
  SUNLinearSolver solver_ = nullptr;
  void* mem_ = nullptr;
};

}  // namespace

IntegrationResult integrate_cvode(Run& run, const Jacobian& jacobian, double t0, double* x) {
  Cvode cvode(run, jacobian, x);
  const double t = cvode.integrate(t0);
  cvode.record_stats();
  return run.finish(t);
}

}  // namespace kanegen::runtime::detail
