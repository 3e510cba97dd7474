// The muscle-parameters file's bodies (declarations and documentation: params_file.hpp), read
// and written with toml++ 3.
//
// Every key of a section is a field of that part's `for_each_field` list, so a field added
// there is read and written here without a change. Two parts carry what a field list of doubles
// cannot: the bladder law (a form and coefficient lists), the gas process and the build's
// construction (enums); their keys are BladderLaw's members, GasParams::process and
// MuscleBuild::construction, spelled as in the C++ and the bindings.
//
// toml++ is used as its user configured it (its CMake target says header-only or a shared
// library): this file defines none of its TOML_* settings.

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <toml++/toml.h>

namespace pamkit {

namespace detail::params_file {

// The sections: MuscleParams' members, and InitialState's.
inline constexpr const char* kBuild = "build";
inline constexpr const char* kBladder = "bladder";
inline constexpr const char* kFriction = "friction";
inline constexpr const char* kGas = "gas";
inline constexpr const char* kExtensions = "extensions";
inline constexpr const char* kInitial = "initial";
// [rig]: the test rig's effects, as catalog specs.
inline constexpr const char* kRig = "rig";
inline constexpr const char* kRigEffects = "effects";

// [bladder]: BladderLaw's members.
inline constexpr const char* kForm = "form";
inline constexpr const char* kLongitudinal = "longitudinal_Pa";
inline constexpr const char* kHoop = "hoop_Pa";
inline constexpr const char* kShearModulus = "shear_modulus_Pa";
inline constexpr std::array<std::pair<const char*, BladderLaw::Form>, 2> kForms{
    {{"polynomial", BladderLaw::Form::polynomial}, {"neo_hookean", BladderLaw::Form::neo_hookean}}};
inline constexpr std::size_t kCoefficients = std::tuple_size<decltype(BladderLaw::longitudinal_Pa)>::value;

// [build]: MuscleBuild::construction, named as to_string(Construction) names it.
inline constexpr const char* kConstruction = "construction";
inline constexpr std::array<Construction, 2> kConstructions{Construction::sleeve, Construction::embedded};

// [gas]: GasParams::process, named as to_string(GasProcess) names it.
inline constexpr const char* kProcess = "process";
inline constexpr std::array<GasProcess, 2> kProcesses{GasProcess::polytropic, GasProcess::heat_transfer};

inline std::string joined(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& name : names) out += (out.empty() ? "" : ", ") + name;
  return out;
}

template <class Struct>
std::vector<std::string> field_names() {
  std::vector<std::string> names;
  Struct::for_each_field([&](const char* name, auto, const FieldInfo&) { names.emplace_back(name); });
  return names;
}

inline std::string type_name(const toml::node& node) {
  std::ostringstream out;
  out << node.type();
  return out.str();
}

/// Reads one file, with the file's name and the place in it in every error.
class Reader {
 public:
  Reader(std::string path, const toml::table& document) : path_(std::move(path)), document_(document) {}

  [[noreturn]] void fail(const toml::source_region& at, const std::string& what) const {
    throw InvalidInput(detail::message(path_, ":", at.begin.line, ":", at.begin.column, ": ", what));
  }

  /// Every section the document has is one of `known`.
  void check_sections(const std::vector<std::string>& known) const {
    for (auto&& [key, node] : document_) {
      (void)node;
      if (std::find(known.begin(), known.end(), key.str()) == known.end()) {
        fail(key.source(), detail::message("unknown section [", key.str(), "] (known: ", joined(known), ")"));
      }
    }
  }

  /// The section `name`, or nullptr if the file has none.
  const toml::table* optional_section(const char* name) const {
    const toml::node* node = document_.get(name);
    if (node == nullptr) return nullptr;
    if (!node->is_table()) {
      fail(node->source(), detail::message(name, " = ... : [", name, "] is a section (a [", name,
                                           "] line, then its keys), not a ", type_name(*node)));
    }
    return node->as_table();
  }

  const toml::table& section(const char* name) const {
    const toml::table* table = optional_section(name);
    if (table == nullptr) {
      throw InvalidInput(detail::message(path_, ": missing section [", name,
                                         "] (a muscle-parameters file states the whole muscle: [", kBuild, "], [",
                                         kBladder, "], [", kFriction, "], [", kGas, "], [", kExtensions, "])"));
    }
    return *table;
  }

