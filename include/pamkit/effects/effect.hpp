#pragma once
/// \file
/// The extension point for effects: physical or instrumental causes of a difference between
/// the model and a measurement. An effect may act at three stages of a simulated measurement:
///   1. the model's parameters (heat exchange, dead volume, leak, ...: new physics or states),
///   2. the motion between the crosshead and the muscle (slack in the fixture),
///   3. the measured channels (sensor lag, clock skew, calibration error).
/// Each stage is the identity unless the effect overrides it. Users add effects by deriving
/// from `Effect` in C++, or from `pamkit.Effect` in Python, and adding a factory to an
/// `EffectCatalog`.

#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "pamkit/fields.hpp"
#include "pamkit/sim/model.hpp"
#include "pamkit/sim/statistics.hpp"

namespace pamkit {

/// The channels a bench test measures, on one time base.
struct Measurement {
  std::vector<double> time_s;             ///< sample times [s]
  std::vector<double> elongation_m;       ///< the crosshead's elongation [m]
  std::vector<double> force_N;            ///< load cell [N]
  std::vector<double> gauge_pressure_Pa;  ///< pressure transducer: above the atmosphere [Pa]
  std::vector<double> temperature_K;      ///< gas temperature sensor [K]
  /// CVODES counters of the run behind a sealed test; all zero where no ODE is integrated (a
  /// supplied test is static at each sample).
  SolverStatistics statistics;

  /// The channel called `name` (force_N, gauge_pressure_Pa or temperature_K).
  /// \throws InvalidInput for any other name.
  std::vector<double>& channel(const std::string& name);
};

/// The names of the measured channels an effect may act on.
inline const std::vector<std::string>& measured_channels() {
  static const std::vector<std::string> names{"force_N", "gauge_pressure_Pa", "temperature_K"};
  return names;
}

/// Where an effect acts in a simulated measurement: the three stages of `Effect`.
enum class EffectStage {
  physics,      ///< the model's parameters and states (new physics)
  motion,       ///< the motion between crosshead and muscle
  measurement,  ///< what the instruments read; the muscle is untouched
};

/// The scale on which a diagnosis moves a parameter while fitting it.
enum class FitScale {
  linear,
  log,         ///< time constants and stiffnesses that span decades
  reciprocal,  ///< "infinity means off" constants, fitted as a rate (0: the effect is off)
};

/// What a record must resolve for a fitted value to mean something.
enum class Resolution {
  any,                ///< every value is resolvable
  sample_interval,    ///< |value| [s] at least the record's sample interval (a skew, a lag)
  travel_per_sample,  ///< value [m] at least the crosshead's travel between two samples (slack)
};

/// A closed interval.
struct ValueRange {
  double min;  ///< lower end
  double max;  ///< upper end (may be infinity)
};

/// The values a parameter takes in real muscles and rigs, with the reason.
struct PlausibleRange {
  double min;          ///< smallest physically plausible value
  double max;          ///< largest physically plausible value (may be infinity)
  const char* source;  ///< why: a material property, a datasheet, a geometric limit
};

/// Where a diagnosis searches a parameter, in the parameter's own unit. An interval of one point
/// (min == max) holds the parameter there: a smoothing width that the data cannot resolve.
struct FitSpace {
  FitScale scale;  ///< how the search moves it
  double min;      ///< search interval's lower end; ending here is "at a bound"
  double max;      ///< search interval's upper end (for `reciprocal`, infinity is the rate 0)
  double start;    ///< where a fit starts
};

/// What an effect declares about a parameter beside its allowed range (`FieldInfo`): declared
/// once in the effect's field list and read by synthetic data, diagnosis and reports alike.
struct EffectFieldInfo {
  ValueRange realistic;      ///< strengths synthetic benches draw (a detectable, typical effect)
  bool either_sign;          ///< `realistic` bounds |value|; the sign is drawn too
  PlausibleRange plausible;  ///< a fitted value outside it is reported, never named as a cause
  FitSpace fit;              ///< the diagnosis's search
  Resolution resolution = Resolution::any;
  /// The value at which the parameter adds nothing to the default model (a zero strength, an
  /// infinite time constant, a unit gain); NaN where no value does. The effect is off when every
  /// parameter that has one takes it; an effect none of whose parameters has one cannot be off.
  double neutral = std::numeric_limits<double>::quiet_NaN();
};

/// One parameter of an effect: its value, unit, allowed range, and what `EffectFieldInfo`
/// declares about it.
struct EffectParameter {
  std::string name;
  double value;
  std::string unit;                                                 ///< SI unit, "1" for a pure number
  double min;                                                       ///< smallest allowed value
  double max;                                                       ///< largest allowed value (may be infinity)
  double realistic_min;                                             ///< smallest value synthetic benches draw
  double realistic_max;                                             ///< largest value synthetic benches draw
  std::string description;                                          ///< meaning
  bool either_sign = false;                                         ///< realistic range bounds |value|
  double plausible_min = -std::numeric_limits<double>::infinity();  ///< physically plausible range
  double plausible_max = std::numeric_limits<double>::infinity();
  std::string plausible_source = {};      ///< why that range
  FitScale fit_scale = FitScale::linear;  ///< diagnosis's search scale
  double fit_min = 0.0;                   ///< diagnosis's search interval
  double fit_max = 0.0;
  double fit_start = 0.0;                   ///< where the search starts
  Resolution resolution = Resolution::any;  ///< what one sample must resolve
  /// The value at which the parameter adds nothing (EffectFieldInfo::neutral); NaN: none.
  double neutral = std::numeric_limits<double>::quiet_NaN();

