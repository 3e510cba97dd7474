#pragma once

#include <algorithm>
#include <cstdint>

#include <boost/math/tools/roots.hpp>

namespace pamkit {

inline MuscleModel::MuscleModel(const MuscleParams& params, const InitialState& initial)
    : params_(params), initial_(initial), geometry_((params.validate(), params.build)) {
  initial_.validate();
  const MuscleShape s = geometry_.shape(initial_.length_m);
  dead_volume_ = params_.extensions.dead_volume_fraction * s.gas_volume;
  initial_gas_volume_ = s.gas_volume + dead_volume_;
  const GasParams& g = params_.gas;
  gas_mass_ = (g.atmospheric_pressure_Pa + initial_.gauge_pressure_Pa) * initial_gas_volume_ /
              (g.gas_constant_J_per_kgK * g.ambient_temperature_K);
  rubber_volume_ = bladder_reference_volume(geometry_);
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

inline double MuscleModel::elastic_force(double braid_length, const State& y, ShapeHint& hint) const {
  const GasParams& g = params_.gas;
  const MuscleShape shape = geometry_.shape_from(hint, braid_length, ShapeParts::kinematics);
  const double pressure =
      y[State::gas_mass_kg] * g.gas_constant_J_per_kgK * y[State::temperature_K] / (shape.gas_volume + dead_volume_);
  const FrictionParams no_friction{0.0, 0.0, 0.0, 0.0, 0.0};
  const MuscleForces f =
      muscle_forces(geometry_, shape, params_.bladder, no_friction, pressure, g.atmospheric_pressure_Pa, 0.0);
  const BladderState b = bladder_state(geometry_, shape, params_.bladder);
  return braid_tension(f.total + rubber_volume_ * (y[State::viscous_stress_l_Pa] * b.d_longitudinal_strain +
                                                   y[State::viscous_stress_h_Pa] * b.d_hoop_strain),
                       detail::slack_band_N(params_));
}

inline double MuscleModel::elastic_slope(double braid_length, const State& y, ShapeHint& hint) const {
  const double h = 1e-7;  // well above rounding, well below the braid's length scales
  return (elastic_force(braid_length + h, y, hint) - elastic_force(braid_length - h, y, hint)) / (2.0 * h);
}

inline double MuscleModel::braid_length(double length_m, const State& y, MuscleWorkspace& workspace) const {
  // The fibers stretch by T Lym / EA; their tension sums to the force, so the braid is shorter
  // than the muscle by F Lym / (N EA): a spring in series with the braid. Its length solves
  // g(L_b) = L_b + c F(L_b) - L = 0, g' = 1 + c dF/dL_b > 0. The integrator and the samples
  // move L a little between calls, so the last solve's stretch and slope start a chord Newton
  // iteration that converges in two or three force evaluations (a bracketing search took ten).
  const double per_newton =
      params_.extensions.fiber_compliance_per_N * geometry_.fiber_length() / geometry_.build().fiber_count;
  const double shortest = geometry_.min_length() * (1.0 + 1e-12);
  const double longest = geometry_.max_length() * (1.0 - 1e-12);
  ShapeHint& hint = workspace.shape;
  double braid = length_m;
  if (std::isfinite(workspace.fiber_stretch_m) && std::isfinite(workspace.force_slope_N_per_m)) {
    braid = length_m - workspace.fiber_stretch_m;
    const double chord = 1.0 + per_newton * workspace.force_slope_N_per_m;
    bool converged = false;
    for (int iteration = 0; iteration < 12 && !converged && chord > 0.0; ++iteration) {
      if (!(braid > shortest && braid < longest)) break;
      const double step = (braid + per_newton * elastic_force(braid, y, hint) - length_m) / chord;
      braid -= step;
      converged = std::abs(step) <= 4.0 * std::numeric_limits<double>::epsilon() * length_m;
    }
    if (!converged || !(braid > shortest && braid < longest)) braid = bracketed_braid_length(length_m, y, hint);
  } else {
    braid = bracketed_braid_length(length_m, y, hint);
  }
  workspace.fiber_stretch_m = length_m - braid;
  workspace.force_slope_N_per_m = elastic_slope(braid, y, hint);
  return braid;
}

inline double MuscleModel::bracketed_braid_length(double length_m, const State& y, ShapeHint& hint) const {
  const double per_newton =
      params_.extensions.fiber_compliance_per_N * geometry_.fiber_length() / geometry_.build().fiber_count;
  auto mismatch = [&](double braid) { return braid + per_newton * elastic_force(braid, y, hint) - length_m; };
  const double stretch = per_newton * elastic_force(length_m, y, hint);
  if (std::abs(stretch) <= 1e-14 * length_m) return length_m;  // unloaded: nothing to solve
  // The force rises with the braid length, so the root lies between L - stretch(L) and L.
  const double margin = 1e-12;
  const double lower = std::max(std::min(length_m, length_m - stretch), geometry_.min_length() * (1.0 + margin));
  const double upper = std::min(std::max(length_m, length_m - stretch), geometry_.max_length() * (1.0 - margin));
  if (mismatch(lower) > 0.0 || mismatch(upper) < 0.0) {
    PAMKIT_THROW(InvalidInput(detail::message("fiber compliance: no braid length between ", lower, " and ", upper,
                                              " m spans the muscle length ", length_m, " m")));
  }
  std::uintmax_t iterations = 100;
  const auto root = boost::math::tools::toms748_solve(mismatch, lower, upper,
                                                      boost::math::tools::eps_tolerance<double>(48), iterations);
  return 0.5 * (root.first + root.second);
}

inline MuscleOutputs MuscleModel::evaluate(double length_m, double velocity_m_per_s, const State& y) const {
  MuscleWorkspace cold;
  return evaluate_with(cold, length_m, velocity_m_per_s, y, ShapeParts::all);
}

inline MuscleOutputs MuscleModel::evaluate_with(MuscleWorkspace& workspace, double length_m, double velocity_m_per_s,
                                                const State& y, ShapeParts parts) const {
  const ModelExtensions& x = params_.extensions;
  MuscleOutputs out{};
  out.braid_length_m = length_m;
  out.braid_velocity_m_per_s = velocity_m_per_s;
  if (x.fiber_compliance_per_N > 0.0) {
    out.braid_length_m = braid_length(length_m, y, workspace);
    // dL/dL_b = 1 + c dF/dL_b, the slope at the solution (braid_length leaves it).
    const double per_newton = x.fiber_compliance_per_N * geometry_.fiber_length() / geometry_.build().fiber_count;
    out.braid_velocity_m_per_s = velocity_m_per_s / (1.0 + per_newton * workspace.force_slope_N_per_m);
  }
  out.shape = geometry_.shape_from(workspace.shape, out.braid_length_m, parts);
  complete_outputs(out, velocity_m_per_s, y);
  return out;
}

inline MuscleOutputs MuscleModel::evaluate_at_shape(const MuscleShape& shape, double velocity_m_per_s,
                                                    const State& y) const {
  if (params_.extensions.fiber_compliance_per_N > 0.0) {
    PAMKIT_THROW(InvalidInput(detail::message(
        "MuscleModel.evaluate_at_shape: fiber_compliance_per_N = ", params_.extensions.fiber_compliance_per_N,
        " 1/N makes the braid's length depend on the force; a shape solved "
        "beforehand needs inextensible fibers")));
  }
  MuscleOutputs out{};
  out.braid_length_m = shape.length;
  out.braid_velocity_m_per_s = velocity_m_per_s;
  out.shape = shape;
  complete_outputs(out, velocity_m_per_s, y);
  return out;
}

inline void MuscleModel::complete_outputs(MuscleOutputs& out, double velocity_m_per_s, const State& y) const {
  const GasParams& g = params_.gas;
  const ModelExtensions& x = params_.extensions;
  const double temperature = y[State::temperature_K];
  const double mass = y[State::gas_mass_kg];
  const double R = g.gas_constant_J_per_kgK;
  const double cv = g.specific_heat_cv();
  const double volume = out.shape.gas_volume + dead_volume_;
  const double volume_rate = out.shape.d_gas_volume * out.braid_velocity_m_per_s;
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
  if (g.process == GasProcess::polytropic || exchanges_instantly) {
    const double n = exchanges_instantly ? 1.0 : g.polytropic_index;
    // T rho^(1-n) = const (eq. 3.1.18 for the gas that stays inside).
    rate[State::temperature_K] = -(n - 1.0) * temperature * (volume_rate / volume - mass_rate / mass);
    out.heat_loss_rate_W = -(mass * cv * rate[State::temperature_K] + out.absolute_pressure_Pa * volume_rate -
                             R * temperature * mass_rate);
  } else {
    out.heat_loss_rate_W = mass * cv * (temperature - g.ambient_temperature_K) / g.heat_transfer_time_constant_s;
    rate[State::temperature_K] =
        (-out.absolute_pressure_Pa * volume_rate - out.heat_loss_rate_W + R * temperature * mass_rate) / (mass * cv);
  }

  out.forces = muscle_forces(geometry_, out.shape, params_.bladder, params_.friction, out.absolute_pressure_Pa,
                             g.atmospheric_pressure_Pa, out.braid_velocity_m_per_s);
  // The bladder's Maxwell branch: its stress follows the tangent modulus times the strain rate
  // and relaxes with its time constant; it acts through the same strains as the elastic law.
  const BladderState b = bladder_state(geometry_, out.shape, params_.bladder);
  const double viscous = rubber_volume_ * (y[State::viscous_stress_l_Pa] * b.d_longitudinal_strain +
                                           y[State::viscous_stress_h_Pa] * b.d_hoop_strain);
  out.forces.bladder += viscous;
  out.forces.total = braid_tension(out.forces.total + viscous, detail::slack_band_N(params_));
  const double relaxation = 1.0 / x.viscoelastic_time_constant_s;
  const BiaxialStress modulus = params_.bladder.tangent_moduli(b.longitudinal_strain, b.hoop_strain);
  rate[State::viscous_stress_l_Pa] =
      x.viscoelastic_strength * modulus.longitudinal * b.d_longitudinal_strain * out.braid_velocity_m_per_s -
      relaxation * y[State::viscous_stress_l_Pa];
  rate[State::viscous_stress_h_Pa] =
      x.viscoelastic_strength * modulus.hoop * b.d_hoop_strain * out.braid_velocity_m_per_s -
      relaxation * y[State::viscous_stress_h_Pa];

  rate[State::work_J] = out.forces.total * velocity_m_per_s;
  rate[State::heat_lost_J] = out.heat_loss_rate_W;
  rate[State::friction_dissipated_J] = out.forces.friction * out.braid_velocity_m_per_s;
}

}  // namespace pamkit
