#pragma once
/// \file
/// The effect catalog of DESIGN.md: nine named model extensions, each with physical
/// parameters, their realistic ranges, and what gives them away in the data.

#include <algorithm>
#include <cmath>
#include <limits>

#include "pamkit/effects/effect.hpp"

namespace pamkit {

namespace detail {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

/// Parses a number for effect `effect`, parameter `key`.
inline double parse_number(const std::string& effect, const std::string& key, const std::string& text) {
  std::size_t used = 0;
  double value = 0.0;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != text.size()) {
    throw InvalidParameter(message("effect ", effect, ": ", key, " = '", text, "' is not a number"));
  }
  return value;
}

/// Common parts of the built-in effects: numeric parameters declared once in a struct whose
/// `for_each_field` visits (name, member, FieldInfo, realistic min, realistic max), and an
/// optional measured channel.
template <class Params>
class ParametricEffect : public Effect {
 public:
  std::string name() const override { return Params::kName; }
  std::string description() const override { return Params::kDescription; }

  std::vector<EffectParameter> parameters() const override {
    std::vector<EffectParameter> out;
    Params::for_each_field([&](const char* key, double Params::*member, const FieldInfo& info, double lo, double hi) {
      out.push_back({key, params_.*member, info.unit, info.min, info.max, lo, hi, info.description});
    });
    return out;
  }

  std::map<std::string, std::string> options() const override {
    if constexpr (Params::kHasChannel) return {{"channel", params_.channel}};
    return {};
  }

  void set(const std::string& key, const std::string& value) override {
    if constexpr (Params::kHasChannel) {
      if (key == "channel") {
        const auto& names = measured_channels();
        if (std::find(names.begin(), names.end(), value) == names.end()) {
          throw InvalidParameter(message("effect ", Params::kName, ": channel = '", value,
                                         "' is not one of force_N, pressure_kPa, temperature_C"));
        }
        params_.channel = value;
        return;
      }
    }
    bool found = false;
    Params::for_each_field([&](const char* field, double Params::*member, const FieldInfo& info, double, double) {
      if (key != field) return;
      const double number = parse_number(Params::kName, key, value);
      check_range(Params::kName, field, number, info);
      params_.*member = number;
      found = true;
    });
    if (!found) {
      std::string known = Params::kHasChannel ? "channel" : "";
      Params::for_each_field([&](const char* field, double Params::*, const FieldInfo&, double, double) {
        known += (known.empty() ? "" : ", ") + std::string(field);
      });
      throw InvalidParameter(message("effect ", Params::kName, " has no parameter '", key, "' (", known, ")"));
    }
  }

  const Params& params() const { return params_; }

 protected:
  Params params_;
};

inline bool sealed_only(const char* effect, GasMode mode, std::string* why_not) {
  if (mode == GasMode::sealed) return true;
  if (why_not) {
    *why_not = message(effect, " acts on the sealed gas; in a supplied test the pressure is measured, not predicted");
  }
  return false;
}

inline bool dynamic_only(const char* effect, GasMode mode, std::string* why_not) {
  if (mode == GasMode::sealed) return true;
  if (why_not) {
    *why_not = message(effect, " needs the dynamic muscle model, which pamkit runs for sealed tests only; a supplied "
                               "test is evaluated statically at the measured pressure");
  }
  return false;
}

}  // namespace detail

/// heat_transfer: the gas exchanges heat with the wall at a finite rate (time constant tau)
/// instead of following a fixed polytropic exponent. tau = 0 is instantaneous exchange, the
/// isothermal baseline.
struct HeatTransferParams {
  static constexpr const char* kName = "heat_transfer";
  static constexpr const char* kDescription =
      "finite-rate heat exchange between gas and wall, in place of a fixed polytropic exponent. Gives it away: "
      "pressure hysteresis that grows with rate while a cycle is slower than tau (and shrinks toward adiabatic "
      "beyond), pressure that relaxes during holds, temperature swings far below the polytropic ones.";
  static constexpr bool kHasChannel = false;
  double time_constant_s = 2.0;  ///< gas-wall exchange time constant [s]
  template <class V>
  static void for_each_field(V&& visit) {
    visit("time_constant_s", &HeatTransferParams::time_constant_s, FieldInfo{"s", 0.0, 1e9, "gas-wall heat exchange time constant"}, 0.5, 10.0);
  }
};
class HeatTransferEffect : public detail::ParametricEffect<HeatTransferParams> {
 public:
  bool acts_in(GasMode mode, std::string* why_not) const override { return detail::sealed_only(HeatTransferParams::kName, mode, why_not); }
  void apply_to_params(MuscleParams& p) const override {
    p.gas.process = GasProcess::heat_transfer;
    p.gas.heat_transfer_time_constant_s = params_.time_constant_s;
  }
};

