#pragma once
/// \file
/// A bench test as its instruments see it: the model extended by effects, driven through the
/// fixture, read through the sensors.

#include "pamkit/effects/effect.hpp"
#include "pamkit/sim/simulator.hpp"

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
    m.pressure_kPa.push_back(r.pressure_gauge_Pa[k] * 1e-3);
    m.temperature_C.push_back(r.temperature_K[k] - 273.15);
  }
  for (const EffectPtr& effect : effects) effect->apply_to_measurement(m);
  return m;
}

}  // namespace pamkit
