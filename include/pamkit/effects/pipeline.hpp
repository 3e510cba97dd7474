#pragma once
/// \file
/// A bench test as its instruments see it: the model extended by effects, driven through the
/// fixture, read through the sensors.

#include <algorithm>

#include "pamkit/effects/effect.hpp"
#include "pamkit/sim/simulator.hpp"
#include "pamkit/units.hpp"

namespace pamkit {

/// Simulates a sealed test with `effects` applied at every stage, in order: parameters, the
/// muscle's motion from the crosshead's `crosshead`, then the measured channels. The result's
/// elongation is the crosshead's (what the machine records).
/// \throws InvalidParameter if an effect cannot act on a sealed test, and whatever the
///         simulator throws.
inline Measurement simulate_measurement(const MuscleParams& params, const InitialState& initial,
                                        const ElongationTrajectory& crosshead, const std::vector<EffectPtr>& effects,
                                        const Simulator& simulator = Simulator()) {
  MuscleParams extended = params;
  std::vector<double> motion = crosshead.elongation();
  for (const EffectPtr& effect : effects) {
    std::string why_not;
    if (!effect->acts_in(GasMode::sealed, &why_not)) throw InvalidParameter(why_not);
    effect->apply_to_params(extended);
    motion = effect->apply_to_elongation(crosshead.time(), motion);
  }
  const SimulationResult r =
      simulator.run(MuscleModel(extended, initial), ElongationTrajectory(crosshead.time(), motion));
  Measurement m;
  m.time_s = r.time_s;
  m.elongation_m = crosshead.elongation();
  m.force_N = r.force_N;
  m.pressure_kPa.reserve(r.time_s.size());
  m.temperature_C.reserve(r.time_s.size());
  for (std::size_t k = 0; k < r.time_s.size(); ++k) {
    m.pressure_kPa.push_back(units::kilopascal_from_pascal(r.pressure_gauge_Pa[k]));
    m.temperature_C.push_back(units::celsius_from_kelvin(r.temperature_K[k]));
  }
  for (const EffectPtr& effect : effects) effect->apply_to_measurement(m);
  return m;
}

/// Simulates a supplied-pressure test as its instruments read it: the muscle hangs on a
/// regulator, so the measured gauge pressure drives the static model sample by sample (the gas
/// stays at `ambient_temperature_C`), and force is what is predicted. `effects` act at every
/// stage, as in a sealed test; an effect that cannot act in a supplied test is refused.
/// \param length_m          muscle length at zero elongation [m]
/// \param crosshead         the crosshead's elongation over time [m]
/// \param pressure_kPa      supplied gauge pressure at the crosshead's samples [kPa]
/// \throws InvalidParameter for an effect that cannot act here; InvalidInput naming the sample
///         whose length leaves the braid's range.
inline Measurement simulate_supplied_measurement(const MuscleParams& params, double length_m,
                                                 const ElongationTrajectory& crosshead,
                                                 const std::vector<double>& pressure_kPa, double ambient_temperature_C,
                                                 const std::vector<EffectPtr>& effects) {
  const std::vector<double>& time = crosshead.time();
  if (pressure_kPa.size() != time.size()) {
    throw InvalidInput(detail::message("simulate_supplied_measurement: ", pressure_kPa.size(), " pressures for ",
                                       time.size(), " samples"));
  }
  MuscleParams extended = params;
  std::vector<double> motion = crosshead.elongation();
  for (const EffectPtr& effect : effects) {
    std::string why_not;
    if (!effect->acts_in(GasMode::supplied, &why_not)) throw InvalidParameter(why_not);
    effect->apply_to_params(extended);
    motion = effect->apply_to_elongation(time, motion);
  }
  const BraidGeometry geometry(extended.build);
  const double atmosphere = extended.gas.atmospheric_pressure_Pa;
  Measurement m;
  m.time_s = time;
  m.elongation_m = crosshead.elongation();
  m.pressure_kPa = pressure_kPa;
  m.temperature_C.assign(time.size(), ambient_temperature_C);
  m.force_N.resize(time.size());
  for (std::size_t k = 0; k < time.size(); ++k) {
    // The rate of the segment ending at each sample (of the first segment at the start), as
    // the sealed simulation's piecewise-linear trajectory has it.
    const std::size_t j = std::max<std::size_t>(k, 1);
    const double velocity = time.size() > 1 ? (motion[j] - motion[j - 1]) / (time[j] - time[j - 1]) : 0.0;
    MuscleShape shape;
    try {
      shape = geometry.shape(length_m + motion[k]);
    } catch (const InvalidInput& error) {
      throw InvalidInput(detail::message("sample ", k + 1, " (time ", time[k], " s, elongation ", motion[k], " m): ",
                                         error.what(), "; check the elongation's zero and [test] initial_length_m"));
    }
    m.force_N[k] =
        braid_tension(muscle_forces(geometry, shape, extended.bladder, extended.friction,
                                    atmosphere + units::pascal_from_kilopascal(pressure_kPa[k]), atmosphere, velocity)
                          .total,
                      extended.extensions.slack_band_N);
  }
  for (const EffectPtr& effect : effects) effect->apply_to_measurement(m);
  return m;
}

/// The muscle's force at rest [N] at each (length, supplied gauge pressure) of a static table: an
/// isometric map, a free-inflation or isotonic table of settled steps. Friction, which needs a
/// velocity, is zero at rest. Only physical effects act (through the parameters): a table has
/// no time axis for motion and instrument effects.
/// \param lengths_m            muscle length of each row [m]
/// \param gauge_pressures_kPa  supplied gauge pressure of each row [kPa]
/// \throws InvalidParameter for an effect that cannot act on a static table; InvalidInput naming
///         the row whose length leaves the braid's range.
inline std::vector<double> static_forces(const MuscleParams& params, const std::vector<double>& lengths_m,
                                         const std::vector<double>& gauge_pressures_kPa,
                                         const std::vector<EffectPtr>& effects = {}) {
  if (lengths_m.size() != gauge_pressures_kPa.size()) {
    throw InvalidInput(detail::message("static_forces: ", lengths_m.size(), " lengths for ", gauge_pressures_kPa.size(),
                                       " pressures"));
  }
  MuscleParams extended = params;
  for (const EffectPtr& effect : effects) {
    std::string why_not;
    if (effect->stage() != EffectStage::physics) {
      throw InvalidParameter(detail::message(effect->name(),
                                             " acts on the motion or the instruments over time; a static table of "
                                             "settled rows has no time axis for it"));
    }
    if (!effect->acts_in(GasMode::supplied, &why_not)) throw InvalidParameter(why_not);
    effect->apply_to_params(extended);
  }
  extended.validate();
  const BraidGeometry geometry(extended.build);
  const double atmosphere = extended.gas.atmospheric_pressure_Pa;
  std::vector<double> force(lengths_m.size());
  for (std::size_t k = 0; k < lengths_m.size(); ++k) {
    MuscleShape shape;
    try {
      shape = geometry.shape(lengths_m[k]);
    } catch (const InvalidInput& error) {
      throw InvalidInput(detail::message("row ", k + 1, " (length ", lengths_m[k], " m): ", error.what()));
    }
    const double gauge = units::pascal_from_kilopascal(gauge_pressures_kPa[k]);
    force[k] = braid_tension(
        muscle_forces(geometry, shape, extended.bladder, extended.friction, atmosphere + gauge, atmosphere, 0.0).total,
        extended.extensions.slack_band_N);
  }
  return force;
}

}  // namespace pamkit
