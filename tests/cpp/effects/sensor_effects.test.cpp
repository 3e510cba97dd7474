// The measurement-chain effects against their analytic answers: sensor_lag (a first-order lag:
// the ramp response and the attenuation of a sine), time_skew (the channel is the truth shifted
// in time), sensor_offset (affine, exactly). Each leaves the other channels alone.

#include <cmath>
#include <cstddef>
#include <vector>

#include <catch2/catch.hpp>

#include "approx.hpp"
#include "effect_test_support.hpp"

namespace {

using namespace pamkit_test;

const double kPi = std::acos(-1.0);

// A measurement with `n` samples `dt` apart and temperature_C = f(t); other channels filled with
// recognisable values so that any change to them shows.
template <class F>
Measurement synthetic(std::size_t n, double dt, F f) {
  Measurement m;
  for (std::size_t k = 0; k < n; ++k) {
    const double t = static_cast<double>(k) * dt;
    m.time_s.push_back(t);
    m.elongation_m.push_back(1e-3 * t);
    m.force_N.push_back(100.0 + t);
    m.pressure_kPa.push_back(200.0 - t);
    m.temperature_C.push_back(f(t));
  }
  return m;
}

}  // namespace

TEST_CASE("sensor_lag: the response to a ramp is the analytic one, and lags by tau once settled",
          "[effects][sensor_lag]") {
  const double tau = 5.0;
  const double rate = 0.05;  // [degC/s]
  const Measurement truth = synthetic(601, 0.1, [&](double t) { return 20.0 + rate * t; });
  Measurement m = truth;
  effect("sensor_lag:channel=temperature_C,time_constant_s=5")->apply_to_measurement(m);

  for (std::size_t k = 0; k < m.time_s.size(); ++k) {
    const double t = m.time_s[k];
    // tau dy/dt = x - y, y(0) = x(0): y = 20 + a (t - tau) + a tau exp(-t/tau). The lag is exact
    // for inputs linear between samples, so only rounding separates the two.
    INFO("t = " << t << " s");
    CHECK(std::abs(m.temperature_C[k] - (20.0 + rate * (t - tau) + rate * tau * std::exp(-t / tau))) < 1e-12);
  }
  // Settled (t = 60 s = 12 tau): the reading is the truth of tau ago, to a tau exp(-12) = 6e-6 s.
  const double lag = (truth.temperature_C.back() - m.temperature_C.back()) / rate;
  CHECK_REL(lag, tau, 1e-5);
  CHECK(identical(m.force_N, truth.force_N));
  CHECK(identical(m.pressure_kPa, truth.pressure_kPa));
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
  effect("sensor_lag:time_constant_s=5")->apply_to_measurement(m);  // temperature_C is the default channel

  const std::size_t last_period = m.time_s.size() - static_cast<std::size_t>(period / dt) - 1;
  std::size_t peak = last_period;
  double low = m.temperature_C[last_period];
  for (std::size_t k = last_period; k < m.time_s.size(); ++k) {
    if (m.temperature_C[k] > m.temperature_C[peak]) peak = k;
    low = std::min(low, m.temperature_C[k]);
  }
  // Errors: the sine taken as linear between samples (<= (w dt)^2 / 8 = 1.2e-6) and the sampled
  // extremes (the same order): 1e-5 allows for both.
  CHECK_REL(0.5 * (m.temperature_C[peak] - low), 1.0 / std::sqrt(1.0 + w * w * tau * tau), 1e-5);
  // The input peaks at t = period/4 (mod period); the reading atan(w tau)/w later, to a sample.
  const double delay = std::fmod(m.time_s[peak] - 0.25 * period, period);
  CHECK(std::abs(delay - std::atan(w * tau) / w) <= dt);
}

