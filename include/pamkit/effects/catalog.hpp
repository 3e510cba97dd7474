#pragma once
/// \file
/// The built-in effect catalog: the candidate causes a diagnosis tries (model extensions, what real
/// muscles add, the instruments' errors), one header each in `builtin/`, each with physical
/// parameters, their realistic and plausible ranges, and what gives it away in the data.
/// `EffectCatalog::builtin()` below is the one place that names them: a new effect is its header,
/// an include and a line here.

#include "pamkit/effects/builtin/bladder_viscoelasticity.hpp"
#include "pamkit/effects/builtin/braid_slack.hpp"
#include "pamkit/effects/builtin/dead_volume.hpp"
#include "pamkit/effects/builtin/fiber_compliance.hpp"
#include "pamkit/effects/builtin/fixture_slack.hpp"
#include "pamkit/effects/builtin/heat_transfer.hpp"
#include "pamkit/effects/builtin/leak.hpp"
#include "pamkit/effects/builtin/load_cell.hpp"
#include "pamkit/effects/builtin/pressure_hysteresis.hpp"
#include "pamkit/effects/builtin/sensor_lag.hpp"
#include "pamkit/effects/builtin/sensor_offset.hpp"
#include "pamkit/effects/builtin/slip_hysteresis.hpp"
#include "pamkit/effects/builtin/thermometer.hpp"
#include "pamkit/effects/builtin/time_skew.hpp"
#include "pamkit/effects/effect.hpp"

namespace pamkit {

namespace detail {
/// Adds the built-in `EffectType` (a ParametricEffect) under its parameters' `kName`.
template <class EffectType>
void add_builtin(EffectCatalog& catalog) {
  catalog.add(EffectType::Params::kName, [] { return std::make_shared<EffectType>(); });
}
}  // namespace detail

inline EffectCatalog EffectCatalog::builtin() {
  EffectCatalog catalog;
  detail::add_builtin<HeatTransferEffect>(catalog);
  detail::add_builtin<DeadVolumeEffect>(catalog);
  detail::add_builtin<LeakEffect>(catalog);
  detail::add_builtin<BladderViscoelasticityEffect>(catalog);
  detail::add_builtin<FiberComplianceEffect>(catalog);
  detail::add_builtin<FixtureSlackEffect>(catalog);
  detail::add_builtin<BraidSlackEffect>(catalog);
  detail::add_builtin<PressureHysteresisEffect>(catalog);
  detail::add_builtin<SlipHysteresisEffect>(catalog);
  detail::add_builtin<SensorLagEffect>(catalog);
  detail::add_builtin<TimeSkewEffect>(catalog);
  detail::add_builtin<SensorOffsetEffect>(catalog);
  detail::add_builtin<LoadCellEffect>(catalog);
  detail::add_builtin<ThermometerEffect>(catalog);
  return catalog;
}

}  // namespace pamkit
