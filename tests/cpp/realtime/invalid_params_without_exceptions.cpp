// Built with -fno-exceptions against pamkit::muscle: a RealtimeMuscle built from an invalid
// parameter cannot throw, so it must print the field's message and abort (PAMKIT_THROW).
// tests/expect_abort.cmake runs it and checks both.

#include <cstdio>

#include "pamkit/muscle/realtime.hpp"

int main() {
  pamkit::MuscleParams params;
  params.build.fiber_count = -3;
  const pamkit::RealtimeMuscle muscle(params);
  std::printf("constructed with fiber_count = -3: force %g N\n", muscle.force(0.19, 200e3, 0.0).force_N);
  return 0;
}
