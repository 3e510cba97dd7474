// A controller-style query: what force does the muscle exert at this length and pressure?
// A device controller would call this in its loop with the measured pressure and the length
// from its encoder. The muscle comes from a muscle-parameters file (pamkit/io/params_file.hpp):
// the one beside this example (PAM 2 of the thesis), or the file given as the first argument,
// e.g. one that `pamkit diagnose EXP.toml --params-out CALIBRATED.toml` calibrated. Built
// against the installed package's header-only targets (find_package(pamkit COMPONENTS params)):
// no compiled pamkit, no SUNDIALS.

#include <cmath>
#include <cstdio>
#include <string>

#include <pamkit/io/params_file.hpp>
#include <pamkit/muscle/force.hpp>

int main(int argc, char** argv) {
  const std::string path = argc > 1 ? argv[1] : PAMKIT_EXAMPLE_PARAMS;
  pamkit::MuscleParams params;
  try {
    params = pamkit::read_muscle_params(path);
  } catch (const pamkit::Error& error) {
    std::fprintf(stderr, "%s\n", error.what());  // names the file, line, column and key
    return 1;
  }
  const pamkit::BraidGeometry geometry(params.build);
  const double atmosphere_Pa = params.gas.atmospheric_pressure_Pa;

  std::printf("muscle from %s\n", path.c_str());
  std::printf("%10s %14s %10s %12s\n", "length_m", "pressure_kPa", "force_N", "braid_deg");
  for (double gauge_kPa : {138.0, 207.0, 276.0}) {
    for (double length_m : {0.17, 0.19, 0.21}) {
      const pamkit::MuscleShape shape = geometry.shape(length_m);
      const pamkit::MuscleForces force =
          pamkit::muscle_forces(geometry, shape, params.bladder, params.friction, atmosphere_Pa + gauge_kPa * 1e3,
                                atmosphere_Pa, /*velocity=*/0.0);
      std::printf("%10.3f %14.1f %10.1f %12.2f\n", length_m, gauge_kPa, force.total,
                  shape.braid_angle * 180.0 / 3.14159265358979);
      if (!std::isfinite(force.total)) return 1;
    }
  }
  return 0;
}
