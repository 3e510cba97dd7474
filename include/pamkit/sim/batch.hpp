#pragma once
/// \file
/// Many runs of one test at once (Simulator::run_batch): N muscles, or N parameter sets of one
/// muscle, along one trajectory, on C++ threads, each run kept as what a design sweep or a
/// screen of candidates reads of it: chosen channels at chosen samples, and each channel's
/// largest and smallest value over the whole run.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "pamkit/sim/model.hpp"
#include "pamkit/sim/statistics.hpp"

namespace pamkit {

/// What a batch keeps of each run, and how many threads run them.
struct BatchRequest {
  /// Output columns of SimulationResult to keep, by name (SimulationResult::for_each_column:
  /// force_N, gauge_pressure_Pa, temperature_K, work_J, ...), each in its own SI unit.
  std::vector<std::string> channels{"force_N", "gauge_pressure_Pa", "temperature_K"};
  /// Trajectory samples at which each channel is kept, strictly increasing (empty: none; the
  /// extremes still cover every sample).
  std::vector<std::size_t> rows;
  /// Threads that run the batch, the calling one among them; 0: one per hardware thread. Never
  /// more than there are runs.
  std::size_t threads = 0;
};

/// Why a run of a batch failed.
enum class RunFailure : std::uint8_t {
  none,        ///< it ran
  parameters,  ///< its parameters were refused before a model was built (ParameterSets::at: a field out of its
               ///< range, a braid angle the build cannot reach, a pressure it cannot inflate to freely)
  input,       ///< the model could not follow the trajectory (InvalidInput or InvalidParameter on the way: a
               ///< start or a sample outside the braid's range)
  solver,      ///< the integrator failed (SolverError)
};

/// The runs of a batch, in the order given. Each run's numbers are `Simulator::run`'s for its
/// muscle, bit for bit, whatever the number of threads.
struct BatchResult {
  std::size_t runs = 0;               ///< how many runs
  std::vector<std::string> channels;  ///< the channels kept, in the request's order
  std::vector<std::size_t> rows;      ///< the samples each channel is kept at
  /// Per channel: runs x rows.size() values, run by run (row-major), in the channel's unit; NaN
  /// for a run that failed.
  std::vector<std::vector<double>> values;
  /// Per channel: each run's largest value over every sample (NaN for a run that failed, or
  /// where the channel is NaN somewhere, as numpy's max has it).
  std::vector<std::vector<double>> maximum;
  std::vector<std::vector<double>> minimum;  ///< per channel: each run's smallest value, likewise
  std::vector<SolverStatistics> statistics;  ///< per run: the solver's counters (zero for a run that failed)
  std::vector<std::string> errors;           ///< per run: why it failed (empty: it ran)
  std::vector<RunFailure> failures;          ///< per run: which kind of failure that was
};

/// One muscle's parameters and sealed start, varied run by run: each run sets its own values of
/// the named fields on a shared base. Holds the base and a compiled setter per name, so the runs
/// are made on the threads that run them.
class ParameterSets {
 public:
  /// \param base every field a run does not set
  /// \param start the sealed start every run shares but for the fields it sets
  /// \param inflated_start true: a run starts at the free length its pressure inflates the muscle
  ///        to, then sealed (inflated_and_sealed), unless it sets initial.length_m; false: at
  ///        `start.length_m` (or the length it sets)
  /// \param names the fields each run sets, each once: "build.<MuscleBuild field>",
  ///        "build.braid_angle_deg" (the fiber revolutions that give the deflated build this braid
  ///        angle in degrees, as fiber_revolutions_for_braid_angle takes it, from the other build
  ///        fields the run sets), "bladder.shear_modulus_Pa" (a neo-Hookean bladder of this
  ///        modulus), "friction.<field>", "gas.<field>", "extensions.<field>",
  ///        "initial.length_m", "initial.gauge_pressure_Pa" (numbers only: not an enumeration)
  /// \param values runs x names.size() values, run by run (row-major), each in its field's unit
  /// \throws InvalidInput for an unknown or repeated name, both braid_angle_deg and
  ///         fiber_revolutions, or values that are not a whole number of runs.
  ParameterSets(MuscleParams base, InitialState start, bool inflated_start, std::vector<std::string> names,
                std::vector<double> values);

  std::size_t runs() const { return runs_; }
  const std::vector<std::string>& names() const { return names_; }

  /// Run `run`'s parameters and start: the base with the run's values set, the braid angle's
  /// revolutions last, validated, then the sealed start (inflated freely where it is).
  /// \throws InvalidParameter for a value out of its field's range or a braid angle outside
  ///         (0, 90) degrees, InvalidInput for a pressure the muscle cannot inflate to freely,
  ///         std::out_of_range for a run past the last.
  std::pair<MuscleParams, InitialState> at(std::size_t run) const;

 private:
  using Setter = std::function<void(MuscleParams&, InitialState&, double)>;
  MuscleParams base_;
  InitialState start_;
  bool inflated_start_;
  std::vector<std::string> names_;
  std::vector<double> values_;
  std::size_t runs_ = 0;
  std::vector<Setter> setters_;      // one per name; braid_angle_deg's is empty (set last)
  std::ptrdiff_t braid_angle_ = -1;  // its name's index, or -1
  bool sets_length_ = false;         // a run sets initial.length_m: no free inflation
};

}  // namespace pamkit