/// dead_volume: gas outside the muscle (hose, transducer) whose volume does not change.
struct DeadVolumeParams {
  static constexpr const char* kName = "dead_volume";
  static constexpr const char* kDescription =
      "gas volume outside the muscle that does not change with stretch (hose and transducer: about 5 % in the "
      "thesis, appendix B). Gives it away: the pressure swing is scaled down evenly, at every rate.";
  static constexpr bool kHasChannel = false;
  double volume_fraction = 0.05;  ///< dead volume over the muscle's initial gas volume [1]
  template <class V>
  static void for_each_field(V&& visit) {
    visit("volume_fraction", &DeadVolumeParams::volume_fraction, FieldInfo{"1", 0.0, 10.0, "dead volume / initial gas volume"}, 0.03, 0.3);
  }
};
class DeadVolumeEffect : public detail::ParametricEffect<DeadVolumeParams> {
 public:
  bool acts_in(GasMode mode, std::string* why_not) const override { return detail::sealed_only(DeadVolumeParams::kName, mode, why_not); }
  void apply_to_params(MuscleParams& p) const override { p.extensions.dead_volume_fraction = params_.volume_fraction; }
};

/// leak: gas escapes through an orifice; the gauge pressure decays with tau at fixed volume.
struct LeakParams {
  static constexpr const char* kName = "leak";
  static constexpr const char* kDescription =
      "gas escaping through an orifice (a seal, the sensor's wires): the gauge pressure decays with a time constant. "
      "Gives it away: pressure and force peaks drift down cycle after cycle.";
  static constexpr bool kHasChannel = false;
  double time_constant_s = 1000.0;  ///< decay time of the gauge pressure at fixed volume [s]; inf: sealed
  template <class V>
  static void for_each_field(V&& visit) {
    visit("time_constant_s", &LeakParams::time_constant_s, FieldInfo{"s", 1e-3, detail::kInfinity, "leak time constant (inf: none)"}, 100.0, 3000.0);
  }
};
class LeakEffect : public detail::ParametricEffect<LeakParams> {
 public:
  bool acts_in(GasMode mode, std::string* why_not) const override { return detail::sealed_only(LeakParams::kName, mode, why_not); }
  void apply_to_params(MuscleParams& p) const override { p.extensions.leak_rate_per_s = 1.0 / params_.time_constant_s; }
};

/// bladder_viscoelasticity: a Maxwell branch beside the bladder's elastic law.
struct BladderViscoelasticityParams {
  static constexpr const char* kName = "bladder_viscoelasticity";
  static constexpr const char* kDescription =
      "rate-dependent bladder stress: a Maxwell branch (modulus = strength x the law's tangent modulus, relaxation "
      "time tau) beside the elastic law of eqs. 3.1.12-13; the thesis's biaxial tests showed the hysteresis "
      "(figure 3.5). Gives it away: force hysteresis that grows with rate while a cycle is slower than tau, "
      "strongest at low pressure, with no matching pressure hysteresis.";
  static constexpr bool kHasChannel = false;
  double time_constant_s = 2.0;  ///< relaxation time of the Maxwell branch [s]
  double strength = 0.5;         ///< branch modulus over the tangent modulus [1]
  template <class V>
  static void for_each_field(V&& visit) {
    visit("time_constant_s", &BladderViscoelasticityParams::time_constant_s, FieldInfo{"s", 1e-4, 1e6, "relaxation time"}, 0.5, 20.0);
    visit("strength", &BladderViscoelasticityParams::strength, FieldInfo{"1", 0.0, 100.0, "branch modulus / tangent modulus"}, 0.3, 3.0);
  }
};
class BladderViscoelasticityEffect : public detail::ParametricEffect<BladderViscoelasticityParams> {
 public:
  bool acts_in(GasMode mode, std::string* why_not) const override {
    return detail::dynamic_only(BladderViscoelasticityParams::kName, mode, why_not);
  }
  void apply_to_params(MuscleParams& p) const override {
    p.extensions.viscoelastic_strength = params_.strength;
    p.extensions.viscoelastic_time_constant_s = params_.time_constant_s;
  }
};