  /// Every key of `table` is one of `known`.
  void check_keys(const toml::table& table, const char* section, const std::vector<std::string>& known) const {
    for (auto&& [key, node] : table) {
      (void)node;
      if (std::find(known.begin(), known.end(), key.str()) == known.end()) {
        fail(key.source(), detail::message("unknown key [", section, "] ", key.str(), " (known: ", joined(known), ")"));
      }
    }
  }

  const toml::node& key(const toml::table& table, const char* section, const char* name,
                        const std::string& meaning) const {
    const toml::node* node = table.get(name);
    if (node == nullptr)
      fail(table.source(), detail::message("missing key [", section, "] ", name, " (", meaning, ")"));
    return *node;
  }

  double number(const toml::node& node, const char* section, const char* name) const {
    if (const auto* value = node.as_floating_point()) return value->get();
    if (const auto* value = node.as_integer()) return static_cast<double>(value->get());
    fail(node.source(), detail::message("[", section, "] ", name, " must be a number, not a ", type_name(node)));
  }

  std::string text(const toml::node& node, const char* section, const char* name) const {
    if (const auto* value = node.as_string()) return value->get();
    fail(node.source(), detail::message("[", section, "] ", name, " must be a string, not a ", type_name(node)));
  }

  /// Reads every field of `Struct` from `table`, each checked against its declared range.
  template <class Struct>
  void fields(const toml::table& table, const char* section, Struct& object) const {
    Struct::for_each_field([&](const char* name, auto Struct::*member, const FieldInfo& info) {
      const toml::node& node = key(table, section, name, detail::message("[", info.unit, "] ", info.description));
      const double value = number(node, section, name);
      try {
        detail::check_range(Struct::kName, name, value, info);
      } catch (const InvalidParameter& error) {
        const toml::source_region& at = node.source();
        throw InvalidParameter(detail::message(path_, ":", at.begin.line, ":", at.begin.column, ": [", section, "] ",
                                               name, ": ", error.what()));
      }
      object.*member = value;
    });
  }

  template <class Struct>
  Struct part(const char* section, const std::vector<std::string>& extra_keys = {}) const {
    const toml::table& table = this->section(section);
    std::vector<std::string> known = field_names<Struct>();
    known.insert(known.end(), extra_keys.begin(), extra_keys.end());
    check_keys(table, section, known);
    Struct object;
    fields(table, section, object);
    return object;
  }

  std::array<double, kCoefficients> coefficients(const toml::node& node, const char* name) const {
    const toml::array* list = node.as_array();
    if (list == nullptr || list->empty() || list->size() > kCoefficients) {
      fail(node.source(),
           detail::message("[", kBladder, "] ", name, " must be a list of 1 to ", kCoefficients,
                           " numbers c0, c1, ... [Pa] (sigma = sum c_k eps^k), not ",
                           list == nullptr ? "a " + type_name(node) : detail::message(list->size(), " numbers")));
    }
    std::array<double, kCoefficients> c{};
    for (std::size_t k = 0; k < list->size(); ++k) {
      const toml::node& element = *list->get(k);
      const std::string element_name = detail::message(name, "[", k, "]");
      c[k] = number(element, kBladder, element_name.c_str());
      if (!std::isfinite(c[k])) {
        fail(element.source(), detail::message("[", kBladder, "] ", element_name, " = ", c[k], " must be finite"));
      }
    }
    return c;
  }

