#pragma once

#include <algorithm>
#include <cstdint>

#include <boost/math/tools/roots.hpp>

namespace pamkit {

inline MuscleModel::MuscleModel(const MuscleParams& params, const InitialState& initial)
    : params_(params), initial_(initial), geometry_((params.validate(), params.build)) {
  initial_.validate();
  if (params_.build.series_compliance_m_per_N > 0.0) {
    // The braid's length would be an algebraic unknown of the ODE's every state (L - c F).
    PAMKIT_THROW(InvalidParameter(detail::message(
        "MuscleBuild.series_compliance_m_per_N = ", params_.build.series_compliance_m_per_N,
        " m/N: a series compliance is modelled where the muscle is settled (static tables, supplied tests, the "
        "real-time force), not in a sealed test's simulation; give 0 there")));
  }
  const GasParams& g = params_.gas;
  MuscleShape s = geometry_.shape(initial_.length_m);
  if (params_.extensions.fiber_compliance_per_N > 0.0) {
    // Inflated to the initial pressure at the initial length, the fibers stretched under it
    // before the muscle was sealed: the gas volume is the stretched braid's.
    dead_volume_ = 0.0;  // a held pressure does not follow the volume
    const double absolute = g.atmospheric_pressure_Pa + initial_.gauge_pressure_Pa;
    MuscleWorkspace inflating;
    const double fiber = balanced_fiber_length(
        initial_.length_m, [absolute](double) { return absolute; }, BiaxialStress{0.0, 0.0}, inflating);
    s = geometry_.shape_from(inflating.shape, initial_.length_m, fiber, ShapeParts::all);
  }
  dead_volume_ = params_.extensions.dead_volume_fraction * s.gas_volume;
  initial_gas_volume_ = s.gas_volume + dead_volume_;
  gas_mass_ = (g.atmospheric_pressure_Pa + initial_.gauge_pressure_Pa) * initial_gas_volume_ /
              (g.gas_constant_J_per_kgK * g.ambient_temperature_K);
  rubber_volume_ = bladder_reference_volume(geometry_);
}

inline InitialState inflated_and_sealed(const MuscleParams& params, double gauge_pressure_Pa) {
  const BraidGeometry geometry(params.build);
  const FreeInflation free =
      free_inflation(geometry, params.bladder, params.gas.atmospheric_pressure_Pa, gauge_pressure_Pa);
  const InitialState rigid{free.length_m, gauge_pressure_Pa};
  if (!(params.extensions.fiber_compliance_per_N > 0.0) || !free.contracted) return rigid;
  // Sealed at the rigid braid's free length, stretched fibers would push (their braid is
  // longer there): the force at rest rises with the length, so the free length lies beyond,
  // where a bracket grows until the force turns.
  const auto force_at_rest = [&](double length_m) {
    const MuscleModel model(params, InitialState{length_m, gauge_pressure_Pa});
    return model.evaluate(length_m, 0.0, model.initial()).forces.total;
  };
  double shorter = free.length_m;
  double pushing = force_at_rest(shorter);
  if (!(pushing < 0.0)) return rigid;  // fibers that the inflation leaves slack do not stretch
  const double longest = geometry.max_length() * (1.0 - 1e-9);
  double step = 1e-4 * free.length_m;
  double longer = shorter;
  double pulling = pushing;
  while (pulling < 0.0) {
    if (longer >= longest) {
      PAMKIT_THROW(InvalidInput(detail::message("inflated freely to ", gauge_pressure_Pa,
                                                " Pa, compliant fibers push at every length the braid allows up to ",
                                                longest, " m: no free length")));
    }
    shorter = longer;
    pushing = pulling;
    longer = std::min(longer + step, longest);
    step *= 2.0;
    pulling = force_at_rest(longer);
  }
  std::uintmax_t iterations = 60;
  const auto [a, b] = boost::math::tools::toms748_solve(force_at_rest, shorter, longer, pushing, pulling,
                                                        boost::math::tools::eps_tolerance<double>(50), iterations);
  return InitialState{0.5 * (a + b), gauge_pressure_Pa};
}

inline State MuscleModel::initial() const {
  State y;
  y[State::temperature_K] = initial_temperature();
  y[State::gas_mass_kg] = gas_mass_;
  return y;
}

inline double MuscleModel::fastest_rate_per_s() const {
  const GasParams& g = params_.gas;
  const ModelExtensions& x = params_.extensions;
  double rate = x.leak_rate_per_s;
  // tau = 0 exchanges instantly: the temperature is then algebraic (isothermal), not a state that relaxes.
  if (g.process == GasProcess::heat_transfer && g.heat_transfer_time_constant_s > 0.0) {
    rate = std::max(rate, 1.0 / g.heat_transfer_time_constant_s);
  }
  // With no strength the viscous stresses start at zero and stay there.
  if (x.viscoelastic_strength > 0.0) rate = std::max(rate, 1.0 / x.viscoelastic_time_constant_s);
  return rate;
}

inline double MuscleModel::stretch_per_newton() const {
  return params_.extensions.fiber_compliance_per_N * geometry_.fiber_length() / geometry_.build().fiber_count;
}

template <class AbsoluteOfVolume>
inline double MuscleModel::fiber_tension_at(double length_m, double fiber_length_m,
                                            const AbsoluteOfVolume& absolute_of_volume, const BiaxialStress& viscous,
                                            ShapeHint& hint) const {
  const MuscleShape shape = geometry_.shape_from(hint, length_m, fiber_length_m, ShapeParts::kinematics);
  const double gauge = absolute_of_volume(shape.gas_volume + dead_volume_) - params_.gas.atmospheric_pressure_Pa;
  return total_fiber_tension(geometry_, shape, geometry_.fiber_length_derivatives(shape, fiber_length_m),
                             params_.bladder, gauge, viscous);
}

template <class AbsoluteOfVolume>
inline double MuscleModel::balanced_fiber_length(double length_m, const AbsoluteOfVolume& absolute_of_volume,
                                                 const BiaxialStress& viscous, MuscleWorkspace& workspace) const {
  // Each fiber stretches by T b / EA, T the tension that their length's virtual work gives, so
  // their length b' solves r(b') = b' - b - s max(N T(b'), 0) = 0 with s = b / (N EA). The gas
  // follows the volume, which grows with b', so the pressure and the tension fall as the fibers
  // stretch: r' = 1 - s d(N T)/db' > 0. The integrator moves L and the state a little between
  // calls, so the last solve's length and slope start a chord Newton iteration that converges
  // in two or three tension evaluations (a bracketing search takes ten).
  const double rest = geometry_.fiber_length();
  const double longest = geometry_.longest_fiber_length(length_m) * (1.0 - 1e-12);
  const double s = stretch_per_newton();
  ShapeHint& hint = workspace.shape;
  const auto residual = [&](double fiber) {
    return fiber - rest - s * std::max(fiber_tension_at(length_m, fiber, absolute_of_volume, viscous, hint), 0.0);
  };
  double fiber = workspace.fiber_length_m;
  bool converged = false;
  if (std::isfinite(fiber) && std::isfinite(workspace.fiber_balance_slope) && workspace.fiber_balance_slope > 0.0) {
    for (int iteration = 0; iteration < 12 && !converged; ++iteration) {
      if (!(fiber >= rest && fiber < longest)) break;
      const double step = residual(fiber) / workspace.fiber_balance_slope;
      fiber -= step;
      converged = std::abs(step) <= 4.0 * std::numeric_limits<double>::epsilon() * rest;
    }
    // A step that lands a rounding below the rest length: the fibers are just slack there.
    if (converged && fiber < rest) fiber = rest;
  }
  if (!converged || !(fiber >= rest && fiber < longest)) {
    fiber = bracketed_fiber_length(length_m, absolute_of_volume, viscous, hint);
  }
  workspace.fiber_length_m = fiber;
  return fiber;
}

template <class AbsoluteOfVolume>
inline double MuscleModel::bracketed_fiber_length(double length_m, const AbsoluteOfVolume& absolute_of_volume,
                                                  const BiaxialStress& viscous, ShapeHint& hint) const {
  const double rest = geometry_.fiber_length();
  const double longest = geometry_.longest_fiber_length(length_m) * (1.0 - 1e-12);
  const double s = stretch_per_newton();
  const auto tension = [&](double fiber) {
    return fiber_tension_at(length_m, fiber, absolute_of_volume, viscous, hint);
  };
  const double at_rest = tension(rest);
  if (!(at_rest > 0.0)) return rest;  // slack fibers keep their length
  // Fibers so stiff that their stretch is below the resolution of their length: the tension
  // at rest is theirs (a bracket of no width would never widen).
  const double stretch = s * at_rest;
  if (stretch <= 4.0 * std::numeric_limits<double>::epsilon() * rest) return rest + stretch;
  const auto residual = [&](double fiber) { return fiber - rest - s * std::max(tension(fiber), 0.0); };
  // r(b) < 0; r(b + s N T(b)) >= 0 where the tension falls as the fibers stretch, as it does
  // wherever the balance is stable; else the bracket widens towards the braid's longest fibers.
  double upper = std::min(rest + stretch, longest);
  while (residual(upper) < 0.0 && upper < longest) upper = std::min(rest + 2.0 * (upper - rest), longest);
  if (residual(upper) < 0.0) {
    PAMKIT_THROW(
        InvalidInput(detail::message("fiber compliance: no fiber length between ", rest, " and ", upper,
                                     " m balances the fibers' tension at the muscle length ", length_m, " m")));
  }
  std::uintmax_t iterations = 100;
  const auto root = boost::math::tools::toms748_solve(residual, rest, upper,
                                                      boost::math::tools::eps_tolerance<double>(50), iterations);
  return 0.5 * (root.first + root.second);
}

inline MuscleOutputs MuscleModel::evaluate(double length_m, double velocity_m_per_s, const State& y) const {
  MuscleWorkspace cold;
  return evaluate_with(cold, length_m, velocity_m_per_s, y, ShapeParts::all);
}

inline MuscleOutputs MuscleModel::evaluate_with(MuscleWorkspace& workspace, double length_m, double velocity_m_per_s,
                                                const State& y, ShapeParts parts) const {
  MuscleOutputs out{};
  out.fiber_length_m = geometry_.fiber_length();
  if (!(params_.extensions.fiber_compliance_per_N > 0.0)) {
    out.shape = geometry_.shape_from(workspace.shape, length_m, parts);
    out.fiber_tension_N = std::numeric_limits<double>::quiet_NaN();
    complete_outputs(out, velocity_m_per_s, y, nullptr);
    return out;
  }
  const GasParams& g = params_.gas;
  const double gas_energy = y[State::gas_mass_kg] * g.gas_constant_J_per_kgK * y[State::temperature_K];
  const auto sealed = [gas_energy](double volume) { return gas_energy / volume; };  // eq. 3.1.17
  const BiaxialStress viscous{y[State::viscous_stress_l_Pa], y[State::viscous_stress_h_Pa]};
  const double fiber = balanced_fiber_length(length_m, sealed, viscous, workspace);
  out.fiber_length_m = fiber;
  out.shape = geometry_.shape_from(workspace.shape, length_m, fiber, parts);
  detail::FiberBalance balance{};
  balance.shape = geometry_.fiber_length_derivatives(out.shape, fiber);
  const double volume = out.shape.gas_volume + dead_volume_;
  const double gauge = sealed(volume) - g.atmospheric_pressure_Pa;
  balance.tension_N = total_fiber_tension(geometry_, out.shape, balance.shape, params_.bladder, gauge, viscous);
  // The tension's slopes at this gas pressure: the rates need them, and the next solve's chord
  // is 1 - s dN T/db' with the pressure following the volume, dp/db' = -(p / V) dV/db'.
  const FiberTensionSlopes slopes =
      total_fiber_tension_slopes(geometry_, out.shape, balance.shape, params_.bladder, gauge, viscous);
  balance.d_tension_d_length = slopes.d_length;
  balance.d_tension_d_fiber = slopes.d_fiber;
  const double d_pressure_d_fiber = -(gauge + g.atmospheric_pressure_Pa) / volume * balance.shape.d_gas_volume;
  workspace.fiber_balance_slope =
      balance.tension_N > 0.0
          ? 1.0 - stretch_per_newton() * (balance.d_tension_d_fiber + d_pressure_d_fiber * balance.shape.d_gas_volume)
          : 1.0;
  out.fiber_tension_N = balance.tension_N / geometry_.build().fiber_count;
  complete_outputs(out, velocity_m_per_s, y, &balance);
  return out;
}

inline MuscleOutputs MuscleModel::evaluate_at_shape(const MuscleShape& shape, double velocity_m_per_s,
                                                    const State& y) const {
  if (params_.extensions.fiber_compliance_per_N > 0.0) {
    PAMKIT_THROW(InvalidInput(detail::message(
        "MuscleModel.evaluate_at_shape: fiber_compliance_per_N = ", params_.extensions.fiber_compliance_per_N,
        " 1/N makes the fibers' length depend on their tension, so on the gas; a shape solved "
        "beforehand needs inextensible fibers")));
  }
  MuscleOutputs out{};
  out.fiber_length_m = geometry_.fiber_length();
  out.fiber_tension_N = std::numeric_limits<double>::quiet_NaN();
  out.shape = shape;
  complete_outputs(out, velocity_m_per_s, y, nullptr);
  return out;
}

inline void MuscleModel::complete_outputs(MuscleOutputs& out, double velocity_m_per_s, const State& y,
                                          const detail::FiberBalance* fibers) const {
  const GasParams& g = params_.gas;
  const ModelExtensions& x = params_.extensions;
  const double temperature = y[State::temperature_K];
  const double mass = y[State::gas_mass_kg];
  const double R = g.gas_constant_J_per_kgK;
  const double cv = g.specific_heat_cv();
  const double volume = out.shape.gas_volume + dead_volume_;
  out.gas_volume_m3 = volume;
  out.absolute_pressure_Pa = mass * R * temperature / volume;  // eq. 3.1.17
  out.gauge_pressure_Pa = out.absolute_pressure_Pa - g.atmospheric_pressure_Pa;

  // A small orifice: the excess mass escapes at a fixed rate, so at fixed volume and
  // temperature the gauge pressure decays as exp(-rate t).
  const double mass_rate = -x.leak_rate_per_s * out.gauge_pressure_Pa * volume / (R * temperature);
  State& rate = out.rate;
  rate[State::gas_mass_kg] = mass_rate;
  // Energy of the gas: m cv dT/dt = dQ_in/dt - p dV/dt + R T dm/dt (escaping gas carries its
  // enthalpy cp T out, which costs the rest R T per unit mass).
  const bool exchanges_instantly = g.process == GasProcess::heat_transfer && g.heat_transfer_time_constant_s == 0.0;
  const bool polytropic = g.process == GasProcess::polytropic || exchanges_instantly;
  const double n = exchanges_instantly ? 1.0 : g.polytropic_index;
  if (!polytropic)
    out.heat_loss_rate_W = mass * cv * (temperature - g.ambient_temperature_K) / g.heat_transfer_time_constant_s;
  const auto temperature_rate = [&](double volume_rate) {
    // T rho^(1-n) = const (eq. 3.1.18 for the gas that stays inside).
    if (polytropic) return -(n - 1.0) * temperature * (volume_rate / volume - mass_rate / mass);
    return (-out.absolute_pressure_Pa * volume_rate - out.heat_loss_rate_W + R * temperature * mass_rate) / (mass * cv);
  };

  const BladderState b = bladder_state(geometry_, out.shape, params_.bladder);
  const double relaxation = 1.0 / x.viscoelastic_time_constant_s;
  const BiaxialStress modulus = params_.bladder.tangent_moduli(b.longitudinal_strain, b.hoop_strain);
  // Compliant fibers: their length's rate keeps their balance N EA (b' - b) / b = N T. N T moves
  // with the length and the fiber length at fixed gas pressure and viscous stresses (its partial
  // slopes), with the gas pressure, whose rate is affine in the volume's, and with the viscous
  // stresses, whose rates are affine in the strains'. Both of those rates are affine in the
  // fiber length's, so one linear equation gives it.
  out.fiber_length_rate_m_per_s = 0.0;
  if (fibers != nullptr && fibers->tension_N > 0.0) {
    const FiberLengthDerivatives& f = fibers->shape;
    const double rubber = rubber_volume_;
    const double lm0 = geometry_.deflated_cylinder_length();
    const double db0 = geometry_.build().bladder_diameter_m;
    const double dl_dfiber = f.d_cylinder_length / lm0;  // d eps_l / db'
    const double dh_dfiber = f.d_diameter / db0;         // d eps_h / db'
    // dp/dt = p (dm/dt / m + dT/dt / T - dV/dt / V) = p_rest + p_per_volume dV/dt.
    const double p = out.absolute_pressure_Pa;
    const double temperature_rest = temperature_rate(0.0);
    const double temperature_per_volume = temperature_rate(1.0) - temperature_rest;
    const double p_rest = p * (mass_rate / mass + temperature_rest / temperature);
    const double p_per_volume = p * (temperature_per_volume / temperature - 1.0 / volume);
    const double k = x.viscoelastic_strength;
    const double stiffness = 1.0 / stretch_per_newton();  // N EA / b
    const double coefficient =
        stiffness - fibers->d_tension_d_fiber - p_per_volume * f.d_gas_volume * f.d_gas_volume +
        rubber * k * (modulus.longitudinal * dl_dfiber * dl_dfiber + modulus.hoop * dh_dfiber * dh_dfiber);
    const double driven = fibers->d_tension_d_length * velocity_m_per_s +
                          f.d_gas_volume * (p_rest + p_per_volume * out.shape.d_gas_volume * velocity_m_per_s) -
                          rubber * (dl_dfiber * (k * modulus.longitudinal * b.d_longitudinal_strain * velocity_m_per_s -
                                                 relaxation * y[State::viscous_stress_l_Pa]) +
                                    dh_dfiber * (k * modulus.hoop * b.d_hoop_strain * velocity_m_per_s -
                                                 relaxation * y[State::viscous_stress_h_Pa]));
    out.fiber_length_rate_m_per_s = driven / coefficient;
  }
  const double fiber_rate = out.fiber_length_rate_m_per_s;

  double volume_rate = out.shape.d_gas_volume * velocity_m_per_s;
  if (fibers != nullptr) volume_rate += fibers->shape.d_gas_volume * fiber_rate;
  rate[State::temperature_K] = temperature_rate(volume_rate);
  if (polytropic) {
    out.heat_loss_rate_W = -(mass * cv * rate[State::temperature_K] + out.absolute_pressure_Pa * volume_rate -
                             R * temperature * mass_rate);
  }

  out.forces = muscle_forces(geometry_, out.shape, params_.bladder, params_.friction, out.absolute_pressure_Pa,
                             g.atmospheric_pressure_Pa, velocity_m_per_s);
  // The bladder's Maxwell branch: its stress follows the tangent modulus times the strain rate
  // and relaxes with its time constant; it acts through the same strains as the elastic law.
  const double viscous = rubber_volume_ * (y[State::viscous_stress_l_Pa] * b.d_longitudinal_strain +
                                           y[State::viscous_stress_h_Pa] * b.d_hoop_strain);
  out.forces.bladder += viscous;
  out.forces.total = braid_tension(out.forces.total + viscous, detail::slack_band_N(params_));
  double driven_l = x.viscoelastic_strength * modulus.longitudinal * b.d_longitudinal_strain * velocity_m_per_s;
  double driven_h = x.viscoelastic_strength * modulus.hoop * b.d_hoop_strain * velocity_m_per_s;
  if (fibers != nullptr) {
    driven_l += x.viscoelastic_strength * modulus.longitudinal *
                (fibers->shape.d_cylinder_length / geometry_.deflated_cylinder_length()) * fiber_rate;
    driven_h += x.viscoelastic_strength * modulus.hoop *
                (fibers->shape.d_diameter / geometry_.build().bladder_diameter_m) * fiber_rate;
  }
  rate[State::viscous_stress_l_Pa] = driven_l - relaxation * y[State::viscous_stress_l_Pa];
  rate[State::viscous_stress_h_Pa] = driven_h - relaxation * y[State::viscous_stress_h_Pa];

  rate[State::work_J] = out.forces.total * velocity_m_per_s;
  rate[State::heat_lost_J] = out.heat_loss_rate_W;
  rate[State::friction_dissipated_J] = out.forces.friction * velocity_m_per_s;
}

}  // namespace pamkit
