#pragma once
/// \file
/// The solver's counters, apart from the simulator so that a simulated measurement
/// (effects/effect.hpp, which the model includes) can carry them.

#include <ostream>

namespace pamkit {

/// How a run is integrated (SimulatorConfig::method).
enum class IntegrationMethod {
  automatic,    ///< `dopri5` where the stiffness test (estimate_stiffness, simulator.hpp) finds the run non-stiff,
                ///< `bdf` otherwise
  bdf,          ///< CVODES's BDF of order 1-5 with a dense Newton solver: stable however fast the model relaxes
  adams,        ///< CVODES's Adams-Moulton of order 1-12 with a fixed-point iteration: no Jacobian, higher order,
                ///< but its steps must stay below ~1 / (the model's fastest rate)
  dopri5,       ///< Dormand-Prince 5(4), explicit, with its dense output (Boost.Odeint): seven evaluations a
                ///< step and no iteration, the cheapest where not stiff (bench/README.md); its steps too must
                ///< stay below ~3 / (the model's fastest rate)
  rosenbrock4,  ///< Boost.Odeint's Rosenbrock 4(3) method (Hairer and Wanner's RODAS4 coefficients), linearly
                ///< implicit and L-stable, with its dense output, on the states that move and the energies
                ///< only: one small LU a step and no iteration, stable however fast the model relaxes
};

/// "auto", "bdf", "adams", "dopri5" or "rosenbrock4", as Python names them.
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
    case IntegrationMethod::rosenbrock4:
      return "rosenbrock4";
  }
  return "unknown";
}
inline std::ostream& operator<<(std::ostream& out, IntegrationMethod method) { return out << to_string(method); }

/// Counters the integrator kept over one run (CVODES's CVodeGet*, or the Boost.Odeint methods' own,
/// summed over the restarts at each corner of the trajectory, where the elongation rate jumps).
struct SolverStatistics {
  IntegrationMethod method = IntegrationMethod::bdf;  ///< the method that ran: never automatic
  long steps = 0;                                     ///< internal time steps (dopri5, rosenbrock4: accepted ones)
  long rhs_evaluations = 0;                           ///< right-hand-side evaluations, Jacobian ones included
  long output_evaluations = 0;                        ///< model evaluations to report the samples
  long tabulated_shapes = 0;                          ///< of those, the ones that read a ShapeTable's shape
  long jacobian_evaluations = 0;                      ///< dense Jacobian evaluations (none with adams or dopri5)
  long linear_solver_setups = 0;  ///< LU factorisations: Newton's (bdf) or a step's (rosenbrock4); none otherwise
  long error_test_failures = 0;   ///< steps rejected by the local error test (dopri5: not counted)
  long nonlinear_iterations = 0;  ///< Newton (bdf) or fixed-point (adams) iterations
  long nonlinear_convergence_failures = 0;  ///< failures of those iterations to converge
  long restarts = 0;                        ///< restarts at trajectory corners
  long sensitivity_rhs_evaluations = 0;  ///< moved models' right-hand sides for the sensitivities (run_sensitivities)

  /// Visits every counter once, in the order above: visit(name, &SolverStatistics::counter,
  /// meaning). The bindings and a batch's per-run arrays read them through it.
  template <class Visitor>
  static void for_each_counter(Visitor&& visit) {
    visit("steps", &SolverStatistics::steps, "internal time steps (dopri5, rosenbrock4: accepted ones)");
    visit("rhs_evaluations", &SolverStatistics::rhs_evaluations,
          "right-hand-side evaluations, difference-quotient Jacobians' included");
    visit("output_evaluations", &SolverStatistics::output_evaluations, "model evaluations to report the samples");
    visit("tabulated_shapes", &SolverStatistics::tabulated_shapes,
          "output evaluations whose braid shape a ShapeTable gave (0: none, or it did not apply)");
    visit("jacobian_evaluations", &SolverStatistics::jacobian_evaluations,
          "dense Jacobian evaluations (none with adams or dopri5)");
    visit("linear_solver_setups", &SolverStatistics::linear_solver_setups,
          "LU factorisations: Newton's (bdf) or a step's (rosenbrock4)");
    visit("error_test_failures", &SolverStatistics::error_test_failures,
          "steps rejected by the local error test (dopri5: not counted)");
    visit("nonlinear_iterations", &SolverStatistics::nonlinear_iterations,
          "Newton (bdf) or fixed-point (adams) iterations");
    visit("nonlinear_convergence_failures", &SolverStatistics::nonlinear_convergence_failures,
          "failures of those iterations to converge");
    visit("restarts", &SolverStatistics::restarts, "restarts at trajectory corners");
    visit("sensitivity_rhs_evaluations", &SolverStatistics::sensitivity_rhs_evaluations,
          "moved models' right-hand sides for the sensitivities (Simulator.run_sensitivities; 0 otherwise)");
  }
};

}  // namespace pamkit