  /// A parameter with only an allowed and a realistic range (a user effect that declares no
  /// more): plausible is the allowed range, the search is linear over the realistic range
  /// widened by its width on each side, within the allowed range.
  static EffectParameter declared(std::string name, double value, std::string unit, double min, double max,
                                  double realistic_min, double realistic_max, std::string description);
  /// A parameter with everything declared.
  static EffectParameter declared(std::string name, double value, const FieldInfo& field, const EffectFieldInfo& info);
};

/// How the muscle's gas is held during a test: sealed after inflation, or supplied by a regulator.
enum class GasMode { sealed, supplied };

/// A model extension with physical parameters. Effects are immutable once configured and
/// safe to share between threads.
class Effect {
 public:
  virtual ~Effect() = default;

  /// The catalog name; never changes.
  virtual std::string name() const = 0;
  /// What the effect is, and what in the data gives it away.
  virtual std::string description() const = 0;
  /// Numeric parameters with their current values.
  virtual std::vector<EffectParameter> parameters() const = 0;
  /// Text parameters (e.g. which channel) with their current values.
  virtual std::map<std::string, std::string> options() const { return {}; }
  /// Sets one parameter or option from text ("time_constant_s", "2.5").
  /// \throws InvalidParameter naming the effect, key and allowed values.
  virtual void set(const std::string& key, const std::string& value) = 0;
  /// Sets one numeric parameter; by default through `set` with the number printed exactly.
  /// \throws InvalidParameter naming the effect, key and allowed values.
  virtual void set_value(const std::string& key, double value);
  /// The stage the effect acts at; a diagnosis fits a measurement effect on the calibrated
  /// model's prediction without moving the model.
  virtual EffectStage stage() const { return EffectStage::physics; }
  /// The measured channels the effect changes; empty: every channel (physics and motion).
  virtual std::vector<std::string> channels_changed() const { return {}; }
  /// A short phrase for a verdict: what the data shows when this is the cause ("peaks drift
  /// down cycle after cycle"); may name "{channel}". Empty: the description is used.
  virtual std::string signature() const { return {}; }
  /// Whether the effect can act in a test of this kind; `why_not` says why when it cannot.
  virtual bool acts_in(GasMode mode, std::string* why_not) const;

  /// Whether the effect shows only as a difference between the pressurising and the venting
  /// branch of a supplied pressure: on one branch alone it cannot be told from the muscle's
  /// force scale, so a record with no venting rows cannot name it.
  virtual bool shows_between_branches() const { return false; }
  /// Whether `apply_to_measurement` makes each sample's reading from that sample alone (an
  /// offset, a gain), not from its neighbours (a lag, a skew): a caller that reads some samples
  /// only may then leave the others unknown (Simulator::run_sensitivities' `rows`). By default,
  /// whether the effect acts before the measurement, where the reading is untouched; an effect
  /// that overrides `apply_to_measurement` says so for itself.
  virtual bool reads_samples_alone() const { return stage() != EffectStage::measurement; }
  /// Whether the effect is an error of the instrument that reads a supplied pressure, so that
  /// in a supplied test (and a static table) it acts on the pressure that drives the model.
  virtual bool reads_supplied_pressure() const { return false; }
  /// Stage 0, supplied tests only: the pressure that drives the model from the transducer's
  /// reading, sample by sample [Pa gauge]. `time_s` is empty for a static table of settled
  /// rows; an effect that needs time then throws InvalidParameter.
  virtual void apply_to_supplied_pressure(const std::vector<double>& time_s,
                                          std::vector<double>& gauge_pressure_Pa) const;
  /// Stage 1: changes the model's parameters.
  virtual void apply_to_params(MuscleParams& params) const;
  /// Stage 2: the muscle's elongation from the crosshead's, sample by sample.
  virtual std::vector<double> apply_to_elongation(const std::vector<double>& time_s,
                                                  const std::vector<double>& crosshead_m) const;
  /// Stage 3: what the instruments read from the true channels.
  virtual void apply_to_measurement(Measurement& measurement) const;
};

using EffectPtr = std::shared_ptr<Effect>;

/// Effect names mapped to factories; `builtin()` holds pamkit's own catalog. An ordinary
/// object, not a global: make one, add your own effects, pass it where effects are parsed.
class EffectCatalog {
 public:
  using Factory = std::function<EffectPtr()>;

  /// pamkit's effects: the model's physical extensions, what real muscles add (braid_slack,
  /// pressure_hysteresis) and the instruments' errors (include/pamkit/effects/catalog.hpp).
  static EffectCatalog builtin();

  /// Adds or replaces an effect. \throws InvalidParameter for an empty name.
  void add(const std::string& name, Factory factory);
  /// A new effect with default parameters. \throws InvalidParameter for an unknown name.
  EffectPtr make(const std::string& name) const;
  /// Parses "NAME" or "NAME:key=value,key=value" into a configured effect.
  /// \throws InvalidParameter naming the bad part of the text.
  EffectPtr parse(const std::string& spec) const;
  /// The grammar `parse` reads, without making the effect: the name, and the settings in the
  /// order written (key, value), as text. A caller that fills in what a spec leaves out (a
  /// synthetic bench drawing the other parameters) reads the given keys here.
  /// \throws InvalidParameter naming an item that is not key=value.
  static std::pair<std::string, std::vector<std::pair<std::string, std::string>>> split(const std::string& spec);
  std::vector<std::string> names() const;

 private:
  std::map<std::string, Factory> factories_;
};

}  // namespace pamkit

#include "pamkit/effects/effect.hxx"
