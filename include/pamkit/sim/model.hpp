#pragma once
/// \file
/// The muscle as a dynamic system: parameters, its state, and the right-hand side of its ODE.
/// The model only computes derivatives and outputs; `Simulator` integrates it.

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "pamkit/gas/air.hpp"
#include "pamkit/muscle/force.hpp"
#include "pamkit/muscle/free_inflation.hpp"
#include "pamkit/muscle/slip.hpp"

namespace pamkit {

/// Physics beyond the thesis's model, all off (zero) by default. The effect catalog
/// (include/pamkit/effects) switches them on; with every field at zero the model is the
/// thesis's, operation for operation.
struct ModelExtensions {
  static constexpr const char* kName = "ModelExtensions";

  double dead_volume_fraction =
      0.0;                       ///< gas volume outside the muscle (hose, transducer) over the initial gas volume [1]
  double leak_rate_per_s = 0.0;  ///< 1/tau of the gauge pressure's decay through an orifice at fixed volume [1/s]
  double viscoelastic_strength = 0.0;  ///< modulus of the bladder's Maxwell branch over the law's tangent modulus [1]
  double viscoelastic_time_constant_s = 1.0;  ///< relaxation time of that branch [s]
  double fiber_compliance_per_N = 0.0;        ///< 1 / axial stiffness EA of one fiber [1/N]; 0: inextensible
  double slack_band_N = 0.0;  ///< the braid cannot push: width of its smooth slack transition [N]; 0: it can (thesis)
  double pressure_hysteresis =
      0.0;                        ///< bladder-braid friction under a supplied pressure, as a fraction of p pi D^2/4 [1]
  double slip_force_N = 0.0;      ///< Maxwell-slip friction with memory: the elements' slip force together [N]; 0: none
  double slip_distance_m = 0.01;  ///< its break-away displacements spread over (0, this] [m] (muscle/slip.hpp)

  template <class Visitor>
  static void for_each_field(Visitor&& visit) {
    visit("dead_volume_fraction", &ModelExtensions::dead_volume_fraction,
          FieldInfo{"1", 0.0, 10.0, "dead gas volume / initial gas volume"});
    visit("leak_rate_per_s", &ModelExtensions::leak_rate_per_s,
          FieldInfo{"1/s", 0.0, 1e3, "leak rate (1 / time constant)"});
    visit("viscoelastic_strength", &ModelExtensions::viscoelastic_strength,
          FieldInfo{"1", 0.0, 100.0, "bladder Maxwell-branch modulus ratio"});
    visit("viscoelastic_time_constant_s", &ModelExtensions::viscoelastic_time_constant_s,
          FieldInfo{"s", 1e-4, 1e6, "bladder relaxation time"});
    visit("fiber_compliance_per_N", &ModelExtensions::fiber_compliance_per_N,
          FieldInfo{"1/N", 0.0, 1.0, "1 / fiber axial stiffness"});
    visit("slack_band_N", &ModelExtensions::slack_band_N,
          FieldInfo{"N", 0.0, 1e4, "width of the slack braid's smooth transition (0: the braid pushes)"});
    visit("pressure_hysteresis", &ModelExtensions::pressure_hysteresis,
          FieldInfo{"1", 0.0, 10.0, "pressurise/vent friction over the pressure force p pi D^2/4"});
    visit("slip_force_N", &ModelExtensions::slip_force_N,
          FieldInfo{"N", 0.0, 1e5, "Maxwell-slip friction with memory: slip force of its elements together"});
    visit("slip_distance_m", &ModelExtensions::slip_distance_m,
          FieldInfo{"m", 1e-6, 1.0, "Maxwell-slip friction: break-away displacements spread over (0, this]"});
  }
  void validate() const { validate_fields(*this); }
};

/// Everything that defines a muscle, constant during a simulation.
struct MuscleParams {
  MuscleBuild build;                          ///< the build (deflated dimensions, braid)
  BladderLaw bladder = BladderLaw::thesis();  ///< bladder stress law (eqs. 3.1.12-3.1.13)
  FrictionParams friction;                    ///< friction (eqs. 3.1.19-3.1.24)
  GasParams gas;                              ///< air, ambient, gas process
  ModelExtensions extensions;                 ///< physics beyond the thesis, off by default

