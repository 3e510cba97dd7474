#pragma once
/// \file
/// The solver's counters, apart from the simulator so that a simulated measurement
/// (effects/effect.hpp, which the model includes) can carry them.

#include <ostream>

namespace pamkit {

/// How CVODES integrates a run (SimulatorConfig::method).
enum class IntegrationMethod {
  automatic,  ///< `adams` where the stiffness test (estimate_stiffness, simulator.hpp) finds the run non-stiff,
              ///< `bdf` otherwise
  bdf,        ///< BDF of order 1-5 with a dense Newton solver: stable however fast the model relaxes
  adams,      ///< Adams-Moulton of order 1-12 with a fixed-point iteration: no Jacobian, higher order, but
              ///< its steps must stay below ~1 / (the model's fastest rate)
};

/// "auto", "bdf" or "adams", as Python names them.
inline const char* to_string(IntegrationMethod method) {
  switch (method) {
    case IntegrationMethod::automatic:
      return "auto";
    case IntegrationMethod::bdf:
      return "bdf";
    case IntegrationMethod::adams:
      return "adams";
  }
  return "unknown";
}
inline std::ostream& operator<<(std::ostream& out, IntegrationMethod method) { return out << to_string(method); }

/// Counters CVODES kept over one run (CVodeGet* summed over the restarts at each corner of
/// the trajectory, where the elongation rate jumps).
struct SolverStatistics {
  IntegrationMethod method = IntegrationMethod::bdf;  ///< the method that ran: bdf or adams, never automatic
  long steps = 0;                                     ///< internal time steps
  long rhs_evaluations = 0;                           ///< right-hand-side evaluations, Jacobian ones included
  long output_evaluations = 0;                        ///< model evaluations to report the samples
  long tabulated_shapes = 0;                          ///< of those, the ones that read a ShapeTable's shape
  long jacobian_evaluations = 0;                      ///< dense Jacobian evaluations (none with adams)
  long linear_solver_setups = 0;                      ///< Newton matrix factorisations (none with adams)
  long error_test_failures = 0;                       ///< steps rejected by the local error test
  long nonlinear_iterations = 0;                      ///< Newton (bdf) or fixed-point (adams) iterations
  long nonlinear_convergence_failures = 0;            ///< failures of those iterations to converge
  long restarts = 0;                                  ///< CVodeReInit calls at trajectory corners
  long sensitivity_rhs_evaluations = 0;  ///< moved models' right-hand sides for the sensitivities (run_sensitivities)
};

}  // namespace pamkit