  BladderLaw bladder() const {
    const toml::table& table = section(kBladder);
    check_keys(table, kBladder, {kForm, kLongitudinal, kHoop, kShearModulus});
    const toml::node& form_node = key(table, kBladder, kForm, "the membrane law: \"polynomial\" or \"neo_hookean\"");
    const std::string form = text(form_node, kBladder, kForm);
    const auto* chosen = std::find_if(kForms.begin(), kForms.end(), [&](const auto& f) { return form == f.first; });
    if (chosen == kForms.end()) {
      fail(form_node.source(),
           detail::message("[", kBladder, "] ", kForm, " = \"", form, "\" must be \"polynomial\" or \"neo_hookean\""));
    }
    // The keys of the other form would be silently ignored: they are errors.
    const std::vector<const char*> own = chosen->second == BladderLaw::Form::polynomial
                                             ? std::vector<const char*>{kLongitudinal, kHoop}
                                             : std::vector<const char*>{kShearModulus};
    for (auto&& [name, node] : table) {
      if (name.str() == kForm) continue;
      if (std::find_if(own.begin(), own.end(), [&](const char* k) { return name.str() == k; }) == own.end()) {
        fail(node.source(),
             detail::message("[", kBladder, "] ", name.str(), " does not belong to ", kForm, " = \"", form, "\""));
      }
    }
    if (chosen->second == BladderLaw::Form::neo_hookean) {
      const toml::node& node = key(table, kBladder, kShearModulus, "neo-Hookean shear modulus mu [Pa]");
      try {
        return BladderLaw::neo_hookean(number(node, kBladder, kShearModulus));
      } catch (const InvalidParameter& error) {
        const toml::source_region& at = node.source();
        throw InvalidParameter(detail::message(path_, ":", at.begin.line, ":", at.begin.column, ": [", kBladder, "] ",
                                               kShearModulus, ": ", error.what()));
      }
    }
    BladderLaw law;
    law.longitudinal_Pa =
        coefficients(key(table, kBladder, kLongitudinal, "coefficients c0..c6 of sigma_l(eps_l) [Pa]"), kLongitudinal);
    law.hoop_Pa = coefficients(key(table, kBladder, kHoop, "coefficients c0..c6 of sigma_h(eps_h) [Pa]"), kHoop);
    return law;
  }

  MuscleBuild build() const {
    MuscleBuild build = part<MuscleBuild>(kBuild, {kConstruction});
    const toml::node& node = key(section(kBuild), kBuild, kConstruction, "\"sleeve\" or \"embedded\"");
    const std::string name = text(node, kBuild, kConstruction);
    const auto* construction = std::find_if(kConstructions.begin(), kConstructions.end(),
                                            [&](Construction c) { return name == to_string(c); });
    if (construction == kConstructions.end()) {
      fail(node.source(),
           detail::message("[", kBuild, "] ", kConstruction, " = \"", name, "\" must be \"",
                           to_string(Construction::sleeve), "\" or \"", to_string(Construction::embedded), "\""));
    }
    build.construction = *construction;
    return build;
  }

  GasParams gas() const {
    GasParams gas = part<GasParams>(kGas, {kProcess});
    const toml::node& node = key(section(kGas), kGas, kProcess, "\"polytropic\" or \"heat_transfer\"");
    const std::string name = text(node, kGas, kProcess);
    const auto* process =
        std::find_if(kProcesses.begin(), kProcesses.end(), [&](GasProcess p) { return name == to_string(p); });
    if (process == kProcesses.end()) {
      fail(node.source(),
           detail::message("[", kGas, "] ", kProcess, " = \"", name, "\" must be \"", to_string(GasProcess::polytropic),
                           "\" or \"", to_string(GasProcess::heat_transfer), "\""));
    }
    gas.process = *process;
    return gas;
  }

  std::optional<InitialState> initial() const {
    const toml::table* table = optional_section(kInitial);
    if (table == nullptr) return std::nullopt;
    check_keys(*table, kInitial, field_names<InitialState>());
    InitialState initial;
    fields(*table, kInitial, initial);
    return initial;
  }

  std::vector<std::string> rig_effects() const {
    const toml::table* table = optional_section(kRig);
    if (table == nullptr) return {};
    check_keys(*table, kRig, {kRigEffects});
    const toml::node& node = key(*table, kRig, kRigEffects, "a list of effect specs, \"NAME:key=value,...\"");
    const toml::array* list = node.as_array();
    if (list == nullptr) {
      fail(node.source(),
           detail::message("[", kRig, "] ", kRigEffects, " must be a list of strings, not a ", type_name(node)));
    }
    std::vector<std::string> specs;
    for (const toml::node& item : *list) specs.push_back(text(item, kRig, kRigEffects));
    return specs;
  }

  const std::string& path() const { return path_; }

 private:
  std::string path_;
  const toml::table& document_;
};

template <class Struct>
void write_fields(std::ostream& out, const char* section, const Struct& object) {
  out << "\n[" << section << "]\n";
  Struct::for_each_field([&](const char* name, auto Struct::*member, const FieldInfo& info) {
    out << name << " = " << toml::value<double>(object.*member) << "  # [" << info.unit << "] " << info.description
        << "\n";
  });
}

inline toml::array coefficient_list(const std::array<double, kCoefficients>& c) {
  toml::array list;
  for (double value : c) list.push_back(value);
  return list;
}

}  // namespace detail::params_file

