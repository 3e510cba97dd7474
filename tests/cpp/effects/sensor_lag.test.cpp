// sensor_lag against a first-order lag's analytic answers: the ramp response and the attenuation
// and delay of a sine; it leaves the other channels alone.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include <catch2/catch.hpp>

#include "approx.hpp"
#include "effect_test_support.hpp"

namespace {

using namespace pamkit_test;

const double kPi = std::acos(-1.0);

}  // namespace

TEST_CASE("sensor_lag: the response to a ramp is the analytic one, and lags by tau once settled",
          "[effects][sensor_lag]") {
  const double tau = 5.0;
  const double rate = 0.05;  // [K/s]
  const Measurement truth = synthetic(601, 0.1, [&](double t) { return 20.0 + rate * t; });
  Measurement m = truth;
  effect("sensor_lag:channel=temperature_K,time_constant_s=5")->apply_to_measurement(m);

  for (std::size_t k = 0; k < m.time_s.size(); ++k) {
    const double t = m.time_s[k];
    // tau dy/dt = x - y, y(0) = x(0): y = 20 + a (t - tau) + a tau exp(-t/tau). The lag is exact
    // for inputs linear between samples, so only rounding separates the two.
    INFO("t = " << t << " s");
    CHECK(std::abs(m.temperature_K[k] - (20.0 + rate * (t - tau) + rate * tau * std::exp(-t / tau))) < 1e-12);
  }
  // Settled (t = 60 s = 12 tau): the reading is the truth of tau ago, to a tau exp(-12) = 6e-6 s.
  const double lag = (truth.temperature_K.back() - m.temperature_K.back()) / rate;
  CHECK_REL(lag, tau, 1e-5);
  CHECK(identical(m.force_N, truth.force_N));
  CHECK(identical(m.gauge_pressure_Pa, truth.gauge_pressure_Pa));
  CHECK(identical(m.elongation_m, truth.elongation_m));
}

TEST_CASE("sensor_lag: a periodic swing is attenuated by 1/sqrt(1 + (w tau)^2) and delayed by atan(w tau)/w",
          "[effects][sensor_lag]") {
  const double tau = 5.0;
  const double period = 20.0;
  const double w = 2.0 * kPi / period;
  const double dt = 0.01;
  // Ten periods; the start's transient has decayed by exp(-180 / 5) by the last one.
  Measurement m = synthetic(20001, dt, [&](double t) { return std::sin(w * t); });
  effect("sensor_lag:time_constant_s=5")->apply_to_measurement(m);  // temperature_K is the default channel

  const std::size_t last_period = m.time_s.size() - static_cast<std::size_t>(period / dt) - 1;
  std::size_t peak = last_period;
  double low = m.temperature_K[last_period];
  for (std::size_t k = last_period; k < m.time_s.size(); ++k) {
    if (m.temperature_K[k] > m.temperature_K[peak]) peak = k;
    low = std::min(low, m.temperature_K[k]);
  }
  // Errors: the sine taken as linear between samples (<= (w dt)^2 / 8 = 1.2e-6) and the sampled
  // extremes (the same order): 1e-5 allows for both.
  CHECK_REL(0.5 * (m.temperature_K[peak] - low), 1.0 / std::sqrt(1.0 + w * w * tau * tau), 1e-5);
  // The input peaks at t = period/4 (mod period); the reading atan(w tau)/w later, to a sample.
  const double delay = std::fmod(m.time_s[peak] - 0.25 * period, period);
  CHECK(std::abs(delay - std::atan(w * tau) / w) <= dt);
}

TEST_CASE("sensor_lag: acts on the channel it names and on no other", "[effects][sensor_lag]") {
  const ElongationTrajectory crosshead = thesis_protocol(0.05, 2.5e-3, 1, 0.1);
  const Measurement truth = measure(MuscleParams(), table_c2_90(), crosshead, {});
  const Measurement lagged =
      measure(MuscleParams(), table_c2_90(), crosshead, {"sensor_lag:channel=gauge_pressure_Pa,time_constant_s=2"});
  CHECK(identical(lagged.force_N, truth.force_N));
  CHECK(identical(lagged.temperature_K, truth.temperature_K));
  CHECK_FALSE(identical(lagged.gauge_pressure_Pa, truth.gauge_pressure_Pa));
  // A lagging reading is attenuated: its peak falls short of the true peak.
  const std::size_t top = tops(truth.elongation_m).front();
  CHECK(lagged.gauge_pressure_Pa[top] < truth.gauge_pressure_Pa[top]);
}