/// fiber_compliance: the braid's fibers stretch under tension, a spring in series.
struct FiberComplianceParams {
  static constexpr const char* kName = "fiber_compliance";
  static constexpr const char* kDescription =
      "braid fibers that stretch under tension (axial stiffness EA of one fiber): a spring in series with the "
      "braid. Gives it away: the force-elongation curve softens at high force; the pressure peaks less than the "
      "crosshead's travel implies.";
  static constexpr bool kHasChannel = false;
  double stiffness_N = 300.0;  ///< axial stiffness EA of one fiber [N]; inf: inextensible
  template <class V>
  static void for_each_field(V&& visit) {
    visit("stiffness_N", &FiberComplianceParams::stiffness_N, FieldInfo{"N", 1.0, detail::kInfinity, "fiber axial stiffness EA (inf: rigid)"}, 100.0, 600.0);
  }
};
class FiberComplianceEffect : public detail::ParametricEffect<FiberComplianceParams> {
 public:
  bool acts_in(GasMode mode, std::string* why_not) const override { return detail::dynamic_only(FiberComplianceParams::kName, mode, why_not); }
  void apply_to_params(MuscleParams& p) const override { p.extensions.fiber_compliance_per_N = 1.0 / params_.stiffness_N; }
};

/// fixture_slack: play between crosshead and muscle (loose pins).
struct FixtureSlackParams {
  static constexpr const char* kName = "fixture_slack";
  static constexpr const char* kDescription =
      "slack between crosshead and muscle (pins in loose holes): the muscle moves only once the crosshead has "
      "taken up the play, at each reversal. Gives it away: force stays flat at the start of each stretch and "
      "each return; the force-elongation loop is shifted and widened by the slack.";
  static constexpr bool kHasChannel = false;
  double slack_m = 1e-3;  ///< total play [m]
  template <class V>
  static void for_each_field(V&& visit) {
    visit("slack_m", &FixtureSlackParams::slack_m, FieldInfo{"m", 0.0, 0.05, "play between crosshead and muscle"}, 0.5e-3, 3e-3);
  }
};
class FixtureSlackEffect : public detail::ParametricEffect<FixtureSlackParams> {
 public:
  /// A play (backlash) operator: the muscle stays put until the crosshead pushes it from
  /// either end of a band `slack_m` wide; it starts at the band's upper end.
  std::vector<double> apply_to_elongation(const std::vector<double>&, const std::vector<double>& crosshead) const override {
    std::vector<double> muscle(crosshead.size());
    double position = crosshead.empty() ? 0.0 : crosshead.front();
    for (std::size_t k = 0; k < crosshead.size(); ++k) {
      position = std::clamp(position, crosshead[k] - params_.slack_m, crosshead[k]);
      muscle[k] = position;
    }
    return muscle;
  }
};

/// sensor_lag: a first-order lag on one measured channel.
struct SensorLagParams {
  static constexpr const char* kName = "sensor_lag";
  static constexpr const char* kDescription =
      "first-order lag of one channel (a TMP36 in still air is slow; a long hose slows a pressure transducer). "
      "Gives it away: that channel lags its prediction and its swings are attenuated, more so at higher rates.";
  static constexpr bool kHasChannel = true;
  std::string channel = "temperature_C";
  double time_constant_s = 5.0;  ///< time constant of the lag [s]; 0: none
  template <class V>
  static void for_each_field(V&& visit) {
    visit("time_constant_s", &SensorLagParams::time_constant_s, FieldInfo{"s", 0.0, 1e4, "sensor time constant"}, 0.5, 20.0);
  }
};
class SensorLagEffect : public detail::ParametricEffect<SensorLagParams> {
 public:
  /// Exact solution of tau dy/dt = x - y for x linear between samples, starting settled.
  void apply_to_measurement(Measurement& m) const override {
    const double tau = params_.time_constant_s;
    if (tau == 0.0) return;
    std::vector<double>& x = m.channel(params_.channel);
    if (x.empty()) return;
    double y = x.front();
    double previous = x.front();  // the true value at the last sample (x is overwritten)
    for (std::size_t k = 1; k < x.size(); ++k) {
      const double decay = std::exp(-(m.time_s[k] - m.time_s[k - 1]) / tau);
      const double slope = (x[k] - previous) / (m.time_s[k] - m.time_s[k - 1]);
      y = x[k] - slope * tau + (y - previous + slope * tau) * decay;
      previous = x[k];
      x[k] = y;
    }
  }
};