TEST_CASE("sensor_lag: acts on the channel it names and on no other", "[effects][sensor_lag]") {
  const ElongationTrajectory crosshead = thesis_protocol(0.05, 2.5e-3, 1, 0.1);
  const Measurement truth = measure(MuscleParams(), table_c2_90(), crosshead, {});
  const Measurement lagged =
      measure(MuscleParams(), table_c2_90(), crosshead, {"sensor_lag:channel=pressure_kPa,time_constant_s=2"});
  CHECK(identical(lagged.force_N, truth.force_N));
  CHECK(identical(lagged.temperature_C, truth.temperature_C));
  CHECK_FALSE(identical(lagged.pressure_kPa, truth.pressure_kPa));
  // A lagging reading is attenuated: its peak falls short of the true peak.
  const std::size_t top = tops(truth.elongation_m).front();
  CHECK(lagged.pressure_kPa[top] < truth.pressure_kPa[top]);
}

TEST_CASE("time_skew: the channel is the truth shifted by the offset", "[effects][time_skew]") {
  SECTION("an offset between samples: the truth interpolated at t - offset, within the interpolation error") {
    const double dt = 0.1;
    const Measurement truth = synthetic(201, dt, [](double t) { return std::sin(t); });
    Measurement m = truth;
    effect("time_skew:channel=temperature_C,offset_s=0.35")->apply_to_measurement(m);
    for (std::size_t k = 0; k < m.time_s.size(); ++k) {
      const double t = m.time_s[k];
      INFO("t = " << t << " s");
      if (t < 0.35) {
        CHECK(m.temperature_C[k] == truth.temperature_C.front());  // before the record: held at its start
      } else {
        // Linear interpolation of sin errs by at most dt^2/8 max|sin''| = 1.25e-3.
        CHECK(std::abs(m.temperature_C[k] - std::sin(t - 0.35)) <= dt * dt / 8.0);
      }
    }
    CHECK(identical(m.pressure_kPa, truth.pressure_kPa));
    CHECK(identical(m.force_N, truth.force_N));
  }

  SECTION("a whole number of samples, either way, on a simulated pressure") {
    const ElongationTrajectory crosshead = thesis_protocol(0.05, 2.5e-3, 1, 0.1);
    const Measurement truth = measure(MuscleParams(), table_c2_90(), crosshead, {});
    const Measurement behind = measure(MuscleParams(), table_c2_90(), crosshead, {"time_skew:offset_s=1"});
    const Measurement ahead = measure(MuscleParams(), table_c2_90(), crosshead, {"time_skew:offset_s=-1"});
    const std::size_t n = truth.time_s.size();
    for (std::size_t k = 0; k < n; ++k) {
      INFO("t = " << truth.time_s[k] << " s");
      // 1 s is 10 samples; the times are multiples of 0.1 s only to rounding, hence CHECK_REL.
      CHECK_REL(behind.pressure_kPa[k], truth.pressure_kPa[k >= 10 ? k - 10 : 0], 1e-12);
      CHECK_REL(ahead.pressure_kPa[k], truth.pressure_kPa[k + 10 < n ? k + 10 : n - 1], 1e-12);
    }
    CHECK(identical(behind.force_N, truth.force_N));
    CHECK(identical(behind.temperature_C, truth.temperature_C));
  }
}

TEST_CASE("sensor_offset: the pressure reads gain x p + offset exactly", "[effects][sensor_offset]") {
  const ElongationTrajectory crosshead = thesis_protocol(0.05, 2.5e-3, 1, 0.1);
  const Measurement truth = measure(MuscleParams(), table_c2_90(), crosshead, {});
  const Measurement m = measure(MuscleParams(), table_c2_90(), crosshead, {"sensor_offset:offset_kPa=-7.5,gain=1.04"});
  for (std::size_t k = 0; k < truth.time_s.size(); ++k) {
    INFO("sample " << k);
    CHECK(m.pressure_kPa[k] == 1.04 * truth.pressure_kPa[k] + -7.5);
  }
  CHECK(identical(m.force_N, truth.force_N));
  CHECK(identical(m.temperature_C, truth.temperature_C));
}
