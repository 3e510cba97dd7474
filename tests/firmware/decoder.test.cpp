// The frame format and the stream decoder, on byte streams built here (no simulator): every
// fault the cable can cause is detected, counted and recovered from, without losing a frame
// that arrived intact.

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "pamkit/logger/decoder.hpp"

using namespace pamkit::logger;
using Bytes = std::vector<std::uint8_t>;

namespace {

pamkit_frame make_frame(std::uint16_t seq, std::uint32_t time_us, std::uint8_t oversample = 16) {
  pamkit_frame f{};
  f.seq = seq;
  f.time_us = time_us;
  f.counts[0] = static_cast<std::uint16_t>((seq * 37u) % (1024u * oversample));
  f.counts[1] = static_cast<std::uint16_t>(150u * oversample + seq % 7u);
  f.oversample = oversample;
  f.dropped = 0;
  return f;
}

void append_frame(Bytes& out, const pamkit_frame& f) {
  std::uint8_t bytes[PAMKIT_FRAME_SIZE];
  pamkit_frame_encode(&f, bytes);
  out.insert(out.end(), bytes, bytes + PAMKIT_FRAME_SIZE);
}

// A banner exactly as the sketch prints it (same format string, same CRC).
std::string banner_line(unsigned long rate_hz = 100, unsigned oversample = 16) {
  char line[PAMKIT_BANNER_MAX];
  const int n = std::snprintf(line, sizeof line, PAMKIT_BANNER_FORMAT, PAMKIT_FIRMWARE_VERSION,
                              static_cast<unsigned>(PAMKIT_FRAME_VERSION), rate_hz, 1000000UL / rate_hz, oversample,
                              115200UL, 5000u);
  std::snprintf(line + n, sizeof line - n, " crc=%04X\r\n",
                pamkit_crc16(reinterpret_cast<const std::uint8_t*>(line), static_cast<std::size_t>(n)));
  return line;
}

void append(Bytes& out, const std::string& text) { out.insert(out.end(), text.begin(), text.end()); }

struct Collected {
  std::vector<Sample> samples;
  std::vector<Banner> banners;
};

Collected decode(Decoder& decoder, const Bytes& stream, std::size_t chunk = 0) {
  Collected out;
  const std::size_t step = chunk ? chunk : std::max<std::size_t>(stream.size(), 1);
  for (std::size_t at = 0; at < stream.size(); at += step) {
    decoder.feed(
        stream.data() + at, std::min(step, stream.size() - at), [&](const Sample& s) { out.samples.push_back(s); },
        [&](const Banner& b) { out.banners.push_back(b); });
  }
  return out;
}

std::vector<unsigned> seqs(const Collected& c) {
  std::vector<unsigned> out;
  for (const auto& s : c.samples) out.push_back(s.frame.seq);
  return out;
}

// Every byte is in a frame, a banner, the skipped count or still pending: the decoder's ledger.
void check_ledger(const Decoder& d, std::size_t banner_bytes) {
  const auto& s = d.stats();
  CHECK(s.frames * PAMKIT_FRAME_SIZE + banner_bytes + s.skipped_bytes + d.pending() == s.bytes);
}

}  // namespace

TEST_CASE("CRC-16/CCITT-FALSE has its catalogue check value", "[firmware][frame]") {
  // Catalogue of parametrised CRC algorithms (R. Williams / G. Cook): CRC-16/CCITT-FALSE,
  // check = 0x29B1 for the ASCII digits "123456789".
  const char* digits = "123456789";
  CHECK(pamkit_crc16(reinterpret_cast<const std::uint8_t*>(digits), 9) == 0x29B1);
}

TEST_CASE("a frame survives encoding and decoding, and a single flipped bit is always caught", "[firmware][frame]") {
  pamkit_frame f = make_frame(0xBEEF, 0xFEDCBA98u, 64);
  f.counts[0] = 65472;  // 64 x 1023, the largest sum
  f.dropped = 3;
  std::uint8_t bytes[PAMKIT_FRAME_SIZE];
  pamkit_frame_encode(&f, bytes);
  pamkit_frame back{};
  REQUIRE(pamkit_frame_decode(bytes, &back) == 1);
  CHECK(back.seq == f.seq);
  CHECK(back.time_us == f.time_us);
  CHECK(back.counts[0] == f.counts[0]);
  CHECK(back.counts[1] == f.counts[1]);
  CHECK(back.oversample == 64);
  CHECK(back.dropped == 3);
  for (int bit = 0; bit < PAMKIT_FRAME_SIZE * 8; ++bit) {
    std::uint8_t damaged[PAMKIT_FRAME_SIZE];
    std::memcpy(damaged, bytes, sizeof damaged);
    damaged[bit / 8] ^= static_cast<std::uint8_t>(1u << (bit % 8));
    INFO("bit " << bit);
    CHECK(pamkit_frame_decode(damaged, &back) == 0);
  }
}

