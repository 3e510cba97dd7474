#pragma once
/// \file
/// The muscle as a dynamic system: parameters, the gas state, and the right-hand side of its
/// ODE. The model only computes derivatives and outputs; `Simulator` integrates it.

#include <cmath>

#include "pamkit/gas/air.hpp"
#include "pamkit/muscle/force.hpp"

namespace pamkit {

/// Everything that defines a muscle, constant during a simulation.
struct MuscleParams {
  MuscleBuild build;                          ///< the build (deflated dimensions, braid)
  BladderLaw bladder = BladderLaw::thesis();  ///< bladder stress law (eqs. 3.1.12-3.1.13)
  FrictionParams friction;                    ///< friction (eqs. 3.1.19-3.1.24)
  GasParams gas;                              ///< air, ambient, gas process

  /// \throws InvalidParameter naming the first bad field.
  void validate() const {
    build.validate();
    friction.validate();
    gas.validate();
  }
};

/// The state of the test when elongation is zero: the muscle inflated, sealed, at rest.
struct InitialState {
  static constexpr const char* kName = "InitialState";

  double length_m = 0.167;               ///< muscle length at zero elongation [m] (table C.2)
  double gauge_pressure_Pa = 236.63e3;   ///< gauge gas pressure at that length [Pa] (table C.2, 90 %)

  template <class Visitor>
  static void for_each_field(Visitor&& visit) {
    visit("length_m", &InitialState::length_m, FieldInfo{"m", 1e-3, 5.0, "muscle length at zero elongation"});
    visit("gauge_pressure_Pa", &InitialState::gauge_pressure_Pa, FieldInfo{"Pa", 0.0, 2e6, "gauge pressure at zero elongation"});
  }
  void validate() const { validate_fields(*this); }
};

/// What the model says at one instant.
struct MuscleOutputs {
  MuscleShape shape;              ///< geometry at this length
  MuscleForces forces;            ///< force and its parts [N]
  double absolute_pressure_Pa;    ///< gas pressure, absolute
  double gauge_pressure_Pa;       ///< gas pressure above ambient
  double temperature_K;           ///< gas temperature
  double temperature_rate_K_per_s;///< dT/dt
  double heat_loss_rate_W;        ///< heat flowing from the gas to the wall
};

/// A muscle in a test: parameters plus the sealed gas mass. Immutable, so one model may be
/// simulated from many threads at once.
class MuscleModel {
 public:
  /// Number of ODE states: the gas temperature [K].
  static constexpr int kStateSize = 1;

  /// \throws InvalidParameter for bad parameters, InvalidInput if the initial length is
  ///         outside what the braid allows.
  MuscleModel(const MuscleParams& params, const InitialState& initial);

  /// Outputs and derivative at muscle length `length_m`, elongation rate `velocity_m_per_s`
  /// and gas temperature `temperature_K`.
  MuscleOutputs evaluate(double length_m, double velocity_m_per_s, double temperature_K) const;

  /// Gas temperature at the start [K]: the ambient temperature.
  double initial_temperature() const { return params_.gas.ambient_temperature_K; }
  /// Sealed mass of air [kg], from the initial state by the ideal gas law (eq. 3.1.17).
  double gas_mass() const { return gas_mass_; }
  /// Gas volume at the initial length [m^3].
  double initial_gas_volume() const { return initial_gas_volume_; }

  const MuscleParams& params() const { return params_; }
  const InitialState& initial_state() const { return initial_; }
  const BraidGeometry& geometry() const { return geometry_; }

 private:
  MuscleParams params_;
  InitialState initial_;
  BraidGeometry geometry_;
  double gas_mass_;
  double initial_gas_volume_;
};

inline MuscleModel::MuscleModel(const MuscleParams& params, const InitialState& initial)
    : params_(params), initial_(initial), geometry_((params.validate(), params.build)) {
  initial_.validate();
  const MuscleShape s = geometry_.shape(initial_.length_m);
  initial_gas_volume_ = s.gas_volume;
  const GasParams& g = params_.gas;
  gas_mass_ = (g.atmospheric_pressure_Pa + initial_.gauge_pressure_Pa) * s.gas_volume /
              (g.gas_constant_J_per_kgK * g.ambient_temperature_K);
}

inline MuscleOutputs MuscleModel::evaluate(double length_m, double velocity_m_per_s, double temperature_K) const {
  const GasParams& g = params_.gas;
  MuscleOutputs out{};
  out.shape = geometry_.shape(length_m);
  const double volume = out.shape.gas_volume;
  const double volume_rate = out.shape.d_gas_volume * velocity_m_per_s;
  out.temperature_K = temperature_K;
  out.absolute_pressure_Pa = gas_mass_ * g.gas_constant_J_per_kgK * temperature_K / volume;  // eq. 3.1.17
  out.gauge_pressure_Pa = out.absolute_pressure_Pa - g.atmospheric_pressure_Pa;
  const double cv = g.specific_heat_cv();
  if (g.process == GasProcess::polytropic) {
    // d/dt of T V^(n-1) = const (eq. 3.1.18).
    out.temperature_rate_K_per_s = -(g.polytropic_index - 1.0) * temperature_K * volume_rate / volume;
    // First law, m cv dT = dQ - p dV, solved for the heat the process must exchange.
    out.heat_loss_rate_W = -(gas_mass_ * cv * out.temperature_rate_K_per_s + out.absolute_pressure_Pa * volume_rate);
  } else {
    const double tau = g.heat_transfer_time_constant_s;
    out.heat_loss_rate_W = gas_mass_ * cv * (temperature_K - g.ambient_temperature_K) / tau;
    out.temperature_rate_K_per_s =
        -(out.absolute_pressure_Pa * volume_rate + out.heat_loss_rate_W) / (gas_mass_ * cv);
  }
  out.forces = muscle_forces(geometry_, out.shape, params_.bladder, params_.friction, out.absolute_pressure_Pa,
                             g.atmospheric_pressure_Pa, velocity_m_per_s);
  return out;
}

}  // namespace pamkit