/// time_skew: a channel's clock runs behind (or ahead of) the tensile machine's.
struct TimeSkewParams {
  static constexpr const char* kName = "time_skew";
  static constexpr const char* kDescription =
      "constant time offset between channels logged by different instruments (the Arduino's pressure and "
      "temperature against the tensile machine's force), left after a synchronisation by hand. Gives it away: "
      "the cross-correlation of that channel's residual with the prediction's rate peaks away from zero lag.";
  static constexpr bool kHasChannel = true;
  std::string channel = "pressure_kPa";
  double offset_s = 1.0;  ///< the channel reads at t what happened at t - offset [s]
  template <class V>
  static void for_each_field(V&& visit) {
    visit("offset_s", &TimeSkewParams::offset_s, FieldInfo{"s", -600.0, 600.0, "time offset of the channel"}, 0.3, 3.0);
  }
};
class TimeSkewEffect : public detail::ParametricEffect<TimeSkewParams> {
 public:
  void apply_to_measurement(Measurement& m) const override {
    if (params_.offset_s == 0.0) return;
    std::vector<double>& x = m.channel(params_.channel);
    const std::vector<double> truth = x;
    const std::vector<double>& t = m.time_s;
    for (std::size_t k = 0; k < x.size(); ++k) {
      const double when = t[k] - params_.offset_s;  // linear interpolation, held at the ends
      const auto upper = std::upper_bound(t.begin(), t.end(), when);
      if (upper == t.begin()) {
        x[k] = truth.front();
      } else if (upper == t.end()) {
        x[k] = truth.back();
      } else {
        const std::size_t j = static_cast<std::size_t>(upper - t.begin());
        const double f = (when - t[j - 1]) / (t[j] - t[j - 1]);
        x[k] = truth[j - 1] + f * (truth[j] - truth[j - 1]);
      }
    }
  }
};

/// sensor_offset: offset and gain error of the pressure calibration.
struct SensorOffsetParams {
  static constexpr const char* kName = "sensor_offset";
  static constexpr const char* kDescription =
      "offset and gain error of the pressure transducer's calibration (appendix B's linear fit, redone by hand). "
      "Gives it away: a constant offset, or a residual proportional to the pressure, at every rate and in holds.";
  static constexpr bool kHasChannel = false;
  double offset_kPa = 5.0;  ///< reading at zero gauge pressure [kPa]
  double gain = 1.0;        ///< reading per true kPa [1]
  template <class V>
  static void for_each_field(V&& visit) {
    visit("offset_kPa", &SensorOffsetParams::offset_kPa, FieldInfo{"kPa", -500.0, 500.0, "pressure offset"}, -12.0, 12.0);
    visit("gain", &SensorOffsetParams::gain, FieldInfo{"1", 0.1, 10.0, "pressure gain"}, 0.93, 1.07);
  }
};
class SensorOffsetEffect : public detail::ParametricEffect<SensorOffsetParams> {
 public:
  void apply_to_measurement(Measurement& m) const override {
    for (double& p : m.pressure_kPa) p = params_.gain * p + params_.offset_kPa;
  }
};

inline EffectCatalog EffectCatalog::builtin() {
  EffectCatalog catalog;
  catalog.add(HeatTransferParams::kName, [] { return std::make_shared<HeatTransferEffect>(); });
  catalog.add(DeadVolumeParams::kName, [] { return std::make_shared<DeadVolumeEffect>(); });
  catalog.add(LeakParams::kName, [] { return std::make_shared<LeakEffect>(); });
  catalog.add(BladderViscoelasticityParams::kName, [] { return std::make_shared<BladderViscoelasticityEffect>(); });
  catalog.add(FiberComplianceParams::kName, [] { return std::make_shared<FiberComplianceEffect>(); });
  catalog.add(FixtureSlackParams::kName, [] { return std::make_shared<FixtureSlackEffect>(); });
  catalog.add(SensorLagParams::kName, [] { return std::make_shared<SensorLagEffect>(); });
  catalog.add(TimeSkewParams::kName, [] { return std::make_shared<TimeSkewEffect>(); });
  catalog.add(SensorOffsetParams::kName, [] { return std::make_shared<SensorOffsetEffect>(); });
  return catalog;
}

}  // namespace pamkit