  /// \throws InvalidParameter naming the first bad field.
  void validate() const {
    build.validate();
    friction.validate();
    gas.validate();
    extensions.validate();
  }
};

namespace detail {
/// Width of the smooth slack transition [N] of fibres embedded in the membrane when no
/// `braid_slack` effect sets one: the width a diagnosis holds that effect at.
constexpr double kEmbeddedSlackBand_N = 1.0;

/// The width of the braid's slack transition [N] that this muscle's force passes through
/// (`braid_tension`): the extension's when set (the catalog's braid_slack), else
/// kEmbeddedSlackBand_N for fibres embedded in the membrane, whose braid cannot push as base
/// physics, else 0: the thesis's braid, which pushes.
inline double slack_band_N(const MuscleParams& params) noexcept {
  if (params.extensions.slack_band_N > 0.0) return params.extensions.slack_band_N;
  return params.build.construction == Construction::embedded ? kEmbeddedSlackBand_N : 0.0;
}

/// What the muscle under a supplied pressure would carry on one branch before the braid's slack:
/// gas, bladder and friction, less the rate-independent bladder-braid friction, plus what the
/// Maxwell-slip elements hold (`slip_N`, SlipState::total_N). The pressure hysteresis resists
/// the motion the pressure drives: raising the pressure contracts the muscle, so the tension it
/// shows is lower than the elastic force; lowering it, higher. `branch` is +1 pressurising, -1
/// venting (pressure_branches, effects/pipeline.hpp); 0 leaves the hysteresis out.
inline double unslackened_supplied_force(const BraidGeometry& geometry, const MuscleParams& extended,
                                         const MuscleShape& shape, double gauge_Pa, double velocity_m_per_s,
                                         double branch, double slip_N) noexcept {
  const double atmosphere = extended.gas.atmospheric_pressure_Pa;
  const double elastic = muscle_forces(geometry, shape, extended.bladder, extended.friction, atmosphere + gauge_Pa,
                                       atmosphere, velocity_m_per_s)
                             .total;
  const double hysteresis = extended.extensions.pressure_hysteresis * std::max(gauge_Pa, 0.0) * 0.25 * detail::kPi *
                            shape.diameter * shape.diameter;
  return elastic - branch * hysteresis + slip_N;
}

/// What the load cell reads of a muscle under a supplied pressure: `unslackened_supplied_force`
/// through a braid that cannot push (slack_band_N).
inline double supplied_force(const BraidGeometry& geometry, const MuscleParams& extended, const MuscleShape& shape,
                             double gauge_Pa, double velocity_m_per_s, double branch, double slip_N = 0.0) noexcept {
  return braid_tension(
      unslackened_supplied_force(geometry, extended, shape, gauge_Pa, velocity_m_per_s, branch, slip_N),
      slack_band_N(extended));
}
}  // namespace detail

/// The state of the test when elongation is zero: the muscle inflated, sealed, at rest.
struct InitialState {
  static constexpr const char* kName = "InitialState";

  double length_m = 0.167;              ///< muscle length at zero elongation [m] (table C.2)
  double gauge_pressure_Pa = 236.63e3;  ///< gauge gas pressure at that length [Pa] (table C.2, 90 %)

  template <class Visitor>
  static void for_each_field(Visitor&& visit) {
    visit("length_m", &InitialState::length_m, FieldInfo{"m", 1e-3, 5.0, "muscle length at zero elongation"});
    visit("gauge_pressure_Pa", &InitialState::gauge_pressure_Pa,
          FieldInfo{"Pa", 0.0, 2e6, "gauge pressure at zero elongation"});
  }
  void validate() const { validate_fields(*this); }
};

/// The thesis's protocol at the start of a sealed test: inflated freely (no force) to
/// `gauge_pressure_Pa`, then sealed, at the free length that pressure gives (table 3.4). Compliant
/// fibers (ModelExtensions::fiber_compliance_per_N) stretch under the tension the inflation puts
/// in them: their free length is where the muscle, its fibers balanced at that pressure as
/// MuscleModel seals them, carries no force.
/// \throws InvalidInput if the muscle cannot inflate freely to that pressure.
inline InitialState inflated_and_sealed(const MuscleParams& params, double gauge_pressure_Pa);

/// The ODE state. The energy integrals ride along as states so that one right-hand side
/// evaluation serves them and the physics alike.
struct State {
  enum Index : int {
    temperature_K,          ///< gas temperature
    gas_mass_kg,            ///< mass of air inside (falls through a leak)
    viscous_stress_l_Pa,    ///< bladder Maxwell-branch stress, longitudinal
    viscous_stress_h_Pa,    ///< bladder Maxwell-branch stress, hoop
    work_J,                 ///< work done on the muscle since the start, integral of F dL
    heat_lost_J,            ///< heat from the gas to the wall since the start
    friction_dissipated_J,  ///< friction work since the start
    size
  };
  std::array<double, size> values{};

