# Turns data/gait/winter_g3.csv (a header row, then numbers) into a C++ header with the same
# numbers as a table, so the library carries Winter's data without reading files at run time
# and the CSV stays the one source. Called at configure time by the top-level CMakeLists.txt.
function(pamkit_embed_gait_table csv header)
  file(STRINGS ${csv} lines)
  list(POP_FRONT lines columns)
  set(rows "")
  set(count 0)
  foreach(line IN LISTS lines)
    string(STRIP "${line}" line)
    if(line STREQUAL "")
      continue()
    endif()
    if(NOT line MATCHES "^[-+0-9.eE]+(,[-+0-9.eE]+)*$")
      message(FATAL_ERROR "${csv}: row '${line}' is not a row of numbers")
    endif()
    string(APPEND rows "    {${line}},\n")
    math(EXPR count "${count} + 1")
  endforeach()
  file(CONFIGURE OUTPUT ${header} CONTENT [=[
#pragma once
// Generated from data/gait/winter_g3.csv by cmake/embed_gait_table.cmake; edit the CSV.
// Columns: @columns@

#include <array>

namespace pamkit::exo::data {
inline constexpr std::array<std::array<double, 5>, @count@> kWinterAppendixG3{{
@rows@}};
}  // namespace pamkit::exo::data
]=] @ONLY)
  set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${csv})
endfunction()
