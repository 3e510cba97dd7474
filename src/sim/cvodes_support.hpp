#pragma once
// The CVODES glue every compiled integrator of pamkit shares (private to the library, not
// installed): RAII handles for the SUNDIALS objects, every return flag checked by name, a
// context that prints nothing, and the counters summed into SolverStatistics.

#include <cvodes/cvodes.h>
#include <sundials/sundials_config.h>
#include <sundials/sundials_context.h>
#include <sundials/sundials_linearsolver.h>
#include <sundials/sundials_matrix.h>
#include <sundials/sundials_nvector.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

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
struct CvodeDeleter {
  void operator()(void* mem) const { CVodeFree(&mem); }
};
using Context = std::unique_ptr<SUNContext, ContextDeleter>;
using Vector = std::unique_ptr<_generic_N_Vector, VectorDeleter>;
using Matrix = std::unique_ptr<_generic_SUNMatrix, MatrixDeleter>;
using LinearSolver = std::unique_ptr<_generic_SUNLinearSolver, LinearSolverDeleter>;
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

/// A BDF solver with a dense Newton system, owning what CVODES borrows: its memory, the
/// Jacobian matrix and the linear solver (destroyed together, in reverse order of creation).
struct BdfSolver {
  Memory memory;
  Matrix jacobian;
  LinearSolver linear_solver;
  void* get() const { return memory.get(); }
};

/// Creates and configures a BDF solver for `rhs` from `y0` at `t0`, every flag checked by name:
/// `user_data` for the right-hand side, per-component absolute `tolerances`, at most
/// `max_steps` between outputs and steps of at most `max_step_s` (0: no limit). Stiff friction
/// (a sharp tanh) is why the simulations use BDF with Newton.
inline BdfSolver make_bdf(SUNContext ctx, CVRhsFn rhs, double t0, N_Vector y0, void* user_data,
                          double relative_tolerance, N_Vector tolerances, double max_steps, double max_step_s) {
  BdfSolver solver{Memory(CVodeCreate(CV_BDF, ctx)), nullptr, nullptr};
  if (!solver.memory) throw SolverError("CVodeCreate failed");
  void* cv = solver.get();
  check_flag(CVodeInit(cv, rhs, t0, y0), "CVodeInit", t0);
  check_flag(CVodeSetUserData(cv, user_data), "CVodeSetUserData", t0);
  silence_errors(cv, t0);
  check_flag(CVodeSVtolerances(cv, relative_tolerance, tolerances), "CVodeSVtolerances", t0);
  check_flag(CVodeSetMaxNumSteps(cv, static_cast<long>(max_steps)), "CVodeSetMaxNumSteps", t0);
  if (max_step_s > 0.0) check_flag(CVodeSetMaxStep(cv, max_step_s), "CVodeSetMaxStep", t0);
  const auto size = static_cast<sunindextype>(N_VGetLength(y0));
  solver.jacobian.reset(SUNDenseMatrix(size, size, ctx));
  if (!solver.jacobian) throw SolverError("SUNDenseMatrix failed");
  solver.linear_solver.reset(SUNLinSol_Dense(y0, solver.jacobian.get(), ctx));
  if (!solver.linear_solver) throw SolverError("SUNLinSol_Dense failed");
  check_flag(CVodeSetLinearSolver(cv, solver.linear_solver.get(), solver.jacobian.get()), "CVodeSetLinearSolver", t0);
  return solver;
}

/// Adds the counters of the CVODES memory `mem` since its last (re)initialisation to `s`.
inline void add_statistics(void* mem, SolverStatistics& s) {
  long value = 0;
  check_flag(CVodeGetNumSteps(mem, &value), "CVodeGetNumSteps", 0.0);
  s.steps += value;
  long rhs = 0;
  check_flag(CVodeGetNumRhsEvals(mem, &rhs), "CVodeGetNumRhsEvals", 0.0);
  long jacobian_rhs = 0;
  check_flag(CVodeGetNumLinRhsEvals(mem, &jacobian_rhs), "CVodeGetNumLinRhsEvals", 0.0);
  s.rhs_evaluations += rhs + jacobian_rhs;
  check_flag(CVodeGetNumJacEvals(mem, &value), "CVodeGetNumJacEvals", 0.0);
  s.jacobian_evaluations += value;
  check_flag(CVodeGetNumLinSolvSetups(mem, &value), "CVodeGetNumLinSolvSetups", 0.0);
  s.linear_solver_setups += value;
  check_flag(CVodeGetNumErrTestFails(mem, &value), "CVodeGetNumErrTestFails", 0.0);
  s.error_test_failures += value;
  check_flag(CVodeGetNumNonlinSolvIters(mem, &value), "CVodeGetNumNonlinSolvIters", 0.0);
  s.nonlinear_iterations += value;
  check_flag(CVodeGetNumNonlinSolvConvFails(mem, &value), "CVodeGetNumNonlinSolvConvFails", 0.0);
  s.nonlinear_convergence_failures += value;
}

}  // namespace pamkit::cvodes