  double& operator[](int i) { return values[static_cast<std::size_t>(i)]; }
  double operator[](int i) const { return values[static_cast<std::size_t>(i)]; }
};

/// What the model says at one instant.
struct MuscleOutputs {
  MuscleShape shape;      ///< geometry of the braid
  MuscleForces forces;    ///< force and its parts [N] (viscous bladder stress in `bladder`)
  double fiber_length_m;  ///< the fibers' length over the cylinder [m]: the build's, stretched when compliant
  double fiber_length_rate_m_per_s;  ///< its rate [m/s]; 0 for inextensible fibers
  double fiber_tension_N;            ///< one fiber's tension [N] when compliant; NaN (not computed) when inextensible
  double gas_volume_m3;              ///< gas volume including any dead volume [m^3]
  double absolute_pressure_Pa;       ///< gas pressure, absolute
  double gauge_pressure_Pa;          ///< gas pressure above ambient
  double heat_loss_rate_W;           ///< heat flowing from the gas to the wall
  State rate;                        ///< d(state)/dt
};

/// The mutable half of model evaluations, as Pinocchio splits Model from Data: what one caller
/// carries from one `MuscleModel::evaluate` to the next. One per simulation (or thread), so the
/// const model stays shareable.
struct MuscleWorkspace {
  ShapeHint shape;  ///< where the braid's last closure solve ended
  /// Compliant fibers only: the fibers' length [m] where their last balance solve ended, and the
  /// slope there of its residual in that length [1] (NaN: none yet). The next solve starts
  /// there: a chord Newton iteration from a nearby length instead of a bracketing search.
  double fiber_length_m = std::numeric_limits<double>::quiet_NaN();
  double fiber_balance_slope = std::numeric_limits<double>::quiet_NaN();
};

namespace detail {
/// Compliant fibers at their balance in one evaluation: what the state's rates need.
struct FiberBalance {
  FiberLengthDerivatives shape;  ///< the shape's derivatives in the fiber length at the balance
  double tension_N;              ///< the fibers' tension together, N T [N] (total_fiber_tension)
  double d_tension_d_length;     ///< d(N T)/dL at fixed fiber length, gas pressure and viscous stresses [N/m]
  double d_tension_d_fiber;      ///< d(N T)/db at fixed muscle length, gas pressure and viscous stresses [N/m]
};
}  // namespace detail

/// A muscle in a test: parameters plus the sealed gas mass. Immutable, so one model may be
/// simulated from many threads at once.
class MuscleModel {
 public:
  /// \throws InvalidParameter for bad parameters, InvalidInput if the initial length is
  ///         outside what the braid allows.
  MuscleModel(const MuscleParams& params, const InitialState& initial);

  /// Outputs and state derivative at muscle length `length_m` and elongation rate
  /// `velocity_m_per_s` (the crosshead's), in state `state`.
  MuscleOutputs evaluate(double length_m, double velocity_m_per_s, const State& state) const;

  /// `evaluate`, the braid's closure started from `workspace` (which it updates), with the
  /// shape's `parts`: `ShapeParts::kinematics` leaves the angles of `MuscleOutputs::shape`
  /// NaN, which the rates do not need. Agrees with the cold evaluation to the closure's Newton
  /// tolerance (about 1e-14 relative).
  MuscleOutputs evaluate_with(MuscleWorkspace& workspace, double length_m, double velocity_m_per_s, const State& state,
                              ShapeParts parts) const;

