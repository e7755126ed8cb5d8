/**
 * \file cvode_solver.hpp
 * \brief Internal: the RAII CVODE integrator the theory module's ODEs share (BDF, dense Newton,
 *        per-component tolerances, every SUNDIALS call checked and named in the error).
 *
 * Not part of the public API (namespace gdsmc::theory::detail); used by theory.cpp (constant
 * restitution), diffusion.cpp (viscoelastic restitution) and smoluchowski.cpp (cluster sizes).
 *
 * The default is BDF with a dense difference-quotient Jacobian, right for a few dozen components:
 * it costs n right-hand sides per Jacobian and n^3 per factorisation; CvodeOptions::jacobian
 * replaces the difference quotients by the caller's Jacobian. Larger systems choose through
 * CvodeOptions a matrix-free SPGMR Krylov solver (stiff; with CvodeOptions::jacobian_diagonal
 * left-preconditioned by the diagonal of CVODE's Newton matrix I - gamma J), or Adams with
 * fixed-point iteration (non-stiff problems only; no linear algebra at all). start_time lets an
 * integration go on from a state at t > 0 (smoluchowski.cpp widens its system that way).
 */
#pragma once

#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunlinsol/sunlinsol_spgmr.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sunnonlinsol/sunnonlinsol_fixedpoint.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <memory>
#include <span>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

namespace gdsmc::theory::detail {


struct ContextDeleter {
  void operator()(SUNContext context) const { SUNContext_Free(&context); }
};
struct VectorDeleter {
  void operator()(N_Vector vector) const { N_VDestroy(vector); }
};
struct MatrixDeleter {
  void operator()(SUNMatrix matrix) const { SUNMatDestroy(matrix); }
};
struct LinearSolverDeleter {
  void operator()(SUNLinearSolver solver) const { SUNLinSolFree(solver); }
};
struct NonlinearSolverDeleter {
  void operator()(SUNNonlinearSolver solver) const { SUNNonlinSolFree(solver); }
};
struct CvodeDeleter {
  void operator()(void* memory) const { CVodeFree(&memory); }
};

using ContextPtr = std::unique_ptr<std::remove_pointer_t<SUNContext>, ContextDeleter>;
using VectorPtr = std::unique_ptr<std::remove_pointer_t<N_Vector>, VectorDeleter>;
using MatrixPtr = std::unique_ptr<std::remove_pointer_t<SUNMatrix>, MatrixDeleter>;
using LinearSolverPtr = std::unique_ptr<std::remove_pointer_t<SUNLinearSolver>, LinearSolverDeleter>;
using NonlinearSolverPtr =
    std::unique_ptr<std::remove_pointer_t<SUNNonlinearSolver>, NonlinearSolverDeleter>;
using CvodeMemoryPtr = std::unique_ptr<void, CvodeDeleter>;

/// How CVODE solves its implicit stage equations.
enum class CvodeMethod {
  bdf_dense,          ///< BDF, Newton, dense LU of a difference-quotient Jacobian
  bdf_spgmr,          ///< BDF, Newton, matrix-free GMRES without preconditioner
  adams_fixed_point,  ///< Adams-Moulton, fixed-point iteration (no linear algebra; non-stiff only)
};

struct CvodeOptions {
  CvodeMethod method = CvodeMethod::bdf_dense;
  long max_steps = 200000;
  double start_time = 0.0;  ///< the time of y0
  /// bdf_dense: the Jacobian df/dy written into a column-major n x n array (zeroed before the call)
  /// instead of CVODE's difference quotients (n right-hand sides per Jacobian).
  std::function<void(double, std::span<const double>, double*)> jacobian;
  /// bdf_spgmr: the diagonal of df/dy; GMRES is then left-preconditioned by
  /// diag(1 - gamma df_i/dy_i)^-1 (CVODE's Newton matrix I - gamma J reduced to its diagonal).
  std::function<void(double, std::span<const double>, std::span<double>)> jacobian_diagonal;
};

class CvodeSolver {
 public:
  /// dy/dt = rhs(t, y); rhs may throw, the exception message is reported by the failing CVode call.
  using RightHandSide = std::function<void(double, std::span<const double>, std::span<double>)>;

  /// Error weights 1/(relative_tolerance[i] |y_i| + absolute_tolerance[i]), one pair per component
  /// (CVODE's scalar rtol cannot express "absolute only" for the ln T components).
  CvodeSolver(RightHandSide rhs, const std::vector<double>& y0,
              std::vector<double> relative_tolerance, std::vector<double> absolute_tolerance)
      : CvodeSolver(std::move(rhs), y0, std::move(relative_tolerance),
                    std::move(absolute_tolerance), CvodeOptions{}) {}