inline MuscleParamsFile read_muscle_params_file(const std::string& path) {
  namespace format = detail::params_file;
  toml::table document;
  try {
    document = toml::parse_file(path);
  } catch (const toml::parse_error& error) {
    const toml::source_region& at = error.source();
    if (at.begin.line == 0) throw InvalidInput(detail::message(path, ": ", error.description()));  // unreadable
    throw InvalidInput(detail::message(path, ":", at.begin.line, ":", at.begin.column, ": ", error.description()));
  }
  const format::Reader reader(path, document);
  reader.check_sections({format::kBuild, format::kBladder, format::kFriction, format::kGas, format::kExtensions,
                         format::kInitial, format::kRig});
  MuscleParamsFile file;
  file.params.build = reader.build();
  file.params.bladder = reader.bladder();
  file.params.friction = reader.part<FrictionParams>(format::kFriction);
  file.params.gas = reader.gas();
  file.params.extensions = reader.part<ModelExtensions>(format::kExtensions);
  file.initial = reader.initial();
  file.rig_effects = reader.rig_effects();
  try {
    file.params.validate();  // the relations between fields (the bladder inside the braid, ...)
  } catch (const InvalidParameter& error) {
    throw InvalidParameter(detail::message(path, ": ", error.what()));
  }
  return file;
}

inline MuscleParams read_muscle_params(const std::string& path) { return read_muscle_params_file(path).params; }

inline void write_muscle_params(const std::string& path, const MuscleParams& params,
                                const std::optional<InitialState>& initial, const std::string& comment,
                                const std::vector<std::string>& rig_effects) {
  namespace format = detail::params_file;
  params.validate();
  if (initial) initial->validate();
  std::ostringstream out;
  std::istringstream comment_lines(comment);
  for (std::string line; std::getline(comment_lines, line);) out << "# " << line << "\n";
  out << "# pamkit muscle parameters, SI units; keys are the C++ fields (include/pamkit/io/params_file.hpp)\n";
  format::write_fields(out, format::kBuild, params.build);
  out << format::kConstruction << " = " << toml::value<std::string>(to_string(params.build.construction)) << "  # "
      << to_string(Construction::sleeve) << " (a bladder in a braided sleeve) or " << to_string(Construction::embedded)
      << " (fibres in the membrane: the braid cannot push)\n";

  out << "\n[" << format::kBladder << "]\n";
  if (params.bladder.form == BladderLaw::Form::neo_hookean) {
    out << format::kForm << " = " << toml::value<std::string>("neo_hookean") << "\n";
    out << format::kShearModulus << " = " << toml::value<double>(params.bladder.shear_modulus_Pa)
        << "  # [Pa] neo-Hookean shear modulus mu\n";
  } else {
    out << format::kForm << " = " << toml::value<std::string>("polynomial") << "  # sigma = sum c_k eps^k, c0..c6\n";
    out << format::kLongitudinal << " = " << format::coefficient_list(params.bladder.longitudinal_Pa)
        << "  # [Pa] sigma_l(eps_l)\n";
    out << format::kHoop << " = " << format::coefficient_list(params.bladder.hoop_Pa) << "  # [Pa] sigma_h(eps_h)\n";
  }

  format::write_fields(out, format::kFriction, params.friction);
  format::write_fields(out, format::kGas, params.gas);
  out << format::kProcess << " = " << toml::value<std::string>(to_string(params.gas.process)) << "  # "
      << to_string(GasProcess::polytropic) << " or " << to_string(GasProcess::heat_transfer) << "\n";
  format::write_fields(out, format::kExtensions, params.extensions);
  if (initial) format::write_fields(out, format::kInitial, *initial);
  if (!rig_effects.empty()) {
    toml::array list;
    for (const std::string& spec : rig_effects) list.push_back(spec);
    out << "\n[" << format::kRig << "]  # the test rig's fixture and instruments, as the effect catalog parses them\n";
    out << format::kRigEffects << " = " << list << "\n";
  }

  std::ofstream file(path);
  file << out.str();
  file.close();
  if (!file) throw InvalidInput(detail::message(path, ": cannot be written"));
}

}  // namespace pamkit
