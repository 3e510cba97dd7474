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
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "pamkit/fields.hpp"
#include "pamkit/sim/model.hpp"

namespace pamkit {

/// The channels a bench test measures, on one time base.
struct Measurement {
  std::vector<double> time_s;         ///< sample times [s]
  std::vector<double> elongation_m;   ///< the crosshead's elongation [m]
  std::vector<double> force_N;        ///< load cell [N]
  std::vector<double> pressure_kPa;   ///< pressure transducer, gauge [kPa]
  std::vector<double> temperature_C;  ///< gas temperature sensor [degC]

  /// The channel called `name` (force_N, pressure_kPa or temperature_C).
  /// \throws InvalidInput for any other name.
  std::vector<double>& channel(const std::string& name);
};

/// The names of the measured channels an effect may act on.
inline const std::vector<std::string>& measured_channels() {
  static const std::vector<std::string> names{"force_N", "pressure_kPa", "temperature_C"};
  return names;
}

/// One parameter of an effect: its value, unit, allowed range, and the range it takes in
/// real benches (what synthetic data draws from).
struct EffectParameter {
  std::string name;
  double value;
  std::string unit;         ///< SI unit, "1" for a pure number
  double min;               ///< smallest allowed value
  double max;               ///< largest allowed value (may be infinity)
  double realistic_min;     ///< smallest value seen on real benches
  double realistic_max;     ///< largest value seen on real benches
  std::string description;  ///< meaning
};

/// How the muscle's gas is held during a test (DESIGN.md, "A measured dataset").
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
  /// Whether the effect can act in a test of this kind; `why_not` says why when it cannot.
  virtual bool acts_in(GasMode mode, std::string* why_not) const;

  /// Stage 1: changes the model's parameters.
  virtual void apply_to_params(MuscleParams& params) const;
  /// Stage 2: the muscle's elongation from the crosshead's, sample by sample.
  virtual std::vector<double> apply_to_elongation(const std::vector<double>& time_s,
                                                  const std::vector<double>& crosshead_m) const;
  /// Stage 3: what the instruments read from the true channels.
  virtual void apply_to_measurement(Measurement& measurement) const;
};

using EffectPtr = std::shared_ptr<Effect>;

/// Effect names mapped to factories; `builtin()` holds the catalog of DESIGN.md. An ordinary
/// object, not a global: make one, add your own effects, pass it where effects are parsed.
class EffectCatalog {
 public:
  using Factory = std::function<EffectPtr()>;

  /// The nine effects of DESIGN.md's catalog.
  static EffectCatalog builtin();

  /// Adds or replaces an effect. \throws InvalidParameter for an empty name.
  void add(const std::string& name, Factory factory);
  /// A new effect with default parameters. \throws InvalidParameter for an unknown name.
  EffectPtr make(const std::string& name) const;
  /// Parses "NAME" or "NAME:key=value,key=value" into a configured effect.
  /// \throws InvalidParameter naming the bad part of the text.
  EffectPtr parse(const std::string& spec) const;
  std::vector<std::string> names() const;

 private:
  std::map<std::string, Factory> factories_;
};

}  // namespace pamkit

#include "pamkit/effects/effect.hxx"
