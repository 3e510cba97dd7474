#pragma once
/// \file
/// The solver's counters, apart from the simulator so that a simulated measurement
/// (effects/effect.hpp, which the model includes) can carry them.

#include <ostream>

namespace pamkit {

/// How a run is integrated (SimulatorConfig::method).
enum class IntegrationMethod {
  automatic,  ///< `dopri5` where the stiffness test (estimate_stiffness, simulator.hpp) finds the run non-stiff,
              ///< `bdf` otherwise
  bdf,        ///< CVODES's BDF of order 1-5 with a dense Newton solver: stable however fast the model relaxes
  adams,      ///< CVODES's Adams-Moulton of order 1-12 with a fixed-point iteration: no Jacobian, higher order,
              ///< but its steps must stay below ~1 / (the model's fastest rate)
  dopri5,     ///< Dormand-Prince 5(4), explicit, with its dense output (Boost.Odeint): seven evaluations a
              ///< step and no iteration, the cheapest where not stiff (bench/README.md); its steps too must
              ///< stay below ~3 / (the model's fastest rate)
};

/// "auto", "bdf", "adams" or "dopri5", as Python names them.
inline const char* to_string(IntegrationMethod method) {
  switch (method) {
    case IntegrationMethod::automatic:
      return "auto";
    case IntegrationMethod::bdf:
      return "bdf";
    case IntegrationMethod::adams:
      return "adams";
    case IntegrationMethod::dopri5:
      return "dopri5";
  }
  return "unknown";
}
inline std::ostream& operator<<(std::ostream& out, IntegrationMethod method) { return out << to_string(method); }

/// Counters the integrator kept over one run (CVODES's CVodeGet* or the explicit method's own,
/// summed over the restarts at each corner of the trajectory, where the elongation rate jumps).
struct SolverStatistics {
  IntegrationMethod method = IntegrationMethod::bdf;  ///< the method that ran: bdf, adams or dopri5, never automatic
  long steps = 0;                                     ///< internal time steps (dopri5: accepted ones)
  long rhs_evaluations = 0;                           ///< right-hand-side evaluations, Jacobian ones included
  long output_evaluations = 0;                        ///< model evaluations to report the samples
  long tabulated_shapes = 0;                          ///< of those, the ones that read a ShapeTable's shape
  long jacobian_evaluations = 0;                      ///< dense Jacobian evaluations (none with adams or dopri5)
  long linear_solver_setups = 0;                      ///< Newton matrix factorisations (none with adams or dopri5)
  long error_test_failures = 0;                       ///< steps rejected by the local error test (dopri5: not counted)
  long nonlinear_iterations = 0;                      ///< Newton (bdf) or fixed-point (adams) iterations
  long nonlinear_convergence_failures = 0;            ///< failures of those iterations to converge
  long restarts = 0;                                  ///< restarts at trajectory corners
  long sensitivity_rhs_evaluations = 0;  ///< moved models' right-hand sides for the sensitivities (run_sensitivities)
};

}  // namespace pamkit
