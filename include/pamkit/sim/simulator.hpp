#pragma once
/// \file
/// Integrates a MuscleModel along a prescribed elongation with SUNDIALS CVODES (BDF with a dense
/// Newton solver, or Adams with a fixed-point iteration where a stiffness test allows it); the
/// energy flows are integrated with the state.

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "pamkit/fields.hpp"
#include "pamkit/sim/batch.hpp"
#include "pamkit/sim/model.hpp"
#include "pamkit/sim/shape_table.hpp"
#include "pamkit/sim/statistics.hpp"
#include "pamkit/sim/trajectory.hpp"

namespace pamkit {

/// Integrator settings.
struct SimulatorConfig {
  static constexpr const char* kName = "SimulatorConfig";

  double relative_tolerance = 1e-8;    ///< CVODE relative tolerance [1]
  double absolute_tolerance_K = 1e-8;  ///< CVODE absolute tolerance on the gas temperature [K]; gas mass and
                                       ///< viscous stresses get the same tolerance relative to their scale
  double absolute_tolerance_J = 1e6;   ///< absolute tolerance on the energy integrals [J]. The default, far
                                       ///< above any energy a muscle stores, leaves them out of the error test
                                       ///< (as SUNDIALS leaves quadratures out by default): they then ride on the
                                       ///< steps the physics needs, which matters on measured, kinked
                                       ///< trajectories. Set it small (1e-8) to control them too.
  double max_steps = 50000;            ///< most internal steps between two samples [1]
  double max_step_s = 0.0;             ///< largest internal step [s]; 0: no limit
  double corner_threshold = 0.2;       ///< a jump of the elongation rate above this share of the largest rate
                                       ///< restarts the integrator (turning points, holds); smaller ones
                                       ///< (sampled curves, encoder noise) are integrated through [1]
  IntegrationMethod method = IntegrationMethod::bdf;  ///< bdf, adams, dopri5, rosenbrock4, or automatic: dopri5
                                                      ///< where estimate_stiffness finds the run non-stiff, else
                                                      ///< rosenbrock4, or bdf below kRosenbrockTightestTolerance

