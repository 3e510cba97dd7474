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
/// `for_each_field` visits (name, member, FieldInfo, EffectFieldInfo), the stage the effect
/// acts at (`kStage`), a verdict phrase (`kSignature`), and an optional measured channel.
template <class Params>
class ParametricEffect : public Effect {
 public:
  std::string name() const override { return Params::kName; }
  std::string description() const override { return Params::kDescription; }
  std::string signature() const override { return Params::kSignature; }
  EffectStage stage() const override { return Params::kStage; }

  std::vector<EffectParameter> parameters() const override {
    std::vector<EffectParameter> out;
    Params::for_each_field(
        [&](const char* key, double Params::*member, const FieldInfo& field, const EffectFieldInfo& info) {
          out.push_back(EffectParameter::declared(key, params_.*member, field, info));
        });
    return out;
  }

  std::map<std::string, std::string> options() const override {
    if constexpr (Params::kHasChannel) return {{"channel", params_.channel}};
    return {};
  }

  std::vector<std::string> channels_changed() const override {
    if constexpr (Params::kHasChannel) {
      return {params_.channel};
    } else if constexpr (Params::kStage == EffectStage::measurement) {
      return {Params::kChannel};
    } else {
      return {};
    }
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
    if (!has_field(key)) throw unknown_key(key);
    set_value(key, parse_number(Params::kName, key, value));
  }

  void set_value(const std::string& key, double value) override {
    bool found = false;
    Params::for_each_field(
        [&](const char* field, double Params::*member, const FieldInfo& info, const EffectFieldInfo&) {
          if (key != field) return;
          check_range(Params::kName, field, value, info);
          params_.*member = value;
          found = true;
        });
    if (!found) throw unknown_key(key);
  }

  const Params& params() const { return params_; }

 protected:
  Params params_;

 private:
  static bool has_field(const std::string& key) {
    bool found = false;
    Params::for_each_field([&](const char* field, double Params::*, const FieldInfo&, const EffectFieldInfo&) {
      found = found || key == field;
    });
    return found;
  }