  /// `evaluate_with` at a braid shape solved beforehand (a ShapeTable's, sim/shape_table.hpp),
  /// for fibers that are inextensible. The same operations on the same shape as
  /// `evaluate_with`, so the same outputs bit for bit.
  /// \throws InvalidInput if the fibers are compliant (fiber_compliance_per_N > 0): their
  ///         length depends on their tension, so on the gas's state, and no shape fixed
  ///         beforehand holds it.
  MuscleOutputs evaluate_at_shape(const MuscleShape& shape, double velocity_m_per_s, const State& state) const;

  /// The state at zero elongation: ambient temperature, the sealed mass, no viscous stress.
  State initial() const;

  /// The fastest rate [1/s] at which a state relaxes on its own, whatever the motion: the gas
  /// temperature towards the wall's (1 / the heat-transfer time constant), the gas mass through a
  /// leak (its rate) and the bladder's viscous stresses (1 / their time constant, when the
  /// branch is on); 0 when none relaxes (a polytropic sealed muscle). The rates the motion drives
  /// (dV/dt / V) change on the trajectory's own time scale and do not make a run stiff.
  double fastest_rate_per_s() const;

  /// Gas temperature at the start [K]: the ambient temperature.
  double initial_temperature() const { return params_.gas.ambient_temperature_K; }
  /// Sealed mass of air at the start [kg], from the initial state by the ideal gas law (eq. 3.1.17).
  double gas_mass() const { return gas_mass_; }
  /// Gas volume at the initial length [m^3], dead volume included.
  double initial_gas_volume() const { return initial_gas_volume_; }
  /// Dead volume [m^3].
  double dead_volume() const { return dead_volume_; }

  const MuscleParams& params() const { return params_; }
  const InitialState& initial_state() const { return initial_; }
  const BraidGeometry& geometry() const { return geometry_; }

 private:
  /// Compliant fibers: the length b' = b (1 + T / EA) [m] at which their tension T balances
  /// their stretch at muscle length `length_m`, the gas's absolute pressure following its volume
  /// (dead volume included) by `absolute_of_volume` and the bladder carrying the viscous stresses
  /// `viscous`. A fiber cannot be compressed: where T would be negative, b' = b. Started from
  /// where `workspace` ended; leaves there the solution and its residual's slope.
  /// \throws InvalidInput if no fiber length in the braid's range balances.
  template <class AbsoluteOfVolume>
  double balanced_fiber_length(double length_m, const AbsoluteOfVolume& absolute_of_volume,
                               const BiaxialStress& viscous, MuscleWorkspace& workspace) const;
  /// The bracketing search balanced_fiber_length falls back on where Newton does not converge.
  template <class AbsoluteOfVolume>
  double bracketed_fiber_length(double length_m, const AbsoluteOfVolume& absolute_of_volume,
                                const BiaxialStress& viscous, ShapeHint& hint) const;
  /// The fibers' tension together, N T [N], at muscle length `length_m` and fiber length
  /// `fiber_length_m`, the gas's absolute pressure `absolute_of_volume` of its volume.
  template <class AbsoluteOfVolume>
  double fiber_tension_at(double length_m, double fiber_length_m, const AbsoluteOfVolume& absolute_of_volume,
                          const BiaxialStress& viscous, ShapeHint& hint) const;
  /// One fiber's stretch per newton of the fibers' tension together, b / (N EA) [m/N].
  double stretch_per_newton() const;
  /// Fills `out`'s gas, forces and rates from its shape at the crosshead's rate
  /// `velocity_m_per_s` in state `state`; `fibers` is the compliant fibers' balance (nullptr:
  /// inextensible), whose rate of length the gas's and the bladder's rates then share.
  void complete_outputs(MuscleOutputs& out, double velocity_m_per_s, const State& state,
                        const detail::FiberBalance* fibers) const;

  MuscleParams params_;
  InitialState initial_;
  BraidGeometry geometry_;
  double dead_volume_;
  double gas_mass_;
  double initial_gas_volume_;
  double rubber_volume_;
};

}  // namespace pamkit

#include "pamkit/sim/model.hxx"
