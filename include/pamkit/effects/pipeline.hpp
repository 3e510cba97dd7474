#pragma once
/// \file
/// A bench test as its instruments see it: the model extended by effects, driven through the
/// fixture, read through the sensors.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>

#include <boost/math/tools/roots.hpp>

#include "pamkit/effects/effect.hpp"
#include "pamkit/sim/held_braid.hpp"
#include "pamkit/sim/simulator.hpp"

namespace pamkit {

/// Receives a simulated measurement's samples in order, a block at a time: `first` is the index
/// of the block's first sample. The block is reused after the call returns.
using MeasurementSink = std::function<void(std::size_t first, const Measurement& block)>;

namespace detail {
/// A sealed test's run with `effects` applied to the parameters and the motion, its samples
/// handed to `sink` in blocks as the instruments' channels before the measurement stage (the
/// elongation is the crosshead's: what the machine records); `shapes` as in Simulator::run, for
/// the extended model along the muscle's motion. \returns the solver's counters.
/// \throws InvalidParameter if an effect cannot act on a sealed test, and whatever the
///         simulator or the sink throws.
inline SolverStatistics sealed_measurement_blocks(const MuscleParams& params, const InitialState& initial,
                                                  const ElongationTrajectory& crosshead,
                                                  const std::vector<EffectPtr>& effects, const Simulator& simulator,
                                                  std::size_t block_size, const MeasurementSink& sink,
                                                  const ShapeTable* shapes) {
  MuscleParams extended = params;
  for (const EffectPtr& effect : effects) {
    std::string why_not;
    if (!effect->acts_in(GasMode::sealed, &why_not)) throw InvalidParameter(why_not);
    effect->apply_to_params(extended);
  }
  // The muscle's motion, when an effect may change it: the crosshead's otherwise, not copied.
  std::optional<ElongationTrajectory> moved;
  if (!effects.empty()) {
    std::vector<double> motion = crosshead.elongation();
    for (const EffectPtr& effect : effects) motion = effect->apply_to_elongation(crosshead.time(), motion);
    moved.emplace(crosshead.time(), std::move(motion));
  }
  Measurement block;
  const auto channels = [&](std::size_t first, const SimulationResult& r) {
    const std::size_t n = r.time_s.size();
    const auto from = crosshead.elongation().begin() + static_cast<std::ptrdiff_t>(first);
    block.time_s = r.time_s;
    block.elongation_m.assign(from, from + static_cast<std::ptrdiff_t>(n));
    block.force_N = r.force_N;
    block.gauge_pressure_Pa = r.gauge_pressure_Pa;
    block.temperature_K = r.temperature_K;
    sink(first, block);
  };
  return simulator.run_blocks(MuscleModel(extended, initial), moved ? *moved : crosshead, block_size, channels, shapes);
}

/// Samples per block when a whole measurement is collected.
constexpr std::size_t kMeasurementBlockSize = 4096;
}  // namespace detail

/// Simulates a sealed test with `effects` applied at every stage, in order: parameters, the
/// muscle's motion from the crosshead's `crosshead`, then the measured channels. The result's
/// elongation is the crosshead's (what the machine records).
/// \param shapes the braid's shapes along the muscle's motion, solved once (ShapeTable) for the
///        many runs of one test that differ in pressure, scales or effects: used where it applies
///        to the run (the effects leave the build, the motion and the fibers' stiffness as the
///        table has them), with the same result bit for bit; ignored otherwise. Null: none.
/// \throws InvalidParameter if an effect cannot act on a sealed test, and whatever the
///         simulator throws.
inline Measurement simulate_measurement(const MuscleParams& params, const InitialState& initial,
                                        const ElongationTrajectory& crosshead, const std::vector<EffectPtr>& effects,
                                        const Simulator& simulator = Simulator(), const ShapeTable* shapes = nullptr) {
  Measurement m;
  for (std::vector<double>* column : {&m.time_s, &m.elongation_m, &m.force_N, &m.gauge_pressure_Pa, &m.temperature_K}) {
    column->reserve(crosshead.size());
  }
  const SolverStatistics statistics = detail::sealed_measurement_blocks(
      params, initial, crosshead, effects, simulator, detail::kMeasurementBlockSize,
      [&m](std::size_t, const Measurement& block) {
        m.time_s.insert(m.time_s.end(), block.time_s.begin(), block.time_s.end());
        m.elongation_m.insert(m.elongation_m.end(), block.elongation_m.begin(), block.elongation_m.end());
        m.force_N.insert(m.force_N.end(), block.force_N.begin(), block.force_N.end());
        m.gauge_pressure_Pa.insert(m.gauge_pressure_Pa.end(), block.gauge_pressure_Pa.begin(),
                                   block.gauge_pressure_Pa.end());
        m.temperature_K.insert(m.temperature_K.end(), block.temperature_K.begin(), block.temperature_K.end());
      },
      shapes);
  for (const EffectPtr& effect : effects) effect->apply_to_measurement(m);
  m.statistics = statistics;  // after the effects: a user effect may return a new Measurement
  return m;
}

/// `simulate_measurement`, its samples handed to `sink` in blocks of `block_size` as they are
/// integrated (Simulator::run_blocks): a long test's channels need not stand in memory at once,
/// only one block and the crosshead's trajectory do. The samples are simulate_measurement's,
/// bit for bit; `shapes` as there. An effect on the measured channels (EffectStage::measurement: a sensor's lag,
/// a clock's skew, a load cell's or thermometer's response) reads the whole series, a filter's
/// past or a later sample, so it is refused here: simulate the whole measurement for it.
/// \returns the solver's counters.
/// \throws InvalidParameter naming an effect that cannot act on a sealed test or on blocks;
///         InvalidInput for a block_size of 0; whatever the simulator or the sink throws.
inline SolverStatistics simulate_measurement_blocks(const MuscleParams& params, const InitialState& initial,
                                                    const ElongationTrajectory& crosshead,
                                                    const std::vector<EffectPtr>& effects, const Simulator& simulator,
                                                    std::size_t block_size, const MeasurementSink& sink,
                                                    const ShapeTable* shapes = nullptr) {
  for (const EffectPtr& effect : effects) {
    if (effect->stage() == EffectStage::measurement) {
      throw InvalidParameter(detail::message(effect->name(),
                                             " acts on the whole measured series, which a simulation in blocks "
                                             "never holds: simulate the whole measurement for it"));
    }
  }
  return detail::sealed_measurement_blocks(params, initial, crosshead, effects, simulator, block_size, sink, shapes);
}

/// Half the change of a supplied pressure that turns its branch [Pa]: above a settled step's noise.
constexpr double kPressureBranchPlay_Pa = 2e3;

/// The branch of each sample of a supplied pressure: +1 while it is raised, -1 while it is
/// lowered. A play operator of half-width `play_Pa` decides, so that noise in a hold or a
/// settled step does not flip it; the record starts on the pressurising branch.
/// \param gauge_pressure_Pa  the supplied gauge pressure, sample by sample [Pa]
/// \param play_Pa            half the change that turns the branch [Pa]
inline std::vector<double> pressure_branches(const std::vector<double>& gauge_pressure_Pa,
                                             double play_Pa = kPressureBranchPlay_Pa) {
  std::vector<double> branch(gauge_pressure_Pa.size(), 1.0);
  if (gauge_pressure_Pa.empty()) return branch;
  double extreme = gauge_pressure_Pa.front();
  double direction = 1.0;
  for (std::size_t k = 0; k < gauge_pressure_Pa.size(); ++k) {
    const double p = gauge_pressure_Pa[k];
    if (direction > 0.0 ? p > extreme : p < extreme) {
      extreme = p;
    } else if (std::abs(p - extreme) > 2.0 * play_Pa) {
      direction = -direction;
      extreme = p;
    }
    branch[k] = direction;
  }
  return branch;
}

namespace detail {
/// The effects a static table admits: physical ones that act at a supplied pressure, and
/// errors of the transducer whose reading drives the model. \throws InvalidParameter otherwise.
inline void apply_static_effects(const std::vector<EffectPtr>& effects, MuscleParams& extended,
                                 std::vector<double>& driving_Pa) {
  for (const EffectPtr& effect : effects) {
    std::string why_not;
    if (!effect->acts_in(GasMode::supplied, &why_not)) throw InvalidParameter(why_not);
    if (effect->stage() != EffectStage::physics && !effect->reads_supplied_pressure()) {
      throw InvalidParameter(detail::message(effect->name(),
                                             " acts on the motion or the instruments over time; a static table of "
                                             "settled rows has no time axis for it"));
    }
    effect->apply_to_supplied_pressure({}, driving_Pa);
    effect->apply_to_params(extended);
  }
  extended.validate();
}
}  // namespace detail

/// Simulates a supplied-pressure test as its instruments read it: the muscle hangs on a
/// regulator, so the measured gauge pressure drives the static model sample by sample (the gas
/// stays at the ambient temperature, `params.gas.ambient_temperature_K`), and force is what is
/// predicted. `effects` act at every stage, as in a sealed test; an effect that cannot act in a
/// supplied test is refused.
/// \param length_m           muscle length at zero elongation [m]
/// \param crosshead          the crosshead's elongation over time [m]
/// \param gauge_pressure_Pa  supplied gauge pressure at the crosshead's samples [Pa]
/// \throws InvalidParameter for an effect that cannot act here; InvalidInput naming the sample
///         whose length leaves the braid's range.
inline Measurement simulate_supplied_measurement(const MuscleParams& params, double length_m,
                                                 const ElongationTrajectory& crosshead,
                                                 const std::vector<double>& gauge_pressure_Pa,
                                                 const std::vector<EffectPtr>& effects) {
  const std::vector<double>& time = crosshead.time();
  if (gauge_pressure_Pa.size() != time.size()) {
    throw InvalidInput(detail::message("simulate_supplied_measurement: ", gauge_pressure_Pa.size(), " pressures for ",
                                       time.size(), " samples"));
  }
  MuscleParams extended = params;
  std::vector<double> motion = crosshead.elongation();
  std::vector<double> driving = gauge_pressure_Pa;
  for (const EffectPtr& effect : effects) {
    std::string why_not;
    if (!effect->acts_in(GasMode::supplied, &why_not)) throw InvalidParameter(why_not);
    effect->apply_to_supplied_pressure(time, driving);
    effect->apply_to_params(extended);
    motion = effect->apply_to_elongation(time, motion);
  }
  const BraidGeometry geometry(extended.build);
  Measurement m;
  m.time_s = time;
  m.elongation_m = crosshead.elongation();
  m.gauge_pressure_Pa = gauge_pressure_Pa;  // what the transducer read: the effects that read it made `driving`
  m.temperature_K.assign(time.size(), params.gas.ambient_temperature_K);
  m.force_N.resize(time.size());
  const std::vector<double> branch = pressure_branches(driving);
  // The muscle was mounted at rest and brought to the test's first length.
  HeldBraidState braid = braid_at_rest(extended.build);
  for (std::size_t k = 0; k < time.size(); ++k) {
    // The rate of the segment ending at each sample (of the first segment at the start), as
    // the sealed simulation's piecewise-linear trajectory has it.
    const std::size_t j = std::max<std::size_t>(k, 1);
    const double velocity = time.size() > 1 ? (motion[j] - motion[j - 1]) / (time[j] - time[j - 1]) : 0.0;
    try {
      geometry.shape(length_m + motion[k]);
    } catch (const InvalidInput& error) {
      throw InvalidInput(detail::message("sample ", k + 1, " (time ", time[k], " s, elongation ", motion[k], " m): ",
                                         error.what(), "; check the elongation's zero and [test] initial_length_m"));
    }
    m.force_N[k] = settle_held_braid(geometry, extended, braid, length_m + motion[k], driving[k], velocity, branch[k]);
  }
  for (const EffectPtr& effect : effects) {
    if (!effect->reads_supplied_pressure()) effect->apply_to_measurement(m);
  }
  return m;
}

/// The muscle's force at rest [N] at each (length, supplied gauge pressure) of a static table: an
/// isometric map, a free-inflation or isotonic table of settled steps, rows in the order they
/// were measured, one record (the pressurise/vent branch follows it, and so does the braid of
/// settle_held_braid, from rest at the deflated length: a map's held lengths are records of their
/// own). Friction, which needs a velocity, is zero at rest. Physical effects act through the
/// parameters, the supplied pressure's transducer through the pressure; a table has no time axis
/// for motion and other instruments.
/// \param lengths_m           muscle length of each row [m]
/// \param gauge_pressures_Pa  supplied gauge pressure of each row [Pa]
/// \throws InvalidParameter for an effect that cannot act on a static table; InvalidInput naming
///         the row whose length leaves the braid's range.
inline std::vector<double> static_forces(const MuscleParams& params, const std::vector<double>& lengths_m,
                                         const std::vector<double>& gauge_pressures_Pa,
                                         const std::vector<EffectPtr>& effects = {}) {
  if (lengths_m.size() != gauge_pressures_Pa.size()) {
    throw InvalidInput(
        detail::message("static_forces: ", lengths_m.size(), " lengths for ", gauge_pressures_Pa.size(), " pressures"));
  }
  MuscleParams extended = params;
  std::vector<double> driving = gauge_pressures_Pa;
  detail::apply_static_effects(effects, extended, driving);
  const BraidGeometry geometry(extended.build);
  const std::vector<double> branch = pressure_branches(driving);
  std::vector<double> force(lengths_m.size());
  HeldBraidState braid = braid_at_rest(extended.build);
  for (std::size_t k = 0; k < lengths_m.size(); ++k) {
    try {
      geometry.shape(lengths_m[k]);
    } catch (const InvalidInput& error) {
      throw InvalidInput(detail::message("row ", k + 1, " (length ", lengths_m[k], " m): ", error.what()));
    }
    force[k] = settle_held_braid(geometry, extended, braid, lengths_m[k], driving[k], 0.0, branch[k]);
  }
  return force;
}

/// Where an isotonic test's muscle settles at each row: its length [m], and whether the
/// equilibrium lay beyond the range searched (then the length is that end of the range).
struct IsotonicLengths {
  std::vector<double> length_m;
  std::vector<bool> at_limit;
  SlipState slip;  ///< what the Maxwell-slip elements hold after the last row
};

/// The length at which the muscle carries `load_N` at each supplied gauge pressure of an
/// isotonic test (a hanging mass, a slide, or nothing), rows in the order measured. The path is
/// quasi-static: each row starts from the previous row's length (`start_length_m` for the first)
/// and moves to the nearest equilibrium in the direction the imbalance drives it, shorter while
/// the muscle pulls more than the load. Where a light load has several equilibria, the muscle
/// stays on the branch it is on, as a real one does. The Maxwell-slip elements (muscle/slip.hpp)
/// start empty and follow the path. The search spans half the deflated length to 1.2 times it,
/// within the braid's range. A series compliance c (MuscleBuild::series_compliance_m_per_N)
/// carries the load too: the muscle's length is its braid's plus c times the load.
/// \param gauge_pressures_Pa  supplied gauge pressure of each row [Pa]
/// \param load_N              the load the muscle carries [N]
/// \param start_length_m      where the braid's first row's search starts [m] (its deflated
///                            length: the muscle at rest, the load then hung on)
/// \throws InvalidParameter for an effect that cannot act on a static table.
inline IsotonicLengths isotonic_lengths(const MuscleParams& params, const std::vector<double>& gauge_pressures_Pa,
                                        double load_N, double start_length_m,
                                        const std::vector<EffectPtr>& effects = {}) {
  MuscleParams extended = params;
  std::vector<double> driving = gauge_pressures_Pa;
  detail::apply_static_effects(effects, extended, driving);
  const BraidGeometry geometry(extended.build);
  const double deflated = extended.build.length_m;
  const double shortest = std::max(geometry.min_length() * (1.0 + 1e-9), 0.5 * deflated);
  const double longest = std::min(geometry.max_length() * (1.0 - 1e-6), 1.2 * deflated);
  const double step = (longest - shortest) / 400.0;
  const std::vector<double> branch = pressure_branches(driving);
  const ModelExtensions& x = extended.extensions;
  IsotonicLengths out;
  const double series_stretch = extended.build.series_compliance_m_per_N * load_N;
  double length = std::clamp(start_length_m, shortest, longest);
  for (std::size_t k = 0; k < driving.size(); ++k) {
    const double gauge = driving[k];
    const double start = length;
    auto imbalance = [&](double L) {
      const double slip = slip_total_after(out.slip, x.slip_force_N, x.slip_distance_m, L - start);
      return detail::supplied_force(geometry, extended, geometry.shape(L), gauge, 0.0, branch[k], slip) - load_N;
    };
    const double here = imbalance(length);
    const double direction = here > 0.0 ? -1.0 : 1.0;  // pulling more than the load: shorten
    double from = length;
    bool found = here == 0.0;
    while (!found) {
      const double to = std::clamp(from + direction * step, shortest, longest);
      if (to == from) break;
      const double there = imbalance(to);
      if ((there > 0.0) != (here > 0.0) || there == 0.0) {
        std::uintmax_t iterations = 100;
        const auto root = boost::math::tools::toms748_solve(imbalance, std::min(from, to), std::max(from, to),
                                                            boost::math::tools::eps_tolerance<double>(40), iterations);
        length = 0.5 * (root.first + root.second);
        found = true;
      }
      from = to;
    }
    if (!found) length = from;
    slip_move(out.slip, x.slip_force_N, x.slip_distance_m, length - start);
    out.length_m.push_back(length + series_stretch);
    out.at_limit.push_back(!found);
  }
  return out;
}

}  // namespace pamkit
