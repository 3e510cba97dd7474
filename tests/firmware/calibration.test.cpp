// The logger's calibration: appendix B's linear fit of the pressure transducer (0-80 psi in
// 10 psi steps) and the TMP36's 10 mV/degC with 500 mV offset.

#include <vector>

#include <catch2/catch.hpp>

#include "pamkit/error.hpp"
#include "pamkit/logger/calibration.hpp"

using namespace pamkit::logger;

TEST_CASE("the pressure fit recovers a line through the appendix B points", "[firmware][calibration]") {
  // A transducer giving 0.5 V at 0 psi and 4.5 V at 80 psi (0.05 V/psi), read with +-2 mV errors.
  std::vector<double> psi, volts;
  const double errors[] = {0.002, -0.001, 0.0, 0.001, -0.002, 0.002, -0.001, 0.0, 0.001};
  for (int i = 0; i <= 8; ++i) {
    psi.push_back(10.0 * i);
    volts.push_back(0.5 + 0.05 * 10.0 * i + errors[i]);
  }
  const PressureFit fit = fit_pressure(psi, volts);
  // exact line: kPa = (V - 0.5) / 0.05 * 6.894757 -> slope 137.895 kPa/V, offset -68.948 kPa;
  // +-2 mV at 137.9 kPa/V moves the fit by well under 0.3 kPa.
  CHECK(fit.kPa_per_V == Approx(20.0 * kKilopascalPerPsi).epsilon(2e-3));
  CHECK(fit.offset_kPa == Approx(-10.0 * kKilopascalPerPsi).margin(0.3));
  CHECK(fit.max_residual_kPa < 0.002 * 137.9 * 2);
  LoggerCalibration c;
  c.pressure_kPa_per_V = fit.kPa_per_V;
  c.pressure_offset_kPa = fit.offset_kPa;
  CHECK(c.pressure_kPa(2.5) == Approx(40.0 * kKilopascalPerPsi).margin(0.3));
}

TEST_CASE("TMP36: 750 mV is 25 degC, 500 mV is 0 degC - counts to volts use 1024 steps", "[firmware][calibration]") {
  const LoggerCalibration c;
  CHECK(c.temperature_C(0.750) == Approx(25.0).epsilon(1e-12));
  CHECK(c.temperature_C(0.500) == Approx(0.0).margin(1e-12));
  CHECK(c.volts(1024.0) == Approx(5.0).epsilon(1e-12));
  CHECK(c.volts(153.6) == Approx(0.75).epsilon(1e-12));
}

TEST_CASE("a calibration that cannot be used says why", "[firmware][calibration]") {
  CHECK_THROWS_AS(fit_pressure({0, 10}, {0.5}), pamkit::InvalidInput);
  CHECK_THROWS_AS(fit_pressure({0}, {0.5}), pamkit::InvalidInput);
  CHECK_THROWS_WITH(fit_pressure({0, 10, 20}, {0, 0, 0}), Catch::Contains("were they filled in"));
  LoggerCalibration c;
  c.adc_reference_V = 12;
  CHECK_THROWS_WITH(c.validate(), Catch::Contains("LoggerCalibration.adc_reference_V"));
}
