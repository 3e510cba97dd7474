// pamkit_bench_realtime: the cost of one RealtimeMuscle::force call (muscle/realtime.hpp) against
// a 1 kHz control period, the heap allocations its calls make (expected 0), and the same for
// the two-call path it replaces (BraidGeometry::shape, then muscle_forces). Built with
// -fno-exceptions against pamkit::muscle alone, as a controller would be. Prints one JSON object;
// exits 1 if the real-time calls allocated. See bench/README.md.
//
// Usage: pamkit_bench_realtime [--calls N] [--batches B]

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <new>
#include <vector>

#include "allocation_counter.hpp"
#include "pamkit/muscle/realtime.hpp"

namespace {

using allocation_counter::allocations;

struct Options {
  long calls = 200000;  ///< calls per timed batch
  int batches = 21;     ///< timed batches of each path, taking turns; the median is reported
};

/// `--name N` with N a positive integer, or a message and false.
bool parse(int argc, char** argv, Options& o) {
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--help") == 0 || std::strcmp(argv[i], "-h") == 0) return false;
    if (i + 1 >= argc) return false;
    char* end = nullptr;
    const long value = std::strtol(argv[i + 1], &end, 10);
    if (end == argv[i + 1] || *end != '\0' || value < 1) return false;
    if (std::strcmp(argv[i], "--calls") == 0) o.calls = value;
    else if (std::strcmp(argv[i], "--batches") == 0) o.batches = static_cast<int>(value);
    else return false;
    ++i;
  }
  return true;
}

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 == 1 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

/// One second of a controller's samples at 1 kHz: a 0.5 Hz stroke of +-15 mm about 0.19 m
/// while the pressure ramps from 100 to 300 kPa, so the braid's Newton solve starts from a
/// different length at every call.
struct Samples {
  std::vector<double> length_m, gauge_Pa, velocity_m_per_s;
};
Samples controller_samples() {
  Samples s;
  const double omega = 3.14159265358979;  // rad/s
  for (int k = 0; k < 1000; ++k) {
    const double t = 1e-3 * k;
    s.length_m.push_back(0.19 + 0.015 * std::sin(omega * t));
    s.velocity_m_per_s.push_back(0.015 * omega * std::cos(omega * t));
    s.gauge_Pa.push_back(100e3 + 200e3 * t);
  }
  return s;
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  if (!parse(argc, argv, o)) {
    std::puts("pamkit_bench_realtime [--calls N] [--batches B]\nPrints one JSON object; times in seconds.");
    return 2;
  }
  const pamkit::MuscleParams params;  // PAM 2 of the thesis
  const pamkit::RealtimeMuscle muscle(params);
  const pamkit::BraidGeometry geometry(params.build);
  const double atmosphere = params.gas.atmospheric_pressure_Pa;
  const Samples s = controller_samples();
  const std::size_t n = s.length_m.size();
  std::vector<double> realtime_s, two_call_s;
  realtime_s.reserve(static_cast<std::size_t>(o.batches));
  two_call_s.reserve(static_cast<std::size_t>(o.batches));

  long realtime_allocations = 0;
  long two_call_allocations = 0;
  long not_ok = 0;
  double sink = 0.0;
  for (int b = 0; b < o.batches; ++b) {
    long before = allocations.load();
    auto start = std::chrono::steady_clock::now();
    for (long i = 0; i < o.calls; ++i) {
      const std::size_t k = static_cast<std::size_t>(i) % n;
      const pamkit::RealtimeForce f = muscle.force(s.length_m[k], s.gauge_Pa[k], s.velocity_m_per_s[k]);
      sink += f.force_N;
      not_ok += f.status != pamkit::ForceStatus::ok;
    }
    realtime_s.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() /
                         static_cast<double>(o.calls));
    realtime_allocations += allocations.load() - before;

    before = allocations.load();
    start = std::chrono::steady_clock::now();
    for (long i = 0; i < o.calls; ++i) {
      const std::size_t k = static_cast<std::size_t>(i) % n;
      const pamkit::MuscleShape shape = geometry.shape(s.length_m[k]);
      sink += pamkit::muscle_forces(geometry, shape, params.bladder, params.friction, atmosphere + s.gauge_Pa[k],
                                    atmosphere, s.velocity_m_per_s[k])
                  .total;
    }
    two_call_s.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() /
                         static_cast<double>(o.calls));
    two_call_allocations += allocations.load() - before;
  }

  const double realtime = median(realtime_s);
  const double two_call = median(two_call_s);
  const double period_s = 1e-3;  // 1 kHz control loop
  std::printf(
      "{\"realtime_call_median_s\": %.4g, \"two_call_median_s\": %.4g, \"ratio_realtime_over_two_call\": %.3f, "
      "\"fraction_of_1kHz_period\": %.3g, \"calls_per_1kHz_period\": %.0f, \"realtime_allocations\": %ld, "
      "\"two_call_allocations\": %ld, \"calls_per_path\": %ld, \"batches\": %d, \"not_ok\": %ld, \"sink\": %.6g}\n",
      realtime, two_call, realtime / two_call, realtime / period_s, period_s / realtime, realtime_allocations,
      two_call_allocations, o.calls * o.batches, o.batches, not_ok, sink);
  return realtime_allocations == 0 && not_ok == 0 ? 0 : 1;
}
