#pragma once
// The CVODES glue every compiled integrator of pamkit shares (private to the library, not
// installed): RAII handles for the SUNDIALS objects, every return flag checked by name, a
// context that prints nothing, and the counters summed into SolverStatistics.

#include <cvodes/cvodes.h>
#include <sundials/sundials_config.h>
#include <sundials/sundials_context.h>
#include <sundials/sundials_linearsolver.h>
#include <sundials/sundials_matrix.h>
#include <sundials/sundials_nonlinearsolver.h>
#include <sundials/sundials_nvector.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sunnonlinsol/sunnonlinsol_fixedpoint.h>

#include <memory>

#include "pamkit/error.hpp"
#include "pamkit/sim/simulator.hpp"

namespace pamkit::cvodes {

/// \throws SolverError naming `call`, the flag and the time if `flag` reports a failure.
inline void check_flag(int flag, const char* call, double time) {
  if (flag < 0) {
    throw SolverError(detail::message(call, " failed with ", CVodeGetReturnFlagName(flag), " at t = ", time, " s"));
  }
}

struct ContextDeleter {
  void operator()(SUNContext* c) const {
    SUNContext_Free(c);
    delete c;
  }
};
struct VectorDeleter {
  void operator()(_generic_N_Vector* v) const { N_VDestroy(v); }
};
struct MatrixDeleter {
  void operator()(_generic_SUNMatrix* m) const { SUNMatDestroy(m); }
};
struct LinearSolverDeleter {
  void operator()(_generic_SUNLinearSolver* s) const { SUNLinSolFree(s); }
};
struct NonlinearSolverDeleter {
  void operator()(_generic_SUNNonlinearSolver* s) const { SUNNonlinSolFree(s); }
};
struct CvodeDeleter {
  void operator()(void* mem) const { CVodeFree(&mem); }
};
using Context = std::unique_ptr<SUNContext, ContextDeleter>;
using Vector = std::unique_ptr<_generic_N_Vector, VectorDeleter>;
using Matrix = std::unique_ptr<_generic_SUNMatrix, MatrixDeleter>;
using LinearSolver = std::unique_ptr<_generic_SUNLinearSolver, LinearSolverDeleter>;
using NonlinearSolver = std::unique_ptr<_generic_SUNNonlinearSolver, NonlinearSolverDeleter>;
using Memory = std::unique_ptr<void, CvodeDeleter>;

// pamkit reports every failed flag itself, as an exception with the flag's name; CVODES's own
// printing to stderr would only repeat it (and cannot be caught). SUNDIALS 6 silences it per
// solver (CVodeSetErrHandlerFn, see silence_errors); SUNDIALS 7 removed that function and prints
// through handlers held by the context, which make_context() clears.
#if SUNDIALS_VERSION_MAJOR < 7
inline void silent_error_handler(int, const char*, const char*, char*, void*) {}
#endif

inline Context make_context() {
  auto context = std::make_unique<SUNContext>();
#if SUNDIALS_VERSION_MAJOR >= 7
  // SUNDIALS 7 takes the MPI communicator as a SUNComm: SUN_COMM_NULL without MPI.
  if (SUNContext_Create(SUN_COMM_NULL, context.get()) != 0) throw SolverError("SUNContext_Create failed");
  Context owned(context.release());
  if (SUNContext_ClearErrHandlers(*owned) != 0) throw SolverError("SUNContext_ClearErrHandlers failed");
  return owned;
#else
  // SUNDIALS 6 takes a pointer to the MPI communicator: null without MPI.
  if (SUNContext_Create(nullptr, context.get()) != 0) throw SolverError("SUNContext_Create failed");
  return Context(context.release());
#endif
}

/// Stops CVODES printing its errors under SUNDIALS 6 (under 7 the context already does).
inline void silence_errors([[maybe_unused]] void* mem, [[maybe_unused]] double t0) {
#if SUNDIALS_VERSION_MAJOR < 7
  check_flag(CVodeSetErrHandlerFn(mem, silent_error_handler, nullptr), "CVodeSetErrHandlerFn", t0);
#endif
}

/// A CVODES solver owning what CVODES borrows: its memory and, for BDF, the Jacobian matrix and
/// the linear solver of its Newton iteration or, for Adams, its fixed-point iteration (destroyed
/// together, in reverse order of creation).
struct Solver {
  IntegrationMethod method;
  Memory memory;
  Matrix jacobian;
  LinearSolver linear_solver;
  NonlinearSolver fixed_point;
  void* get() const { return memory.get(); }
};
/// The name the BDF-only callers (effects/isotonic_motion.cpp) know it by.
using BdfSolver = Solver;

/// Creates and configures a solver of `method` (bdf or adams) for `rhs` from `y0` at `t0`, every
/// flag checked by name: `user_data` for the right-hand side, per-component absolute
/// `tolerances`, at most `max_steps` between outputs and steps of at most `max_step_s` (0: no
/// limit). BDF iterates with Newton on a dense Jacobian (stable on stiff runs: a fast heat
/// exchange, a sharp tanh friction); Adams with a fixed-point iteration, which needs no Jacobian
/// and converges while the step times the fastest rate stays below about 1.
inline Solver make_solver(IntegrationMethod method, SUNContext ctx, CVRhsFn rhs, double t0, N_Vector y0,
                          void* user_data, double relative_tolerance, N_Vector tolerances, double max_steps,
                          double max_step_s) {
  if (method != IntegrationMethod::bdf && method != IntegrationMethod::adams) {
    throw SolverError(detail::message("make_solver: method ", method, " is neither bdf nor adams"));
  }
  const bool adams = method == IntegrationMethod::adams;
  Solver solver{method, Memory(CVodeCreate(adams ? CV_ADAMS : CV_BDF, ctx)), nullptr, nullptr, nullptr};
  if (!solver.memory) throw SolverError("CVodeCreate failed");
  void* cv = solver.get();
  check_flag(CVodeInit(cv, rhs, t0, y0), "CVodeInit", t0);
  check_flag(CVodeSetUserData(cv, user_data), "CVodeSetUserData", t0);
  silence_errors(cv, t0);
  check_flag(CVodeSVtolerances(cv, relative_tolerance, tolerances), "CVodeSVtolerances", t0);
  check_flag(CVodeSetMaxNumSteps(cv, static_cast<long>(max_steps)), "CVodeSetMaxNumSteps", t0);
  if (max_step_s > 0.0) check_flag(CVodeSetMaxStep(cv, max_step_s), "CVodeSetMaxStep", t0);
  if (adams) {
    // Plain fixed-point iteration (no Anderson acceleration: 0 vectors kept).
    solver.fixed_point.reset(SUNNonlinSol_FixedPoint(y0, 0, ctx));
    if (!solver.fixed_point) throw SolverError("SUNNonlinSol_FixedPoint failed");
    check_flag(CVodeSetNonlinearSolver(cv, solver.fixed_point.get()), "CVodeSetNonlinearSolver", t0);
    return solver;
  }
  const auto size = static_cast<sunindextype>(N_VGetLength(y0));
  solver.jacobian.reset(SUNDenseMatrix(size, size, ctx));
  if (!solver.jacobian) throw SolverError("SUNDenseMatrix failed");
  solver.linear_solver.reset(SUNLinSol_Dense(y0, solver.jacobian.get(), ctx));
  if (!solver.linear_solver) throw SolverError("SUNLinSol_Dense failed");
  check_flag(CVodeSetLinearSolver(cv, solver.linear_solver.get(), solver.jacobian.get()), "CVodeSetLinearSolver", t0);
  return solver;
}

/// A BDF solver with a dense Newton system (make_solver).
inline Solver make_bdf(SUNContext ctx, CVRhsFn rhs, double t0, N_Vector y0, void* user_data, double relative_tolerance,
                       N_Vector tolerances, double max_steps, double max_step_s) {
  return make_solver(IntegrationMethod::bdf, ctx, rhs, t0, y0, user_data, relative_tolerance, tolerances, max_steps,
                     max_step_s);
}

/// Adds the counters of `solver` since its last (re)initialisation to `s`; the linear solver's
/// only where there is one (BDF).
inline void add_statistics(const Solver& solver, SolverStatistics& s) {
  void* mem = solver.get();
  s.method = solver.method;
  long value = 0;
  check_flag(CVodeGetNumSteps(mem, &value), "CVodeGetNumSteps", 0.0);
  s.steps += value;
  check_flag(CVodeGetNumRhsEvals(mem, &value), "CVodeGetNumRhsEvals", 0.0);
  s.rhs_evaluations += value;
  if (solver.linear_solver) {
    check_flag(CVodeGetNumLinRhsEvals(mem, &value), "CVodeGetNumLinRhsEvals", 0.0);
    s.rhs_evaluations += value;  // the difference-quotient Jacobian's
    check_flag(CVodeGetNumJacEvals(mem, &value), "CVodeGetNumJacEvals", 0.0);
    s.jacobian_evaluations += value;
    check_flag(CVodeGetNumLinSolvSetups(mem, &value), "CVodeGetNumLinSolvSetups", 0.0);
    s.linear_solver_setups += value;
  }
  check_flag(CVodeGetNumErrTestFails(mem, &value), "CVodeGetNumErrTestFails", 0.0);
  s.error_test_failures += value;
  check_flag(CVodeGetNumNonlinSolvIters(mem, &value), "CVodeGetNumNonlinSolvIters", 0.0);
  s.nonlinear_iterations += value;
  check_flag(CVodeGetNumNonlinSolvConvFails(mem, &value), "CVodeGetNumNonlinSolvConvFails", 0.0);
  s.nonlinear_convergence_failures += value;
}

}  // namespace pamkit::cvodes