  template <class Visitor>
  static void for_each_field(Visitor&& visit) {
    visit("relative_tolerance", &SimulatorConfig::relative_tolerance,
          FieldInfo{"1", 1e-14, 1e-2, "relative tolerance"});
    visit("absolute_tolerance_K", &SimulatorConfig::absolute_tolerance_K,
          FieldInfo{"K", 1e-16, 1.0, "absolute tolerance on temperature"});
    visit("absolute_tolerance_J", &SimulatorConfig::absolute_tolerance_J,
          FieldInfo{"J", 1e-16, 1e12, "absolute tolerance on energies (large: leave them out of the error test)"});
    visit("max_steps", &SimulatorConfig::max_steps, FieldInfo{"1", 10, 1e9, "most steps between samples"});
    visit("max_step_s", &SimulatorConfig::max_step_s, FieldInfo{"s", 0.0, 1e9, "largest step (0: no limit)"});
    visit("corner_threshold", &SimulatorConfig::corner_threshold,
          FieldInfo{"1", 0.0, 2.0, "rate jump that restarts, share of the largest rate"});
    visit("method", &SimulatorConfig::method,
          FieldInfo{"1", 0.0, 4.0,
                    "integration method: bdf, adams, dopri5, rosenbrock4 or auto (dopri5 where the run is not stiff, "
                    "else rosenbrock4, or bdf at a relative tolerance below 1e-9)"});
  }
  void validate() const { validate_fields(*this); }
};

/// The tightest relative tolerance at which IntegrationMethod::automatic runs a stiff run by
/// rosenbrock4; tighter, by bdf. The Rosenbrock method's steps shrink as rtol^(1/4) (its error
/// estimate is of order 3), BDF's as rtol^(1/6) at its order 5: on the thesis's stiff bench test
/// (bench/bench_simulate.py, heat exchanged in 0.02 s) rosenbrock4 is 1.4x faster at 1e-8, the two
/// tie at 1e-9 and BDF is 1.6x faster at 1e-10.
constexpr double kRosenbrockTightestTolerance = 1e-9;

/// The stiffness test behind IntegrationMethod::automatic, made before a run from the model's
/// parameters and the trajectory's times alone (so the same on every machine and thread).
/// A run is stiff where the model relaxes faster than the steps the tolerance allows: an explicit
/// method's steps (dopri5's) and Adams's fixed-point iteration then shrink to ~1 / rate, where
/// the implicit methods' (rosenbrock4's linear solve, BDF's Newton iteration) keep the steps the
/// tolerance sets.
struct StiffnessEstimate {
  double fastest_rate_per_s;  ///< MuscleModel::fastest_rate_per_s [1/s]
  double longest_piece_s;     ///< longest stretch between corners of the trajectory [s]
  double expected_step_s;     ///< a step the tolerance allows on it: longest_piece_s rtol^(1/6), at most max_step_s
  /// fastest_rate_per_s x expected_step_s: above 1, stiff.
  double ratio() const { return fastest_rate_per_s * expected_step_s; }
  bool stiff() const { return ratio() > 1.0; }
};

/// The stiffness test of `model` along `trajectory` under `config` (its tolerance, max_step_s
/// and corner_threshold); `Simulator::run` makes it when `config.method` is automatic.
StiffnessEstimate estimate_stiffness(const MuscleModel& model, const ElongationTrajectory& trajectory,
                                     const SimulatorConfig& config);

/// Time series of one run; every vector has one entry per trajectory sample.
struct SimulationResult {
  std::vector<double> time_s;                 ///< sample times
  std::vector<double> elongation_m;           ///< prescribed elongation
  std::vector<double> length_m;               ///< muscle length
  std::vector<double> force_N;                ///< axial force (tension > 0), friction included
  std::vector<double> friction_force_N;       ///< friction part of force_N
  std::vector<double> gauge_pressure_Pa;      ///< gas pressure above ambient
  std::vector<double> temperature_K;          ///< gas temperature
  std::vector<double> gas_volume_m3;          ///< gas volume (eq. 3.1.2, plus any dead volume)
  std::vector<double> gas_mass_kg;            ///< mass of air inside
  std::vector<double> braid_angle_rad;        ///< braid angle of the cylinder
  std::vector<double> diameter_m;             ///< braid diameter
  std::vector<double> work_J;                 ///< work done on the muscle since t0, integral of F dL
  std::vector<double> heat_lost_J;            ///< heat from gas to wall since t0
  std::vector<double> friction_dissipated_J;  ///< friction work since t0
  SolverStatistics statistics;

  /// Visits every column once, in the order above: visit(name, &SimulationResult::column, unit,
  /// meaning, output), `output` false for the two the trajectory prescribes (time_s,
  /// elongation_m). The bindings and a batch's channels read the columns through it.
  template <class Visitor>
  static void for_each_column(Visitor&& visit) {
    visit("time_s", &SimulationResult::time_s, "s", "sample times", false);
    visit("elongation_m", &SimulationResult::elongation_m, "m", "prescribed elongation", false);
    visit("length_m", &SimulationResult::length_m, "m", "muscle length", true);
    visit("force_N", &SimulationResult::force_N, "N", "axial force, tension > 0, friction included", true);
    visit("friction_force_N", &SimulationResult::friction_force_N, "N", "friction part of the force", true);
    visit("gauge_pressure_Pa", &SimulationResult::gauge_pressure_Pa, "Pa", "gas pressure above ambient", true);
    visit("temperature_K", &SimulationResult::temperature_K, "K", "gas temperature", true);
    visit("gas_volume_m3", &SimulationResult::gas_volume_m3, "m^3", "gas volume, dead volume included", true);
    visit("gas_mass_kg", &SimulationResult::gas_mass_kg, "kg", "mass of air inside", true);
    visit("braid_angle_rad", &SimulationResult::braid_angle_rad, "rad", "braid angle of the cylinder", true);
    visit("diameter_m", &SimulationResult::diameter_m, "m", "braid diameter", true);
    visit("work_J", &SimulationResult::work_J, "J", "work done on the muscle since the start", true);
    visit("heat_lost_J", &SimulationResult::heat_lost_J, "J", "heat from gas to wall since the start", true);
    visit("friction_dissipated_J", &SimulationResult::friction_dissipated_J, "J", "friction work since the start",
          true);
  }
};

/// A run and its forward sensitivities (Simulator::run_sensitivities).
struct SensitivityResult {
  SimulationResult run;  ///< the run at the nominal parameters (its statistics count the sensitivities' work too)
  /// One per parameter: the derivative of each output column of `run` with respect to it (per
  /// unit of the parameter). time_s is the run's; elongation_m is the muscle's motion's (zero
  /// unless the parameter moves the motion: run_sensitivities' `moved_motions`); statistics are
  /// empty.
  std::vector<SimulationResult> derivatives;
};

/// Receives a run's samples in order, a block at a time: `first` is the trajectory index of the
/// block's first sample, and every column of `block` holds the block's samples (its statistics
/// are empty: the run returns them at its end). The block is reused after the call returns.
using SampleSink = std::function<void(std::size_t first, const SimulationResult& block)>;

/// Runs simulations. Holds only its configuration, so one Simulator may run many models at
/// once from different threads; each run owns its own CVODES memory.
class Simulator {
 public:
  /// \throws InvalidParameter for a bad configuration.
  explicit Simulator(SimulatorConfig config = {});

