// A bench test simulated in C++: PAM 2 of the thesis inflated freely to 207 kPa and sealed, then
// stretched by 45 mm and back ten times at 2.5 mm/s (the protocol of section 3.2.1), the gas
// exchanging heat with the wall in 5 s. Built against the installed package (find_package(pamkit
// COMPONENTS pamkit), target pamkit::pamkit: the library and its CVODES simulator).

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <pamkit/sim/simulator.hpp>
#include <pamkit/version.hpp>

int main() {
  pamkit::MuscleParams params;  // PAM 2 of the thesis (tables 3.4, C.4)
  params.gas.process = pamkit::GasProcess::heat_transfer;
  params.gas.heat_transfer_time_constant_s = 5.0;
  const pamkit::InitialState start = pamkit::inflated_and_sealed(params, 207e3);  // [Pa] gauge
  const pamkit::MuscleModel model(params, start);

  const pamkit::SimulationResult run = pamkit::Simulator().run(model, pamkit::thesis_protocol(0.045));
  const auto peak_force = std::max_element(run.force_N.begin(), run.force_N.end());
  const auto peak_pressure = std::max_element(run.gauge_pressure_Pa.begin(), run.gauge_pressure_Pa.end());
  std::printf("pamkit %s: %zu samples over %.0f s in %ld CVODES steps\n", PAMKIT_VERSION_STRING, run.time_s.size(),
              run.time_s.back(), static_cast<long>(run.statistics.steps));
  std::printf("sealed at %.4f m and %.0f kPa: peak force %.1f N, peak pressure %.1f kPa\n", start.length_m,
              start.gauge_pressure_Pa * 1e-3, *peak_force, *peak_pressure * 1e-3);
  return std::isfinite(*peak_force) && *peak_force > 0.0 ? 0 : 1;
}