  CvodeSolver(RightHandSide rhs, const std::vector<double>& y0,
              std::vector<double> relative_tolerance, std::vector<double> absolute_tolerance,
              CvodeOptions options)
      : rhs_(std::move(rhs)),
        size_(y0.size()),
        relative_tolerance_(std::move(relative_tolerance)),
        absolute_tolerance_(std::move(absolute_tolerance)) {
    const auto n = static_cast<sunindextype>(size_);
    SUNContext raw_context = nullptr;
    check(SUNContext_Create(nullptr, &raw_context), "SUNContext_Create");
    context_.reset(raw_context);

    state_.reset(check_pointer(N_VNew_Serial(n, context_.get()), "N_VNew_Serial"));
    std::copy(y0.begin(), y0.end(), N_VGetArrayPointer(state_.get()));

    const bool adams = options.method == CvodeMethod::adams_fixed_point;
    memory_.reset(
        check_pointer(CVodeCreate(adams ? CV_ADAMS : CV_BDF, context_.get()), "CVodeCreate"));
    check(CVodeSetErrHandlerFn(memory_.get(), &CvodeSolver::record_error, this),
          "CVodeSetErrHandlerFn");
    check(CVodeInit(memory_.get(), &CvodeSolver::evaluate_rhs, options.start_time, state_.get()), "CVodeInit");
    check(CVodeSetUserData(memory_.get(), this), "CVodeSetUserData");
    check(CVodeWFtolerances(memory_.get(), &CvodeSolver::error_weights), "CVodeWFtolerances");
    check(CVodeSetMaxNumSteps(memory_.get(), options.max_steps), "CVodeSetMaxNumSteps");

    switch (options.method) {
      case CvodeMethod::bdf_dense: {
        matrix_.reset(check_pointer(SUNDenseMatrix(n, n, context_.get()), "SUNDenseMatrix"));
        linear_solver_.reset(
            check_pointer(SUNLinSol_Dense(state_.get(), matrix_.get(), context_.get()),
                          "SUNLinSol_Dense"));
        attach_linear_solver();
        if (options.jacobian) {
          jacobian_ = std::move(options.jacobian);
          const int flag = CVodeSetJacFn(memory_.get(), &CvodeSolver::evaluate_jacobian);
          if (flag != CVLS_SUCCESS) fail("CVodeSetJacFn", CVodeGetLinReturnFlagName(flag));
        }
        break;
      }
      case CvodeMethod::bdf_spgmr: {
        const bool preconditioned = static_cast<bool>(options.jacobian_diagonal);
        linear_solver_.reset(check_pointer(
            SUNLinSol_SPGMR(state_.get(), preconditioned ? SUN_PREC_LEFT : SUN_PREC_NONE, 0,
                            context_.get()),
            "SUNLinSol_SPGMR"));
        attach_linear_solver();
        if (preconditioned) {
          jacobian_diagonal_ = std::move(options.jacobian_diagonal);
          preconditioner_.assign(size_, 1.0);
          const int flag = CVodeSetPreconditioner(memory_.get(), &CvodeSolver::setup_preconditioner,
                                                  &CvodeSolver::solve_preconditioner);
          if (flag != CVLS_SUCCESS) fail("CVodeSetPreconditioner", CVodeGetLinReturnFlagName(flag));
        }
        break;
      }
      case CvodeMethod::adams_fixed_point:
        nonlinear_solver_.reset(check_pointer(
            SUNNonlinSol_FixedPoint(state_.get(), 0, context_.get()), "SUNNonlinSol_FixedPoint"));
        check(CVodeSetNonlinearSolver(memory_.get(), nonlinear_solver_.get()),
              "CVodeSetNonlinearSolver");
        break;
    }
  }

  CvodeSolver(const CvodeSolver&) = delete;  // CVODE holds `this` as user data
  CvodeSolver& operator=(const CvodeSolver&) = delete;

  /// Advances to t_out (> current time) and interpolates the state there (CV_NORMAL).
  void advance_to(double t_out) {
    sunrealtype t_reached = 0.0;
    check(CVode(memory_.get(), t_out, state_.get(), &t_reached, CV_NORMAL), "CVode");
  }

  std::span<const double> state() const {
    return {N_VGetArrayPointer(state_.get()), size_};
  }

  /// Right-hand-side evaluations so far (CVODE's own, excluding Jacobian and Krylov ones).
  long rhs_evaluations() const {
    long count = 0;
    CVodeGetNumRhsEvals(memory_.get(), &count);
    return count;
  }

 private:
  void attach_linear_solver() {
    const int flag = CVodeSetLinearSolver(memory_.get(), linear_solver_.get(), matrix_.get());
    if (flag != CVLS_SUCCESS) fail("CVodeSetLinearSolver", CVodeGetLinReturnFlagName(flag));
  }


