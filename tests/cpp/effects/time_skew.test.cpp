// time_skew: the channel is the truth shifted in time, interpolated between samples.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include <catch2/catch.hpp>

#include "approx.hpp"
#include "effect_test_support.hpp"

using namespace pamkit_test;

TEST_CASE("time_skew: the channel is the truth shifted by the offset", "[effects][time_skew]") {
  SECTION("an offset between samples: the truth interpolated at t - offset, within the interpolation error") {
    const double dt = 0.1;
    const Measurement truth = synthetic(201, dt, [](double t) { return std::sin(t); });
    Measurement m = truth;
    effect("time_skew:channel=temperature_K,offset_s=0.35")->apply_to_measurement(m);
    for (std::size_t k = 0; k < m.time_s.size(); ++k) {
      const double t = m.time_s[k];
      INFO("t = " << t << " s");
      if (t < 0.35) {
        CHECK(m.temperature_K[k] == truth.temperature_K.front());  // before the record: held at its start
      } else {
        // Linear interpolation of sin errs by at most dt^2/8 max|sin''| = 1.25e-3.
        CHECK(std::abs(m.temperature_K[k] - std::sin(t - 0.35)) <= dt * dt / 8.0);
      }
    }
    CHECK(identical(m.gauge_pressure_Pa, truth.gauge_pressure_Pa));
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
      CHECK_REL(behind.gauge_pressure_Pa[k], truth.gauge_pressure_Pa[k >= 10 ? k - 10 : 0], 1e-12);
      CHECK_REL(ahead.gauge_pressure_Pa[k], truth.gauge_pressure_Pa[k + 10 < n ? k + 10 : n - 1], 1e-12);
    }
    CHECK(identical(behind.force_N, truth.force_N));
    CHECK(identical(behind.temperature_K, truth.temperature_K));
  }

  SECTION("uneven samples, either way: a channel linear in time is read exactly, held at the ends") {
    Measurement m;
    double t = 0.0;
    for (std::size_t k = 0; k < 400; ++k) {  // uneven steps of 0.01-0.3 s
      m.time_s.push_back(t);
      t += 0.01 + 0.29 * std::abs(std::sin(1.7 * static_cast<double>(k * k)));
    }
    for (const double offset : {0.37, -2.9, 12.0}) {
      Measurement read = m;
      read.force_N.clear();
      for (const double time : m.time_s) read.force_N.push_back(3.0 * time + 1.0);
      effect("time_skew:channel=force_N,offset_s=" + std::to_string(offset))->apply_to_measurement(read);
      const double first = m.time_s.front(), last = m.time_s.back();
      for (std::size_t k = 0; k < m.time_s.size(); ++k) {
        const double when = std::clamp(m.time_s[k] - offset, first, last);
        INFO("offset " << offset << " s, t = " << m.time_s[k] << " s");
        CHECK(std::abs(read.force_N[k] - (3.0 * when + 1.0)) <= 1e-12 * (3.0 * last + 1.0));
      }
    }
  }
}
