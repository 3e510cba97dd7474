// libFuzzer target for the logger's stream decoder (built with clang, ASan and UBSan; run for a
// bounded time by ctest). Two modes, chosen by the first input byte:
//
//  raw     the input is the byte stream. The decoder must not crash, must account for every
//          byte exactly once (frames + banners + skipped + pending = fed), and must decode the
//          same frames whatever the chunking.
//  script  the input is a recipe: intact frames, banners, garbage, flipped bits, dropped bytes,
//          cuts. Every frame emitted intact and not overlapped by damage must come out, in order.

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "pamkit/logger/decoder.hpp"

using namespace pamkit::logger;

namespace {

void require(bool condition, const char* what) {
  if (!condition) {
    std::fprintf(stderr, "decoder invariant violated: %s\n", what);
    std::abort();
  }
}

struct Run {
  std::vector<std::pair<std::uint32_t, std::uint16_t>> frames;  // (boot, seq)
  std::size_t banner_bytes = 0;
};

Run decode(Decoder& d, const std::uint8_t* data, std::size_t size, std::size_t chunk) {
  Run run;
  for (std::size_t at = 0; at < size; at += chunk) {
    d.feed(
        data + at, std::min(chunk, size - at),
        [&](const Sample& s) {
          require(s.frame.oversample >= 1 && s.frame.oversample <= PAMKIT_OVERSAMPLE_MAX, "oversample range");
          run.frames.emplace_back(s.boot, s.frame.seq);
        },
        [&](const Banner& b) { run.banner_bytes += b.line.size() + 2; });
  }
  return run;
}

void check_ledger(const Decoder& d, const Run& run) {
  const DecoderStats& s = d.stats();
  require(s.frames * PAMKIT_FRAME_SIZE + run.banner_bytes + s.skipped_bytes + d.pending() == s.bytes,
          "every byte accounted for once");
  require(s.frames >= run.frames.size(), "frames counted");
}

void raw_mode(const std::uint8_t* data, std::size_t size) {
  Decoder whole, pieces;
  const Run a = decode(whole, data, size, size ? size : 1);
  const Run b = decode(pieces, data, size, 1 + (size % 7));
  check_ledger(whole, a);
  check_ledger(pieces, b);
  require(a.frames == b.frames, "same frames whatever the chunking");
  require(whole.stats().skipped_bytes == pieces.stats().skipped_bytes, "same skipped bytes whatever the chunking");
  whole.end_of_stream();
  require(whole.pending() == 0, "nothing pending after end of stream");
}

std::string banner() {
  char line[PAMKIT_BANNER_MAX];
  const int n = std::snprintf(line, sizeof line, PAMKIT_BANNER_FORMAT, PAMKIT_FIRMWARE_VERSION,
                              static_cast<unsigned>(PAMKIT_FRAME_VERSION), 100UL, 10000UL, 16u, 115200UL, 5000u);
  std::snprintf(line + n, sizeof line - n, " crc=%04X\r\n",
                pamkit_crc16(reinterpret_cast<const std::uint8_t*>(line), static_cast<std::size_t>(n)));
  return line;
}

void script_mode(const std::uint8_t* data, std::size_t size) {
  std::vector<std::uint8_t> stream;
  std::vector<std::uint16_t> expected;  // seqs of frames that must come out (one boot: no banners mid-way)
  std::vector<std::size_t> starts;      // where those frames start in the stream
  std::uint16_t seq = 0;
  std::uint32_t time_us = 0;
  // Damage only ever touches the bytes of the frame it is applied to or inserts garbage between
  // frames, so every other frame stays intact and must be decoded.
  for (std::size_t i = 0; i + 1 < size; i += 2) {
    const std::uint8_t op = data[i] % 5, arg = data[i + 1];
    pamkit_frame f{};
    f.seq = seq++;
    f.time_us = time_us;
    time_us += 1000u + arg;
    f.counts[0] = static_cast<std::uint16_t>(arg * 97u);
    f.counts[1] = static_cast<std::uint16_t>(arg * 13u);
    f.oversample = static_cast<std::uint8_t>(1 + arg % PAMKIT_OVERSAMPLE_MAX);
    std::uint8_t bytes[PAMKIT_FRAME_SIZE];
    pamkit_frame_encode(&f, bytes);
    switch (op) {
      case 0:
      case 1:  // intact
        starts.push_back(stream.size());
        stream.insert(stream.end(), bytes, bytes + PAMKIT_FRAME_SIZE);
        expected.push_back(f.seq);
        break;
      case 2:  // a flipped bit
        bytes[(arg >> 3) % PAMKIT_FRAME_SIZE] ^= static_cast<std::uint8_t>(1u << (arg & 7));
        stream.insert(stream.end(), bytes, bytes + PAMKIT_FRAME_SIZE);
        break;
      case 3:  // a dropped byte
        for (unsigned k = 0; k < PAMKIT_FRAME_SIZE; ++k)
          if (k != arg % PAMKIT_FRAME_SIZE) stream.push_back(bytes[k]);
        break;
      case 4: {  // garbage: taken from the input itself (so sync pairs, '#' and CRLF appear), then the frame
        const std::size_t n = std::min<std::size_t>(arg % 40, size - i);
        stream.insert(stream.end(), data + i, data + i + n);
        starts.push_back(stream.size());
        stream.insert(stream.end(), bytes, bytes + PAMKIT_FRAME_SIZE);
        expected.push_back(f.seq);
        break;
      }
    }
  }
  Decoder d;
  const Run run = decode(d, stream.data(), stream.size(), 1 + size % 23);
  check_ledger(d, run);
  // Damage can forge a frame: 16 bytes that pass the CRC by chance (2^-16 per candidate, and a
  // fuzzer can aim for it). No CRC framing can then promise the intact frame it overlaps, so the
  // oracle only holds when no forgery overlaps an intact frame. Forged frames elsewhere are extra
  // output the check tolerates; every expected frame must be there, in order.
  std::size_t next_start = 0;
  for (std::size_t p = 0; p + PAMKIT_FRAME_SIZE <= stream.size(); ++p) {
    while (next_start < starts.size() && starts[next_start] + PAMKIT_FRAME_SIZE <= p) ++next_start;
    pamkit_frame forged;
    if (pamkit_frame_decode(stream.data() + p, &forged) && !(next_start < starts.size() && starts[next_start] == p)) {
      const bool overlaps = (next_start < starts.size() && starts[next_start] < p + PAMKIT_FRAME_SIZE) ||
                            (next_start + 1 < starts.size() && starts[next_start + 1] < p + PAMKIT_FRAME_SIZE);
      if (overlaps) return;
    }
  }
  std::size_t found = 0;
  for (const auto& [boot, s] : run.frames) {
    if (found < expected.size() && s == expected[found]) ++found;
  }
  require(found == expected.size(), "every intact frame decoded, in order");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  if (data[0] & 1) {
    raw_mode(data + 1, size - 1);
  } else {
    script_mode(data + 1, size - 1);
  }
  static const std::string line = banner();  // keep the banner path exercised with a valid line
  Decoder d;
  Run run = decode(d, reinterpret_cast<const std::uint8_t*>(line.data()), line.size(), 1 + size % 5);
  require(d.stats().banners == 1 && run.banner_bytes == line.size(), "the sketch's banner parses");
  return 0;
}
