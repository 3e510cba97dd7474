#pragma once
/// \file
/// The exceptions pamkit throws. Every one derives from pamkit::Error so a caller can catch
/// them all; the bindings map InvalidParameter and InvalidInput to Python's ValueError.
///
/// The headers of the muscle's force (pamkit::muscle: muscle/, sim/model.hpp and what they
/// include) raise errors through PAMKIT_THROW, so that a controller built with -fno-exceptions
/// can include them: there an error prints its message and aborts, as it would end the program
/// uncaught. Only parameter checks at construction can reach it; the real-time force call
/// (muscle/realtime.hpp) reports by status instead.

#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <stdexcept>
#include <string>

namespace pamkit {

/// Base of every pamkit exception.
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A parameter is outside its allowed range. The message names the structure, the field,
/// the value and the range, e.g. "MuscleBuild.fiber_count = -3 is outside [1, 2000]".
class InvalidParameter : public Error {
 public:
  using Error::Error;
};

/// An input (a trajectory, a length, a pressure) cannot be used; the message says which and where.
class InvalidInput : public Error {
 public:
  using Error::Error;
};

/// The integrator failed; the message carries the SUNDIALS flag name and the time reached.
class SolverError : public Error {
 public:
  using Error::Error;
};

namespace detail {
/// Builds a message from streamable parts: detail::message("x = ", x, " at t = ", t).
template <class... Parts>
std::string message(const Parts&... parts) {
  std::ostringstream out;
  out.precision(10);
  (out << ... << parts);
  return out.str();
}

/// What PAMKIT_THROW does without exceptions: the message on stderr, then std::abort().
[[noreturn]] inline void abort_with(const std::exception& error) noexcept {
  std::fprintf(stderr, "pamkit: %s\n", error.what());
  std::fflush(stderr);
  std::abort();
}
}  // namespace detail

}  // namespace pamkit

#if defined(__cpp_exceptions) || defined(_CPPUNWIND)
/// Throws `error` (a pamkit::Error); aborts with its message when exceptions are off.
#define PAMKIT_THROW(error) throw error
#else
#define PAMKIT_THROW(error) ::pamkit::detail::abort_with(error)
#endif
