// A controller-style query: what force does the muscle exert at this length and pressure?
// A device controller would call this in its loop with the measured pressure and the length
// from its encoder. Built against the installed package (find_package(pamkit)).

#include <cmath>
#include <cstdio>

#include <pamkit/muscle/force.hpp>

int main() {
  const pamkit::MuscleBuild build;  // PAM 2 of the thesis (table 3.4, C.4)
  const pamkit::BraidGeometry geometry(build);
  const pamkit::BladderLaw bladder = pamkit::BladderLaw::thesis();
  const pamkit::FrictionParams friction;
  const double atmosphere_Pa = 101e3;

  std::printf("%10s %14s %10s %12s\n", "length_m", "pressure_kPa", "force_N", "braid_deg");
  for (double gauge_kPa : {138.0, 207.0, 276.0}) {
    for (double length_m : {0.17, 0.19, 0.21}) {
      const pamkit::MuscleShape shape = geometry.shape(length_m);
      const pamkit::MuscleForces force = pamkit::muscle_forces(
          geometry, shape, bladder, friction, atmosphere_Pa + gauge_kPa * 1e3, atmosphere_Pa, /*velocity=*/0.0);
      std::printf("%10.3f %14.1f %10.1f %12.2f\n", length_m, gauge_kPa, force.total,
                  shape.braid_angle * 180.0 / 3.14159265358979);
      if (!std::isfinite(force.total)) return 1;
    }
  }
  return 0;
}
