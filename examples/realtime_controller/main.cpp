// A controller's use of the muscle's force: one RealtimeMuscle built before the loop, one
// force() call per 1 kHz sample with the length from the encoder and the measured gauge
// pressure. Built with -fno-exceptions against pamkit::muscle alone (find_package(pamkit
// COMPONENTS muscle)); here the "sensors" are a 2 s sweep and the loop does not sleep.

#include <cmath>
#include <cstdio>

#include <pamkit/muscle/realtime.hpp>

int main() {
  pamkit::MuscleParams params;                  // PAM 2 of the thesis (tables 3.4, C.4)
  params.extensions.slack_band_N = 1.0;         // the braid cannot push
  const pamkit::RealtimeMuscle muscle(params);  // validates; outside the loop

  const double period_s = 1e-3;                     // 1 kHz
  const double omega_rad_per_s = 3.14159265358979;  // a 0.5 Hz stroke of +-15 mm
  int failures = 0;
  for (int k = 0; k < 2000; ++k) {
    const double t = k * period_s;
    const double length_m = 0.19 + 0.015 * std::sin(omega_rad_per_s * t);  // encoder
    const double velocity_m_per_s = 0.015 * omega_rad_per_s * std::cos(omega_rad_per_s * t);
    const double gauge_Pa = 100e3 + 100e3 * t;  // pressure transducer
    const pamkit::RealtimeForce f = muscle.force(length_m, gauge_Pa, velocity_m_per_s);
    if (f.status != pamkit::ForceStatus::ok || !std::isfinite(f.force_N)) ++failures;
    if (k % 250 == 0)
      std::printf("t = %5.3f s  L = %.4f m  p = %6.1f kPa  F = %7.2f N\n", t, length_m, gauge_Pa * 1e-3, f.force_N);
  }
  // A length past the braid's range is a status, not an exception.
  const pamkit::RealtimeForce beyond = muscle.force(muscle.max_length_m() + 0.01, 200e3, 0.0);
  std::printf("L = %.4f m (max %.4f m): status too_long = %d, F = %g N\n", muscle.max_length_m() + 0.01,
              muscle.max_length_m(), beyond.status == pamkit::ForceStatus::too_long, beyond.force_N);
  if (beyond.status != pamkit::ForceStatus::too_long) ++failures;
  return failures == 0 ? 0 : 1;
}
