#pragma once
/// \file
/// The solver's counters, apart from the simulator so that a simulated measurement
/// (effects/effect.hpp, which the model includes) can carry them.

namespace pamkit {

/// Counters CVODES kept over one run (CVodeGet* summed over the restarts at each corner of
/// the trajectory, where the elongation rate jumps).
struct SolverStatistics {
  long steps = 0;                           ///< internal time steps
  long rhs_evaluations = 0;                 ///< right-hand-side evaluations, Jacobian ones included
  long output_evaluations = 0;              ///< model evaluations to report the samples
  long jacobian_evaluations = 0;            ///< dense Jacobian evaluations
  long linear_solver_setups = 0;            ///< Newton matrix factorisations
  long error_test_failures = 0;             ///< steps rejected by the local error test
  long nonlinear_iterations = 0;            ///< Newton iterations
  long nonlinear_convergence_failures = 0;  ///< Newton failures
  long restarts = 0;                        ///< CVodeReInit calls at trajectory corners
};

}  // namespace pamkit