TEST_CASE("a clean stream decodes completely, in any chunking", "[firmware][decoder]") {
  Bytes stream;
  const std::string banner = banner_line();
  append(stream, banner);
  for (unsigned k = 0; k < 500; ++k)
    append_frame(stream, make_frame(static_cast<std::uint16_t>(k), 1000u + 10000u * k));
  for (std::size_t chunk : {std::size_t{1}, std::size_t{7}, std::size_t{16}, std::size_t{4096}}) {
    Decoder d;
    const Collected c = decode(d, stream, chunk);
    INFO("chunk " << chunk);
    REQUIRE(c.banners.size() == 1);
    CHECK(c.banners[0].rate_hz == 100);
    CHECK(c.banners[0].oversample == 16);
    CHECK(c.banners[0].baud == 115200);
    CHECK(c.banners[0].vref_V == 5.0);
    CHECK(c.banners[0].firmware_version == PAMKIT_FIRMWARE_VERSION);
    REQUIRE(c.samples.size() == 500);
    CHECK(c.samples[499].device_time_s == Approx(1000e-6 + 499 * 0.01).epsilon(1e-12));
    CHECK(d.stats().skipped_bytes == 0);
    CHECK(d.stats().gaps == 0);
    CHECK(d.stats().resets == 0);
    check_ledger(d, banner.size());
  }
}

TEST_CASE("garbage between frames is skipped, counted and loses nothing", "[firmware][decoder]") {
  std::mt19937 rng(7);
  Bytes stream;
  std::size_t garbage = 0;
  for (unsigned k = 0; k < 300; ++k) {
    if (k % 10 == 5) {
      // random bytes salted with sync pairs, '#' and CR LF: false frames and false banners
      const std::size_t n = 1 + rng() % 50;
      for (std::size_t i = 0; i < n; ++i) {
        const unsigned r = rng() % 8;
        stream.push_back(r == 0   ? 0xA5
                         : r == 1 ? 0x5A
                         : r == 2 ? '#'
                         : r == 3 ? '\n'
                                  : static_cast<std::uint8_t>(rng()));
      }
      garbage += n;
    }
    append_frame(stream, make_frame(static_cast<std::uint16_t>(k), 10000u * k));
  }
  Decoder d;
  const Collected c = decode(d, stream, 13);
  std::vector<unsigned> expected(300);
  for (unsigned k = 0; k < 300; ++k) expected[k] = k;
  CHECK(seqs(c) == expected);
  CHECK(d.stats().skipped_bytes == garbage);
  CHECK(d.stats().resyncs == 30);
  CHECK(d.stats().gaps == 0);
  check_ledger(d, 0);
}

TEST_CASE("flipped bits and dropped bytes cost exactly the frame they hit", "[firmware][decoder]") {
  std::mt19937 rng(11);
  Bytes stream;
  std::vector<unsigned> expected;
  std::size_t damaged_bytes = 0, damaged = 0;
  for (unsigned k = 0; k < 400; ++k) {
    Bytes frame;
    append_frame(frame, make_frame(static_cast<std::uint16_t>(k), 10000u * k));
    if (k % 20 == 3) {
      frame[2 + rng() % 14] ^= static_cast<std::uint8_t>(1u << (rng() % 8));  // a flipped bit
      damaged_bytes += PAMKIT_FRAME_SIZE;
      ++damaged;
    } else if (k % 20 == 13) {
      frame.erase(frame.begin() + 2 + rng() % 14);  // a dropped byte
      damaged_bytes += PAMKIT_FRAME_SIZE - 1;
      ++damaged;
    } else {
      expected.push_back(k);
    }
    stream.insert(stream.end(), frame.begin(), frame.end());
  }
  Decoder d;
  const Collected c = decode(d, stream, 64);
  CHECK(seqs(c) == expected);
  CHECK(d.stats().gaps == damaged);
  CHECK(d.stats().missing_frames == damaged);
  CHECK(d.stats().skipped_bytes == damaged_bytes);
  CHECK(d.stats().checksum_errors >= damaged);
  // the frame after each damaged one says how many went missing before it
  for (const auto& s : c.samples)
    CHECK(s.missing_before == ((s.frame.seq % 20 == 4 || s.frame.seq % 20 == 14) ? 1u : 0u));
  check_ledger(d, 0);
}

