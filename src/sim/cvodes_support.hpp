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
