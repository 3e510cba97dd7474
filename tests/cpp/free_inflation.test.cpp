// Table 3.4: the free (zero-force) length and diameter against inflation pressure, predicted
// from the deflated build with the thesis bladder (eqs. 3.1.12-3.1.13), against the measured rows.

#include <cmath>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <vector>

#include <catch2/catch.hpp>

#include "approx.hpp"
#include "pamkit/muscle/free_inflation.hpp"

namespace {

using namespace pamkit;

constexpr double kAtmosphere = 101e3;  // Patm, table C.4

struct Row {
  double deflated_length_m;  // PAM 1: 0.223 m, PAM 2: 0.225 m (table 3.4)
  double gauge_kPa;
  double measured_length_m;
  double measured_diameter_m;
};

// Table 3.4 (thesis section 3.2.1), the inflated rows.
const std::vector<Row> kTable34 = {
    {0.223, 35, 0.185, 0.02725}, {0.223, 48, 0.181, 0.0276},  {0.223, 55, 0.180, 0.0278},
    {0.223, 69, 0.177, 0.0280},  {0.223, 83, 0.174, 0.02875}, {0.223, 104, 0.172, 0.029},
    {0.225, 138, 0.171, 0.031},  {0.225, 207, 0.167, 0.033},  {0.225, 276, 0.165, 0.033},
};

FreeInflation inflate(const Row& row, double bladder_thickness_m) {
  MuscleBuild build;  // other fields: table C.4 (the MuscleBuild defaults)
  build.length_m = row.deflated_length_m;
  build.bladder_thickness_m = bladder_thickness_m;
  return free_inflation(BraidGeometry(build), BladderLaw::thesis(), kAtmosphere, row.gauge_kPa * 1e3);
}

double percent(double predicted, double measured) { return 100.0 * (predicted - measured) / measured; }

}  // namespace

TEST_CASE("Table 3.4: free length and diameter with table C.4's 0.254 mm bladder", "[free_inflation][thesis]") {
  std::ostringstream table;
  table << "Table 3.4, free inflation (bladder 0.254 mm, table C.4) vs measured\n"
        << "| PAM | p [kPa] | L model [m] | L measured [m] | L error | D model [m] | D measured [m] | D error |\n"
        << "|---|---|---|---|---|---|---|---|\n";
  double previous_length = 1.0;
  for (const Row& row : kTable34) {
    const FreeInflation f = inflate(row, 0.254e-3);
    table << std::fixed << "| " << (row.deflated_length_m == 0.223 ? 1 : 2) << " | " << std::setprecision(0)
          << row.gauge_kPa << " | " << std::setprecision(4) << f.length_m << " | " << std::setprecision(3)
          << row.measured_length_m << " | " << std::setprecision(1) << std::showpos
          << percent(f.length_m, row.measured_length_m) << " % | " << std::noshowpos << std::setprecision(4)
          << f.diameter_m << " | " << std::setprecision(5) << row.measured_diameter_m << " | " << std::setprecision(1)
          << std::showpos << percent(f.diameter_m, row.measured_diameter_m) << " % |\n"
          << std::noshowpos;
    INFO(row.gauge_kPa << " kPa: L = " << f.length_m << " m (measured " << row.measured_length_m
                       << "), D = " << f.diameter_m << " m (measured " << row.measured_diameter_m << ")");
    CHECK(f.contracted);
    // What the model meets honestly: length within 5 % (worst -3.4 % at 138 kPa) and diameter
    // within 10 % (worst -9.3 % at 207 kPa: PAM 2's measured 33 mm is wider than the braid
    // gets before its cones flatten, 32 mm = d + 2 Lz).
    CHECK(std::abs(percent(f.length_m, row.measured_length_m)) < 5.0);
    CHECK(std::abs(percent(f.diameter_m, row.measured_diameter_m)) < 10.0);
    // More pressure, shorter muscle, within each muscle (and across, PAM 2 being only 2 mm longer).
    CHECK(f.length_m < previous_length);
    previous_length = f.length_m;
  }
  std::cout << table.str() << std::flush;
}

TEST_CASE("Table 3.4 with the measured 0.9 mm bladder: the muscle barely inflates at low pressure",
          "[free_inflation][thesis]") {
  // Section 3.1.2 measured the butyl tube at 0.9 mm. Strains count from the deflated tube as
  // in table 3.1, so the deflated 20 mm braid already holds the 15.45 mm bladder at 29 % hoop
  // strain, where eq. 3.1.13 gives 376 kPa. On a 0.9 mm wall that pushes the ends apart with
  // 51.5 N while 35 and 48 kPa pull them together with 44.6 and 61.1 N: at 35 kPa the model
  // stays at its deflated length, at 48 kPa it contracts by 1.8 %, while table 3.4 shows the
  // muscle contracted by 17-19 %. Table C.4's 0.254 mm is the thickness the thesis's model was
  // run with (docs/model.md).
  const FreeInflation lowest = inflate(kTable34[0], 0.9e-3);
  CHECK_FALSE(lowest.contracted);
  CHECK(lowest.length_m == kTable34[0].deflated_length_m);
  for (const Row& row : {kTable34[0], kTable34[1]}) {
    INFO(row.gauge_kPa << " kPa");
    CHECK(percent(inflate(row, 0.9e-3).length_m, row.measured_length_m) > 15.0);
  }
}
