#pragma once
/// \file
/// Parameter structures list their fields once, with unit, allowed range and meaning, in a
/// static `for_each_field(visitor)` (the habit of Drake's `Serialize`). Validation, the Python
/// bindings, `repr` and the experiment-file reader are all driven by that one list, so a field
/// added there is checked, bound and read everywhere.

#include <cmath>
#include <string>
#include <type_traits>

#include "pamkit/error.hpp"

namespace pamkit {

/// What a structure says about one of its fields.
struct FieldInfo {
  const char* unit;         ///< SI unit, or "1" for a pure number
  double min;               ///< smallest allowed value (inclusive)
  double max;               ///< largest allowed value (inclusive); +infinity allows infinity
  const char* description;  ///< meaning and source (table or equation of the thesis)
};

namespace detail {

/// Throws InvalidParameter if `value` is NaN or outside `info`'s range.
inline void check_range(const char* struct_name, const char* name, double value, const FieldInfo& info) {
  if (std::isnan(value) || value < info.min || value > info.max) {
    PAMKIT_THROW(InvalidParameter(message(struct_name, ".", name, " = ", value, " ", info.unit,
                                          " is outside the allowed range [", info.min, ", ", info.max, "] (",
                                          info.description, ")")));
  }
}

/// A field's value as a number: an enumeration's by its underlying value (its range then spans
/// the enumerators, so a value cast from a stray integer is caught).
template <class T>
double field_value(T value) {
  if constexpr (std::is_enum_v<T>) {
    return static_cast<double>(static_cast<std::underlying_type_t<T>>(value));
  } else {
    return static_cast<double>(value);
  }
}

/// Visitor that throws InvalidParameter for the first field out of its range.
template <class Struct>
struct RangeChecker {
  const Struct& object;
  const char* struct_name;

  template <class T, class... Extra>
  void operator()(const char* name, T Struct::*member, const FieldInfo& info, const Extra&...) const {
    check_range(struct_name, name, field_value(object.*member), info);
  }
};

}  // namespace detail

/// Checks every field of `object` against the range its structure declares.
/// \throws InvalidParameter naming the structure, field, value and range.
template <class Struct>
void validate_fields(const Struct& object) {
  Struct::for_each_field(detail::RangeChecker<Struct>{object, Struct::kName});
}

}  // namespace pamkit