TEST_CASE("a board reset shows as a new boot, by its banner or by its clock", "[firmware][decoder]") {
  Bytes stream;
  const std::string banner = banner_line();
  append(stream, banner);
  for (unsigned k = 0; k < 50; ++k)
    append_frame(stream, make_frame(static_cast<std::uint16_t>(k), 5000000u + 10000u * k));
  stream.resize(stream.size() - 7);  // reset in the middle of frame 49
  append(stream, banner);
  for (unsigned k = 0; k < 50; ++k) append_frame(stream, make_frame(static_cast<std::uint16_t>(k), 4000u + 10000u * k));
  // a reset whose banner was lost: the clock goes back
  for (unsigned k = 0; k < 50; ++k) append_frame(stream, make_frame(static_cast<std::uint16_t>(k), 3000u + 10000u * k));
  Decoder d;
  const Collected c = decode(d, stream, 100);
  REQUIRE(c.samples.size() == 149);
  CHECK(c.banners.size() == 2);
  CHECK(d.stats().resets == 2);
  CHECK(d.stats().gaps == 0);
  CHECK(d.stats().skipped_bytes == PAMKIT_FRAME_SIZE - 7);
  CHECK(c.samples[48].boot == 0);
  CHECK(c.samples[49].boot == 1);
  CHECK(c.samples[49].device_time_s == Approx(0.004));
  CHECK(c.samples[99].boot == 2);
  check_ledger(d, 2 * banner.size());
}

TEST_CASE("sequence numbers and device time unwrap - the board's own drops are told apart", "[firmware][decoder]") {
  Bytes stream;
  append(stream, banner_line(1000, 1));
  std::uint32_t t = 0xFFFFFFFFu - 25000u;  // micros() wraps during the run
  std::uint16_t seq = 65530;               // and so does the sequence number
  std::vector<unsigned> expected;
  for (unsigned k = 0; k < 20; ++k) {
    pamkit_frame f = make_frame(seq, t, 1);
    if (k == 10) {  // the board lost 3 samples (buffer full) and says so
      f.seq = static_cast<std::uint16_t>(f.seq + 3);
      f.time_us += 3000u;
      f.dropped = 3;
      seq = static_cast<std::uint16_t>(seq + 3);
      t += 3000u;
    }
    append_frame(stream, f);
    seq = static_cast<std::uint16_t>(seq + 1);
    t += 1000u;
  }
  Decoder d;
  // the banner says seq starts at 0 after a reset; this stream starts at 65530: 65530 missing
  // frames are reported before the first one, which is what a receiver must assume.
  const Collected c = decode(d, stream, 5);
  REQUIRE(c.samples.size() == 20);
  CHECK(d.stats().gaps == 2);
  CHECK(d.stats().missing_frames == 65530u + 3u);
  CHECK(d.stats().device_dropped == 3);
  CHECK(c.samples[19].device_time_s - c.samples[0].device_time_s == Approx(0.022).epsilon(1e-9));
  CHECK(d.stats().resets == 0);
}

TEST_CASE("a damaged banner is rejected and counted - the frames after it still decode", "[firmware][decoder]") {
  std::string banner = banner_line();
  banner[20] ^= 0x01;  // one flipped bit in the text
  Bytes stream;
  append(stream, banner);
  for (unsigned k = 0; k < 10; ++k) append_frame(stream, make_frame(static_cast<std::uint16_t>(k), 10000u * k));
  Decoder d;
  const Collected c = decode(d, stream, 3);
  CHECK(c.banners.empty());
  CHECK(d.stats().banner_errors == 1);
  CHECK(c.samples.size() == 10);
  CHECK(d.stats().skipped_bytes == banner.size());
}

TEST_CASE("a cut stream counts the unfinished frame as skipped", "[firmware][decoder]") {
  Bytes stream;
  for (unsigned k = 0; k < 3; ++k) append_frame(stream, make_frame(static_cast<std::uint16_t>(k), 10000u * k));
  stream.resize(stream.size() - 5);
  Decoder d;
  const Collected c = decode(d, stream);
  CHECK(c.samples.size() == 2);
  CHECK(d.pending() == PAMKIT_FRAME_SIZE - 5);
  d.end_of_stream();
  CHECK(d.pending() == 0);
  CHECK(d.stats().skipped_bytes == PAMKIT_FRAME_SIZE - 5);
  check_ledger(d, 0);
}