  /// Simulates `model` along `trajectory` (elongation from the model's initial length).
  /// Samples are reported at the trajectory's times; the friction at a sample uses the
  /// elongation rate of the segment that ends there (of the first segment at the start).
  /// Between corners CVODES takes its own steps and each sample is read off the polynomial of
  /// the step that passed it (CVodeGetDky; a step that passed more samples than its order + 1
  /// reads that polynomial's Taylor coefficients once and each sample by a Horner sum, the same
  /// values to rounding), so the samples do not steer the steps. With IntegrationMethod::dopri5
  /// (or automatic on a run that is not stiff) an explicit Dormand-Prince 5(4) method takes the
  /// steps instead, each piece's last one shortened to end on its corner, and each sample is
  /// read off its dense output.
  /// With `shapes`, the samples' braid shapes are read from that table where it applies to this
  /// run (ShapeTable::applies_to: the same build, the same sample lengths, inextensible fibers)
  /// instead of solved, with the same numbers bit for bit; where it does not apply, they are
  /// solved as without it. `statistics.tabulated_shapes` counts the samples it gave.
  /// \throws InvalidInput if a sample's length is outside the braid's range (naming the
  ///         sample), SolverError with the CVODES flag name and time if integration fails.
  SimulationResult run(const MuscleModel& model, const ElongationTrajectory& trajectory,
                       const ShapeTable* shapes = nullptr) const;

  /// `run`, its samples handed to `sink` as they are integrated, in blocks of `block_size`
  /// samples (the last block may be shorter), as SUNDIALS's and Drake's simulators hand output
  /// to a monitor: only one block stands in memory, so a long test's outputs need not. The
  /// samples are `run`'s, bit for bit (`run` is this with a sink that copies the blocks);
  /// `shapes` as in `run`.
  /// \returns the solver's counters over the run.
  /// \throws InvalidInput for a block_size of 0, and whatever `run` or `sink` throws; the
  ///         samples handed over before stand.
  SolverStatistics run_blocks(const MuscleModel& model, const ElongationTrajectory& trajectory, std::size_t block_size,
                              const SampleSink& sink, const ShapeTable* shapes = nullptr) const;

