// Decoder throughput of the logger's host side, as a multiple of what a serial line can carry at
// 1 Mbaud (8N1: 10 bits per byte, 100 000 bytes/s). Two streams of 16-byte frames: clean, and
// with 1 % of the frames damaged (a flipped bit) and a garbage burst every 100 frames.
// Usage: pamkit_bench_logger_decoder [megabytes=64]

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <vector>

#include "pamkit/logger/decoder.hpp"

namespace {

std::vector<std::uint8_t> make_stream(std::size_t bytes, bool faults) {
  std::mt19937 rng(1);
  std::vector<std::uint8_t> out;
  out.reserve(bytes + 1024);
  std::uint16_t seq = 0;
  std::uint32_t t = 0;
  while (out.size() < bytes) {
    pamkit_frame f{};
    f.seq = seq++;
    f.time_us = t += 10000;
    f.counts[0] = static_cast<std::uint16_t>(rng() % 16368);
    f.counts[1] = static_cast<std::uint16_t>(rng() % 16368);
    f.oversample = 16;
    std::uint8_t frame[PAMKIT_FRAME_SIZE];
    pamkit_frame_encode(&f, frame);
    if (faults && seq % 100 == 50) frame[2 + rng() % 14] ^= static_cast<std::uint8_t>(1u << (rng() % 8));
    if (faults && seq % 100 == 0) {
      for (int i = 0; i < 40; ++i) out.push_back(static_cast<std::uint8_t>(rng()));
    }
    out.insert(out.end(), frame, frame + PAMKIT_FRAME_SIZE);
  }
  return out;
}

double run(const std::vector<std::uint8_t>& stream, std::uint64_t& frames) {
  using clock = std::chrono::steady_clock;
  pamkit::logger::Decoder decoder;
  std::uint64_t checksum = 0;
  const auto start = clock::now();
  // 4096-byte reads, as the Reader does
  for (std::size_t at = 0; at < stream.size(); at += 4096) {
    decoder.feed(
        stream.data() + at, std::min<std::size_t>(4096, stream.size() - at),
        [&](const pamkit::logger::Sample& s) { checksum += s.frame.counts[0]; }, [](const pamkit::logger::Banner&) {});
  }
  const double seconds = std::chrono::duration<double>(clock::now() - start).count();
  frames = decoder.stats().frames;
  if (checksum == 0) std::puts("");  // keep the work observable
  return seconds;
}

}  // namespace

int main(int argc, char** argv) {
  const std::size_t megabytes = argc > 1 ? std::strtoul(argv[1], nullptr, 10) : 64;
  const double line_bytes_per_s = 1e6 / 10.0;  // 1 Mbaud, 8N1
  std::printf("decoder throughput over %zu MB, 4096-byte reads; line rate at 1 Mbaud = %.0f bytes/s\n", megabytes,
              line_bytes_per_s);
  for (bool faults : {false, true}) {
    const auto stream = make_stream(megabytes << 20, faults);
    std::uint64_t frames = 0;
    double best = 1e30;
    for (int repeat = 0; repeat < 3; ++repeat) best = std::min(best, run(stream, frames));
    const double rate = stream.size() / best;
    std::printf("%-34s %8.1f MB/s  %10.3g frames/s  = %8.0f x the 1 Mbaud line rate (best of 3)\n",
                faults ? "1 % flipped frames + garbage bursts:" : "clean stream:", rate / 1e6, frames / best,
                rate / line_bytes_per_s);
  }
  return 0;
}