  static InvalidParameter unknown_key(const std::string& key) {
    std::string known = Params::kHasChannel ? "channel" : "";
    Params::for_each_field([&](const char* field, double Params::*, const FieldInfo&, const EffectFieldInfo&) {
      known += (known.empty() ? "" : ", ") + std::string(field);
    });
    return InvalidParameter(message("effect ", Params::kName, " has no parameter '", key, "' (", known, ")"));
  }
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
    *why_not = message(effect,
                       " needs the dynamic muscle model, which pamkit runs for sealed tests only; a supplied "
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
  static constexpr const char* kSignature = "pressure loops open up with rate and the gas exchanges heat with the wall";
  static constexpr EffectStage kStage = EffectStage::physics;
  static constexpr bool kHasChannel = false;
  /// gas-wall exchange time constant [s]; the gas model's own default (table 3.6)
  double time_constant_s = GasParams{}.heat_transfer_time_constant_s;
  template <class V>
  static void for_each_field(V&& visit) {
    visit("time_constant_s", &HeatTransferParams::time_constant_s,
          FieldInfo{"s", 0.0, 1e9, "gas-wall heat exchange time constant"},
          EffectFieldInfo{{0.5, 10.0},
                          false,
                          {0.05, 30.0,
                           "0.38 s reproduces table 3.6 on the thesis muscle (forced flow into the cones); natural "
                           "convection in a 20-30 mm muscle gives 0.8-3.8 s (docs/table_3_6.md); a factor 8 below "
                           "for small muscles and above for thick, slow walls"},
                          {FitScale::log, 0.02, 200.0, 2.0}});
  }
};
class HeatTransferEffect : public detail::ParametricEffect<HeatTransferParams> {
 public:
  bool acts_in(GasMode mode, std::string* why_not) const override {
    return detail::sealed_only(HeatTransferParams::kName, mode, why_not);
  }
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
  static constexpr const char* kSignature = "the pressure swings less than the muscle's volume change implies, evenly";
  static constexpr EffectStage kStage = EffectStage::physics;
  static constexpr bool kHasChannel = false;
  double volume_fraction = 0.05;  ///< dead volume over the muscle's initial gas volume [1]
  template <class V>
  static void for_each_field(V&& visit) {
    visit("volume_fraction", &DeadVolumeParams::volume_fraction,
          FieldInfo{"1", 0.0, 10.0, "dead volume / initial gas volume"},
          EffectFieldInfo{{0.03, 0.3},
                          false,
                          {0.0, 0.6,
                           "hose and transducer: 5 % in the thesis (appendix B); a metre of 4 mm hose is 9 % of the "
                           "thesis muscle's 140 cm^3; more than 60 % needs a reservoir the test would declare"},
                          {FitScale::linear, 0.0, 1.0, 0.1}});
  }
};
class DeadVolumeEffect : public detail::ParametricEffect<DeadVolumeParams> {
 public:
  bool acts_in(GasMode mode, std::string* why_not) const override {
    return detail::sealed_only(DeadVolumeParams::kName, mode, why_not);
  }
  void apply_to_params(MuscleParams& p) const override { p.extensions.dead_volume_fraction = params_.volume_fraction; }
};

/// leak: gas escapes through an orifice; the gauge pressure decays with tau at fixed volume.
struct LeakParams {
  static constexpr const char* kName = "leak";
  static constexpr const char* kDescription =
      "gas escaping through an orifice (a seal, the sensor's wires): the gauge pressure decays with a time constant. "
      "Gives it away: pressure and force peaks drift down cycle after cycle.";
  static constexpr const char* kSignature = "peaks drift down cycle after cycle";
  static constexpr EffectStage kStage = EffectStage::physics;
  static constexpr bool kHasChannel = false;
  double time_constant_s = 1000.0;  ///< decay time of the gauge pressure at fixed volume [s]; inf: sealed
  template <class V>
  static void for_each_field(V&& visit) {
    visit("time_constant_s", &LeakParams::time_constant_s,
          FieldInfo{"s", 1e-3, detail::kInfinity, "leak time constant (inf: none)"},
          EffectFieldInfo{{100.0, 3000.0},
                          false,
                          {20.0, detail::kInfinity,
                           "a sealed test runs 5-10 stretch cycles of 2-200 s after one inflation; a muscle that "
                           "loses 63 % of its gauge pressure in under 20 s could not be tested sealed"},
                          {FitScale::reciprocal, 5.0, detail::kInfinity, 1000.0}});
  }
};
class LeakEffect : public detail::ParametricEffect<LeakParams> {
 public:
  bool acts_in(GasMode mode, std::string* why_not) const override {
    return detail::sealed_only(LeakParams::kName, mode, why_not);
  }
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
  static constexpr const char* kSignature = "force hysteresis that pressure does not share";
  static constexpr EffectStage kStage = EffectStage::physics;
  static constexpr bool kHasChannel = false;
  double time_constant_s = 2.0;  ///< relaxation time of the Maxwell branch [s]
  double strength = 0.5;         ///< branch modulus over the tangent modulus [1]
  template <class V>
  static void for_each_field(V&& visit) {
    visit("time_constant_s", &BladderViscoelasticityParams::time_constant_s,
          FieldInfo{"s", 1e-4, 1e6, "relaxation time"},
          EffectFieldInfo{{0.5, 20.0},
                          false,
                          {0.2, 100.0,
                           "the thesis's biaxial tests show the hysteresis at cycle times of seconds (figure 3.5); a "
                           "branch relaxing in under 0.2 s is elastic at bench rates, over 100 s a drift"},
                          {FitScale::log, 0.1, 200.0, 2.0}});
    visit("strength", &BladderViscoelasticityParams::strength,
          FieldInfo{"1", 0.0, 100.0, "branch modulus / tangent modulus"},
          EffectFieldInfo{{0.3, 3.0},
                          false,
                          {0.0, 3.0,
                           "a branch stiffer than 3x the elastic tangent modulus means a loss tangent above 1, "
                           "beyond the most damped butyl compounds"},
                          {FitScale::linear, 0.0, 20.0, 0.5}});
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
  static constexpr const char* kSignature = "force softens at high stretch";
  static constexpr EffectStage kStage = EffectStage::physics;
  static constexpr bool kHasChannel = false;
  double stiffness_N = 300.0;  ///< axial stiffness EA of one fiber [N]; inf: inextensible
  template <class V>
  static void for_each_field(V&& visit) {
    visit("stiffness_N", &FiberComplianceParams::stiffness_N,
          FieldInfo{"N", 1.0, detail::kInfinity, "fiber axial stiffness EA (inf: rigid)"},
          EffectFieldInfo{{100.0, 600.0},
                          false,
                          {50.0, detail::kInfinity,
                           "a braid strand of 0.1-0.5 mm^2 polyester or nylon (E = 2-5 GPa) has EA = 200-2500 N; "
                           "below 50 N the braid would stretch by several per cent at bench tensions"},
                          {FitScale::reciprocal, 10.0, detail::kInfinity, 300.0}});
  }
};
class FiberComplianceEffect : public detail::ParametricEffect<FiberComplianceParams> {
 public:
  bool acts_in(GasMode mode, std::string* why_not) const override {
    return detail::dynamic_only(FiberComplianceParams::kName, mode, why_not);
  }
  void apply_to_params(MuscleParams& p) const override {
    p.extensions.fiber_compliance_per_N = 1.0 / params_.stiffness_N;
  }
};

/// braid_slack: the braid carries tension but cannot push.
struct BraidSlackParams {
  static constexpr const char* kName = "braid_slack";
  static constexpr const char* kDescription =
      "a braid of fibers that cannot push: held shorter than its free length at the pressure, the muscle goes "
      "slack and carries nothing, where the thesis's braid would push. Gives it away: the measured force stays "
      "at zero where the model's turns negative (short lengths, low pressures of an isometric map; contraction "
      "below the free length).";
  static constexpr const char* kSignature = "force stays at zero where the model pushes";
  static constexpr EffectStage kStage = EffectStage::physics;
  static constexpr bool kHasChannel = false;
  double band_N = 1.0;  ///< width of the smooth transition to slack [N]
  template <class V>
  static void for_each_field(V&& visit) {
    visit("band_N", &BraidSlackParams::band_N, FieldInfo{"N", 1e-3, 1e4, "width of the smooth slack transition"},
          EffectFieldInfo{{0.5, 5.0},
                          false,
                          {0.0, detail::kInfinity,
                           "a smoothing width, not a property of the braid: the data cannot tell one width from "
                           "another, so a diagnosis holds it at 1 N"},
                          {FitScale::linear, 1.0, 1.0, 1.0}});
  }
};
class BraidSlackEffect : public detail::ParametricEffect<BraidSlackParams> {
 public:
  /// A sealed test stretched from its free length keeps the braid taut, and where it would not
  /// (a sealed muscle pushed below its free length) the gas volume should follow the free
  /// length, which the slack force alone does not model. The simulator still honours
  /// ModelExtensions::slack_band_N in sealed runs for those who set it.
  bool acts_in(GasMode mode, std::string* why_not) const override {
    if (mode == GasMode::supplied) return true;
    if (why_not) {
      *why_not =
          "braid_slack acts in supplied tests and static tables; a sealed muscle stretched from its free length "
          "keeps its braid taut";
    }
    return false;
  }
  void apply_to_params(MuscleParams& p) const override { p.extensions.slack_band_N = params_.band_N; }
};

/// pressure_hysteresis: rate-independent friction between bladder and braid as the supplied
/// pressure is raised and lowered.
struct PressureHysteresisParams {
  static constexpr const char* kName = "pressure_hysteresis";
  static constexpr const char* kDescription =
      "rate-independent friction between the bladder and the braid as the supplied pressure is raised and lowered "
      "(a Coulomb friction proportional to the pressure force p pi D^2/4): raising the pressure the muscle shows less "
      "tension than its elastic force, lowering it more. Gives it away: at the same pressure and length the force "
      "on venting lies above the force on pressurising; under a load, the muscle is shorter on venting; the loop "
      "does not shrink with slower steps.";
  static constexpr const char* kSignature = "force on venting above force on pressurising, at any rate";
  static constexpr EffectStage kStage = EffectStage::physics;
  static constexpr bool kHasChannel = false;
  double coefficient = 0.1;  ///< friction over the pressure force p pi D^2/4 [1]
  template <class V>
  static void for_each_field(V&& visit) {
    visit("coefficient", &PressureHysteresisParams::coefficient,
          FieldInfo{"1", 0.0, 10.0, "pressurise/vent friction over the pressure force p pi D^2/4"},
          EffectFieldInfo{{0.03, 0.3},
                          false,
                          {0.0, 1.0,
                           "rubber on a polyamide or aramid braid has a friction coefficient of 0.3-1, and only part "
                           "of the pressure force presses the bladder into the braid's crossings: above 1 the "
                           "friction would exceed the whole pressure force"},
                          {FitScale::linear, 0.0, 2.0, 0.05}});
  }
};
class PressureHysteresisEffect : public detail::ParametricEffect<PressureHysteresisParams> {
 public:
  bool shows_between_branches() const override { return true; }
  /// In a sealed test the pressure follows the stretch, and the thesis's friction (eqs.
  /// 3.1.19-3.1.24) already acts on the braid's velocity.
  bool acts_in(GasMode mode, std::string* why_not) const override {
    if (mode == GasMode::supplied) return true;
    if (why_not) {
      *why_not =
          "pressure_hysteresis acts where a supplied pressure is raised and lowered; in a sealed test the thesis's "
          "friction acts on the braid's velocity";
    }
    return false;
  }
  void apply_to_params(MuscleParams& p) const override { p.extensions.pressure_hysteresis = params_.coefficient; }
};

/// fixture_slack: play between crosshead and muscle (loose pins).
struct FixtureSlackParams {
  static constexpr const char* kName = "fixture_slack";
  static constexpr const char* kDescription =
      "slack between crosshead and muscle (pins in loose holes): the muscle moves only once the crosshead has "
      "taken up the play, at each reversal. Gives it away: force stays flat at the start of each stretch and "
      "each return; the force-elongation loop is shifted and widened by the slack.";
  static constexpr const char* kSignature = "force stays flat at the start of each stretch";
  static constexpr EffectStage kStage = EffectStage::motion;
  static constexpr bool kHasChannel = false;
  double slack_m = 1e-3;  ///< total play [m]
  template <class V>
  static void for_each_field(V&& visit) {
    visit("slack_m", &FixtureSlackParams::slack_m, FieldInfo{"m", 0.0, 0.05, "play between crosshead and muscle"},
          EffectFieldInfo{{0.5e-3, 3e-3},
                          false,
                          {0.0, 5e-3,
                           "pins in loose holes: two clearance fits of 0.1-1 mm each; 5 mm of play is a visibly "
                           "loose fixture"},
                          {FitScale::linear, 0.0, 0.02, 1e-3},
                          Resolution::travel_per_sample});
  }
};
class FixtureSlackEffect : public detail::ParametricEffect<FixtureSlackParams> {
 public:
  /// A play (backlash) operator: the muscle stays put until the crosshead pushes it from
  /// either end of a band `slack_m` wide; it starts at the band's upper end.
  std::vector<double> apply_to_elongation(const std::vector<double>&,
                                          const std::vector<double>& crosshead) const override {
    std::vector<double> muscle(crosshead.size());
    double position = crosshead.empty() ? 0.0 : crosshead.front();
    for (std::size_t k = 0; k < crosshead.size(); ++k) {
      position = std::clamp(position, crosshead[k] - params_.slack_m, crosshead[k]);
      muscle[k] = position;
    }
    return muscle;
  }
};

namespace detail {
/// The exact response of tau dy/dt = x - y to an `x` linear between samples, starting settled,
/// written over `x`.
inline void first_order_lag(const std::vector<double>& time_s, std::vector<double>& x, double tau) {
  if (tau == 0.0 || x.empty()) return;
  double y = x.front();
  double previous = x.front();  // the input at the last sample (x is overwritten)
  for (std::size_t k = 1; k < x.size(); ++k) {
    const double decay = std::exp(-(time_s[k] - time_s[k - 1]) / tau);
    const double slope = (x[k] - previous) / (time_s[k] - time_s[k - 1]);
    y = x[k] - slope * tau + (y - previous + slope * tau) * decay;
    previous = x[k];
    x[k] = y;
  }
}
}  // namespace detail

/// sensor_lag: a first-order lag on one measured channel.
struct SensorLagParams {
  static constexpr const char* kName = "sensor_lag";
  static constexpr const char* kDescription =
      "first-order lag of one channel (a TMP36 in still air is slow; a long hose slows a pressure transducer). "
      "In a supplied test on pressure_kPa, the muscle's pressure lags the transducer's reading (a hose and the "
      "muscle's volume between them). Gives it away: that channel lags its prediction and its swings are "
      "attenuated, more so at higher rates; in a supplied test the force lags the pressure.";
  static constexpr const char* kSignature = "{channel} lags its prediction and swings less";
  static constexpr EffectStage kStage = EffectStage::measurement;
  static constexpr bool kHasChannel = true;
  std::string channel = "temperature_C";
  double time_constant_s = 5.0;  ///< time constant of the lag [s]; 0: none
  template <class V>
  static void for_each_field(V&& visit) {
    visit("time_constant_s", &SensorLagParams::time_constant_s, FieldInfo{"s", 0.0, 1e4, "sensor time constant"},
          EffectFieldInfo{{0.5, 20.0},
                          false,
                          {0.0, 60.0,
                           "a TMP36 in still air: 9-32 s from its thermal resistance and capacity "
                           "(docs/table_3_6.md); transducers and load cells respond in milliseconds"},
                          {FitScale::log, 1e-3, 300.0, 2.0},
                          Resolution::sample_interval});
  }
};
class SensorLagEffect : public detail::ParametricEffect<SensorLagParams> {
 public:
  /// On the pressure of a supplied test the lag sits between the transducer and the muscle:
  /// the reading is the regulator's, and the muscle's gas follows it through the hose.
  bool reads_supplied_pressure() const override { return params_.channel == "pressure_kPa"; }
  /// A static table's rows are settled (empty `time_s`): the lag has died out.
  void apply_to_supplied_pressure(const std::vector<double>& time_s, std::vector<double>& pressure_kPa) const override {
    if (reads_supplied_pressure() && !time_s.empty())
      detail::first_order_lag(time_s, pressure_kPa, params_.time_constant_s);
  }
  void apply_to_measurement(Measurement& m) const override {
    detail::first_order_lag(m.time_s, m.channel(params_.channel), params_.time_constant_s);
  }
};

/// time_skew: a channel's clock runs behind (or ahead of) the tensile machine's.
struct TimeSkewParams {
  static constexpr const char* kName = "time_skew";
  static constexpr const char* kDescription =
      "constant time offset between channels logged by different instruments (the Arduino's pressure and "
      "temperature against the tensile machine's force), left after a synchronisation by hand. Gives it away: "
      "the cross-correlation of that channel's residual with the prediction's rate peaks away from zero lag.";
  static constexpr const char* kSignature = "{channel} is shifted in time against the machine's channels";
  static constexpr EffectStage kStage = EffectStage::measurement;
  static constexpr bool kHasChannel = true;
  std::string channel = "pressure_kPa";
  double offset_s = 1.0;  ///< the channel reads at t what happened at t - offset [s]
  template <class V>
  static void for_each_field(V&& visit) {
    visit("offset_s", &TimeSkewParams::offset_s, FieldInfo{"s", -600.0, 600.0, "time offset of the channel"},
          EffectFieldInfo{{0.3, 3.0},
                          true,
                          {-5.0, 5.0,
                           "two instruments started by hand and aligned by eye or by cross-correlation "
                           "(pamkit align): seconds at most"},
                          {FitScale::linear, -6.0, 6.0, 0.0},
                          Resolution::sample_interval});
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
  static constexpr const char* kSignature = "pressure reads off by a constant or a scale";
  static constexpr EffectStage kStage = EffectStage::measurement;
  static constexpr const char* kChannel = "pressure_kPa";
  static constexpr bool kHasChannel = false;
  double offset_kPa = 5.0;  ///< reading at zero gauge pressure [kPa]
  double gain = 1.0;        ///< reading per true kPa [1]
  template <class V>
  static void for_each_field(V&& visit) {
    visit("offset_kPa", &SensorOffsetParams::offset_kPa, FieldInfo{"kPa", -500.0, 500.0, "pressure offset"},
          EffectFieldInfo{{-12.0, 12.0},
                          false,
                          {-15.0, 15.0,
                           "2 % of the 61CP transducer's 0-100 psi span (689 kPa) after a calibration by hand "
                           "(appendix B)"},
                          {FitScale::linear, -100.0, 100.0, 0.0}});
    visit("gain", &SensorOffsetParams::gain, FieldInfo{"1", 0.1, 10.0, "pressure gain"},
          EffectFieldInfo{{0.93, 1.07},
                          false,
                          {0.9, 1.1, "a calibration line through appendix B's points off by at most 10 % in slope"},
                          {FitScale::linear, 0.5, 1.5, 1.0}});
  }
};
class SensorOffsetEffect : public detail::ParametricEffect<SensorOffsetParams> {
 public:
  /// In a supplied test the transducer's reading is the model's input: the true pressure is
  /// the reading with the calibration error undone, and the reported channel is read again.
  bool reads_supplied_pressure() const override { return true; }
  void apply_to_supplied_pressure(const std::vector<double>&, std::vector<double>& pressure_kPa) const override {
    for (double& p : pressure_kPa) p = (p - params_.offset_kPa) / params_.gain;
  }
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
  catalog.add(BraidSlackParams::kName, [] { return std::make_shared<BraidSlackEffect>(); });
  catalog.add(PressureHysteresisParams::kName, [] { return std::make_shared<PressureHysteresisEffect>(); });
  catalog.add(SensorLagParams::kName, [] { return std::make_shared<SensorLagEffect>(); });
  catalog.add(TimeSkewParams::kName, [] { return std::make_shared<TimeSkewEffect>(); });
  catalog.add(SensorOffsetParams::kName, [] { return std::make_shared<SensorOffsetEffect>(); });
  return catalog;
}

}  // namespace pamkit