  /// `run`, with the forward sensitivities of every output column to parameters of the caller's
  /// choosing, integrated by CVODES beside the state (staggered corrector) on the state's own
  /// steps: outside the error test, so the run is the plain run's to rounding (a fit's residual
  /// and its Jacobian see one model). The Jacobian a fit needs, free of the noise that
  /// differencing two adaptively stepped runs carries.
  ///
  /// Parameter i is given as `moved[i]`: the model with that parameter (and nothing else) moved by
  /// `steps[i]` (signed), its own initial state, sealed gas mass and initial length following
  /// from it. Any number of the model, of its build, bladder law, gas, initial state or an
  /// effect's extension, is thus a parameter, and so is a coordinate that maps to several. Each
  /// sensitivity's right-hand side, and each sample's output derivative, is the directional
  /// difference quotient (f_i(y + h_i s_i) - f(y)) / h_i that CVODES forms for the parameters it
  /// holds itself: the model's functions are smooth and their closure solved to ~1e-14, so
  /// steps near 1e-6 of a parameter of order one give derivatives to ~1e-6 relative.
  ///
  /// The sensitivities share the state's absolute tolerances, so parameters should be of order
  /// one (a fit's unit box). They are integrated by BDF whatever config().method says (Adams's
  /// fixed-point iteration has no sensitivity corrector here). `shapes` serves the nominal
  /// model and every moved one it applies to (a moved friction, bladder law, gas or pressure
  /// at a given initial length).
  ///
  /// A parameter may also move the muscle's motion (an effect at EffectStage::motion, such as
  /// a fixture's slack): `moved_motions[i]` is then moved model i's elongation along the same
  /// sample times, and both its right-hand side and its outputs follow that motion (its
  /// derivative's elongation_m is the motion's, (moved - nominal) / h_i). Empty: every moved
  /// model follows `trajectory`. CVODES restarts at `trajectory`'s corners, so a moved motion
  /// should keep them where they are (a step of 1e-6 moves a corner by less than a sample).
  ///
  /// `rows`: the samples (increasing trajectory indices) whose derivatives the caller reads, such
  /// as a fit's training samples; the derivatives are NaN at the others, where neither the
  /// sensitivities are interpolated nor the moved models evaluated (most of a long record's cost).
  /// Empty: every sample. The nominal run is whole either way; at `rows` the derivatives are the
  /// same to the braid closure's tolerance (a moved model's closure then starts from the last
  /// sample read, not the one before).
  /// \throws InvalidInput if `moved` and `steps` differ in size, a step is zero or not finite,
  ///         `moved_motions` is neither empty nor one per moved model, a moved motion's times are
  ///         not `trajectory`'s, a moved model's motion leaves its braid's range, or `rows` does not
  ///         increase or passes the trajectory's end; as `run` otherwise.
  SensitivityResult run_sensitivities(const MuscleModel& model, const std::vector<MuscleModel>& moved,
                                      const std::vector<double>& steps, const ElongationTrajectory& trajectory,
                                      const ShapeTable* shapes = nullptr,
                                      const std::vector<ElongationTrajectory>& moved_motions = {},
                                      const std::vector<std::size_t>& rows = {}) const;

  /// Runs every model of `models` along `trajectory`, as `run_blocks` runs each, on
  /// `request.threads` threads, and keeps of each run the request's channels at its rows and
  /// their extremes over every sample: a screen of many candidate muscles of one test, with no
  /// result per run to build. A run that fails leaves NaN and its message (BatchResult::errors);
  /// the others run. `shapes` serves every run it applies to (ShapeTable::applies_to); with
  /// `motions`, run i follows motions[i] (an effect that moves the muscle off the crosshead: a
  /// fixture's slack), on the trajectory's sample times.
  /// \throws InvalidInput for an unknown or repeated channel, rows that do not increase or pass
  ///         the trajectory's end, or `motions` neither empty nor one per model on the
  ///         trajectory's times.
  BatchResult run_batch(const std::vector<MuscleModel>& models, const ElongationTrajectory& trajectory,
                        const BatchRequest& request = {}, const ShapeTable* shapes = nullptr,
                        const std::vector<ElongationTrajectory>& motions = {}) const;

  /// `run_batch` over the runs of `sets`, each run's muscle made on the thread that runs it
  /// (ParameterSets::at): a design sweep with no work per run outside C++. A run whose parameters
  /// are refused fails with RunFailure::parameters.
  /// \throws InvalidInput as the other overload.
  BatchResult run_batch(const ParameterSets& sets, const ElongationTrajectory& trajectory,
                        const BatchRequest& request = {}) const;

  const SimulatorConfig& config() const { return config_; }

 private:
  SimulatorConfig config_;
};

}  // namespace pamkit