  static int evaluate_rhs(sunrealtype t, N_Vector y, N_Vector ydot, void* user_data) {
    auto* self = static_cast<CvodeSolver*>(user_data);
    const std::span<const double> state{N_VGetArrayPointer(y), self->size_};
    const std::span<double> derivative{N_VGetArrayPointer(ydot), self->size_};
    try {
      self->rhs_(t, state, derivative);
    } catch (const std::exception& error) {
      self->rhs_error_ = error.what();
      return -1;  // unrecoverable
    }
    for (double d : derivative)
      if (!std::isfinite(d)) return 1;  // recoverable: CVODE retries with a smaller step
    return 0;
  }

  static int evaluate_jacobian(sunrealtype t, N_Vector y, N_Vector, SUNMatrix jacobian,
                               void* user_data, N_Vector, N_Vector, N_Vector) {
    auto* self = static_cast<CvodeSolver*>(user_data);
    SUNMatZero(jacobian);
    try {
      self->jacobian_(t, {N_VGetArrayPointer(y), self->size_}, SUNDenseMatrix_Data(jacobian));
    } catch (const std::exception& error) {
      self->rhs_error_ = error.what();
      return -1;
    }
    return 0;
  }

  static int setup_preconditioner(sunrealtype t, N_Vector y, N_Vector, sunbooleantype,
                                  sunbooleantype* jacobian_current, sunrealtype gamma,
                                  void* user_data) {
    auto* self = static_cast<CvodeSolver*>(user_data);
    try {
      self->jacobian_diagonal_(t, {N_VGetArrayPointer(y), self->size_}, self->preconditioner_);
    } catch (const std::exception& error) {
      self->rhs_error_ = error.what();
      return -1;
    }
    for (double& d : self->preconditioner_) {
      d = 1.0 - gamma * d;  // diagonal of I - gamma J
      if (!std::isfinite(d) || d == 0.0) return 1;
    }
    *jacobian_current = SUNTRUE;
    return 0;
  }

  static int solve_preconditioner(sunrealtype, N_Vector, N_Vector, N_Vector r, N_Vector z,
                                  sunrealtype, sunrealtype, int, void* user_data) {
    const auto* self = static_cast<const CvodeSolver*>(user_data);
    const double* in = N_VGetArrayPointer(r);
    double* out = N_VGetArrayPointer(z);
    for (std::size_t i = 0; i < self->size_; ++i) out[i] = in[i] / self->preconditioner_[i];
    return 0;
  }

  static int error_weights(N_Vector y, N_Vector weight, void* user_data) {
    const auto* self = static_cast<const CvodeSolver*>(user_data);
    const double* value = N_VGetArrayPointer(y);
    double* w = N_VGetArrayPointer(weight);
    for (std::size_t i = 0; i < self->size_; ++i) {
      const double tolerance =
          self->relative_tolerance_[i] * std::abs(value[i]) + self->absolute_tolerance_[i];
      if (!(tolerance > 0.0)) return -1;
      w[i] = 1.0 / tolerance;
    }
    return 0;
  }

  static void record_error(int, const char*, const char* function, char* message, void* data) {
    static_cast<CvodeSolver*>(data)->sundials_message_ = std::string(function) + ": " + message;
  }

  void check(int flag, const char* call) {
    if (flag >= 0) return;
    fail(call, memory_ ? CVodeGetReturnFlagName(flag) : nullptr, flag);
  }

  template <class Pointer>
  Pointer check_pointer(Pointer pointer, const char* call) {
    if (pointer == nullptr) fail(call, "returned NULL");
    return pointer;
  }

  [[noreturn]] void fail(const char* call, char* flag_name, int flag = 0) {
    std::string what = std::string("SUNDIALS call ") + call + " failed";
    if (flag_name != nullptr) {
      what += std::string(" (") + flag_name + ")";
      std::free(flag_name);  // CVodeGet*ReturnFlagName returns malloc'ed memory
    } else if (flag != 0) {
      what += " (flag " + std::to_string(flag) + ")";
    }
    if (!sundials_message_.empty()) what += ": " + sundials_message_;
    if (!rhs_error_.empty()) what += "; right-hand side: " + rhs_error_;
    throw std::runtime_error(what);
  }
  [[noreturn]] void fail(const char* call, const char* reason) {
    throw std::runtime_error(std::string("SUNDIALS call ") + call + " " + reason);
  }

  RightHandSide rhs_;
  std::function<void(double, std::span<const double>, double*)> jacobian_;
  std::function<void(double, std::span<const double>, std::span<double>)> jacobian_diagonal_;
  std::vector<double> preconditioner_;  // diagonal of I - gamma J (bdf_spgmr with jacobian_diagonal)
  std::size_t size_;
  std::vector<double> relative_tolerance_;
  std::vector<double> absolute_tolerance_;
  std::string sundials_message_;
  std::string rhs_error_;
  // Declaration order = reverse destruction order: the integrator goes first, the context last.
  ContextPtr context_;
  VectorPtr state_;
  MatrixPtr matrix_;
  LinearSolverPtr linear_solver_;
  NonlinearSolverPtr nonlinear_solver_;
  CvodeMemoryPtr memory_;
};


}  // namespace gdsmc::theory::detail
