#pragma once
/// \file
/// What the built-in effects share: `detail::ParametricEffect`, an `Effect` whose numeric
/// parameters are declared once in a struct's `for_each_field`, and the reasons an effect gives
/// when it cannot act in a test. Each built-in effect is one header in `builtin/`.

#include <algorithm>
#include <limits>
#include <map>
#include <string>
#include <vector>

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
template <class EffectParams>
class ParametricEffect : public Effect {
 public:
  using Params = EffectParams;  ///< the parameter struct: name, stage, fields

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
                                         "' is not one of force_N, gauge_pressure_Pa, temperature_K"));
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

}  // namespace pamkit
