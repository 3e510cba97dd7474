#pragma once

#include <sstream>

namespace pamkit {

inline std::vector<double>& Measurement::channel(const std::string& name) {
  if (name == "force_N") return force_N;
  if (name == "pressure_kPa") return pressure_kPa;
  if (name == "temperature_C") return temperature_C;
  throw InvalidInput(detail::message("no measured channel '", name, "' (force_N, pressure_kPa, temperature_C)"));
}

inline bool Effect::acts_in(GasMode, std::string*) const { return true; }
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

inline EffectPtr EffectCatalog::parse(const std::string& spec) const {
  const auto colon = spec.find(':');
  EffectPtr effect = make(spec.substr(0, colon));
  if (colon == std::string::npos) return effect;
  std::istringstream items(spec.substr(colon + 1));
  std::string item;
  while (std::getline(items, item, ',')) {
    const auto equals = item.find('=');
    if (equals == std::string::npos || equals == 0) {
      throw InvalidParameter(detail::message("effect '", spec, "': '", item, "' is not key=value"));
    }
    effect->set(item.substr(0, equals), item.substr(equals + 1));
  }
  return effect;
}

inline std::vector<std::string> EffectCatalog::names() const {
  std::vector<std::string> out;
  for (const auto& [name, unused] : factories_) out.push_back(name);
  return out;
}

}  // namespace pamkit
