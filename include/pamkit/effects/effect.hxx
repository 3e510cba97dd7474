#pragma once

#include <algorithm>
#include <sstream>

namespace pamkit {

inline std::vector<double>& Measurement::channel(const std::string& name) {
  if (name == "force_N") return force_N;
  if (name == "gauge_pressure_Pa") return gauge_pressure_Pa;
  if (name == "temperature_K") return temperature_K;
  throw InvalidInput(detail::message("no measured channel '", name, "' (force_N, gauge_pressure_Pa, temperature_K)"));
}

inline bool Effect::acts_in(GasMode, std::string*) const { return true; }
inline void Effect::set_value(const std::string& key, double value) {
  std::ostringstream text;
  text.precision(17);
  text << value;
  set(key, text.str());
}

inline EffectParameter EffectParameter::declared(std::string name, double value, std::string unit, double min,
                                                 double max, double realistic_min, double realistic_max,
                                                 std::string description) {
  const double width = std::max(realistic_max - realistic_min, 1e-12);
  const double fit_min = std::max(min, realistic_min - width);
  const double fit_max = std::min(max, realistic_max + width);
  EffectParameter p{std::move(name), value,         std::move(unit),       min, max,
                    realistic_min,   realistic_max, std::move(description)};
  p.plausible_min = min;
  p.plausible_max = max;
  p.plausible_source = "not declared by the effect: its allowed range";
  p.fit_min = fit_min;
  p.fit_max = fit_max;
  p.fit_start = 0.5 * (realistic_min + realistic_max);
  return p;
}

inline EffectParameter EffectParameter::declared(std::string name, double value, const FieldInfo& field,
                                                 const EffectFieldInfo& info) {
  EffectParameter p{std::move(name),  value, field.unit, field.min, field.max, info.realistic.min, info.realistic.max,
                    field.description};
  p.either_sign = info.either_sign;
  p.plausible_min = info.plausible.min;
  p.plausible_max = info.plausible.max;
  p.plausible_source = info.plausible.source;
  p.fit_scale = info.fit.scale;
  p.fit_min = info.fit.min;
  p.fit_max = info.fit.max;
  p.fit_start = info.fit.start;
  p.resolution = info.resolution;
  p.neutral = info.neutral;
  return p;
}
inline void Effect::apply_to_supplied_pressure(const std::vector<double>&, std::vector<double>&) const {}
inline void Effect::apply_to_params(MuscleParams&) const {}
inline std::vector<double> Effect::apply_to_elongation(const std::vector<double>&,
                                                       const std::vector<double>& crosshead_m) const {
  return crosshead_m;
}
inline void Effect::apply_to_measurement(Measurement&) const {}

inline void EffectCatalog::add(const std::string& name, Factory factory) {
  if (name.empty()) throw InvalidParameter("EffectCatalog.add: an effect needs a name");
  factories_[name] = std::move(factory);
}

inline EffectPtr EffectCatalog::make(const std::string& name) const {
  const auto found = factories_.find(name);
  if (found == factories_.end()) {
    std::ostringstream known;
    for (const auto& [key, unused] : factories_) known << (known.tellp() > 0 ? ", " : "") << key;
    throw InvalidParameter(detail::message("unknown effect '", name, "' (known: ", known.str(), ")"));
  }
  return found->second();
}

inline std::pair<std::string, std::vector<std::pair<std::string, std::string>>> EffectCatalog::split(
    const std::string& spec) {
  const auto colon = spec.find(':');
  std::pair<std::string, std::vector<std::pair<std::string, std::string>>> out{spec.substr(0, colon), {}};
  if (colon == std::string::npos) return out;
  std::istringstream items(spec.substr(colon + 1));
  std::string item;
  while (std::getline(items, item, ',')) {
    const auto equals = item.find('=');
    if (equals == std::string::npos || equals == 0) {
      throw InvalidParameter(detail::message("effect '", spec, "': '", item, "' is not key=value"));
    }
    out.second.emplace_back(item.substr(0, equals), item.substr(equals + 1));
  }
  return out;
}

inline EffectPtr EffectCatalog::parse(const std::string& spec) const {
  EffectPtr effect = make(spec.substr(0, spec.find(':')));  // an unknown name is the first thing said
  for (const auto& [key, value] : split(spec).second) effect->set(key, value);
  return effect;
}

inline std::vector<std::string> EffectCatalog::names() const {
  std::vector<std::string> out;
  for (const auto& [name, unused] : factories_) out.push_back(name);
  return out;
}

}  // namespace pamkit
