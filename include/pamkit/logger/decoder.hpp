#pragma once
/// \file
/// Decoder of the logger's byte stream (firmware/pamkit_logger/pamkit_frame.h): finds frames and
/// banners in whatever arrives, resynchronises after garbage, rejects damaged frames by their
/// CRC, follows sequence numbers and device time across gaps and board resets, and counts each
/// kind of trouble. Pure computation: no I/O, no exceptions, usable from any thread that owns it.
///
/// Every byte fed is accounted for exactly once: it ends up in an intact frame, in a banner, in
/// `skipped_bytes`, or is still `pending()` (an unfinished frame or line at the end of a chunk).

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "pamkit_frame.h"  // the one definition of the frame, shared with the sketch

namespace pamkit::logger {

/// The board's start-up line: firmware version and settings (PAMKIT_BANNER_FORMAT).
struct Banner {
  std::string firmware_version;  ///< e.g. "1.0.0"
  unsigned frame_version = 0;    ///< PAMKIT_FRAME_VERSION the firmware was built with
  double rate_hz = 0;            ///< configured sample rate [Hz]
  std::uint32_t period_us = 0;   ///< sample period [us]
  unsigned oversample = 0;       ///< conversions summed per channel and sample
  std::uint32_t baud = 0;        ///< serial line rate [bit/s]
  double vref_V = 0;             ///< ADC reference the firmware was configured with [V]
  std::string line;              ///< the line as received, without "\r\n"
};

/// One intact frame, with what the decoder knows around it.
struct Sample {
  pamkit_frame frame{};              ///< raw fields as sent
  std::uint32_t boot = 0;            ///< board start counted by this decoder (0 = the first seen)
  double device_time_s = 0;          ///< device clock since its reset, unwrapped across micros() wraps [s]
  std::uint32_t missing_before = 0;  ///< frames absent between the previous intact frame and this one
  /// Mean conversion of `channel` (PAMKIT_CHANNEL_PRESSURE or _TEMPERATURE) [counts, 0..1023].
  double mean_counts(int channel) const { return static_cast<double>(frame.counts[channel]) / frame.oversample; }
};

/// What the decoder has seen. Counters only grow.
struct DecoderStats {
  std::uint64_t bytes = 0;            ///< bytes fed
  std::uint64_t frames = 0;           ///< intact frames
  std::uint64_t banners = 0;          ///< intact banners
  std::uint64_t skipped_bytes = 0;    ///< bytes in no intact frame or banner: garbage, damaged or cut frames
  std::uint64_t resyncs = 0;          ///< runs of skipped bytes that ended at an intact frame or banner
  std::uint64_t checksum_errors = 0;  ///< frame candidates (sync pair found) failing their CRC
  std::uint64_t banner_errors = 0;    ///< banner candidates failing their CRC or syntax
  std::uint64_t gaps = 0;             ///< places where sequence numbers jump
  std::uint64_t missing_frames = 0;   ///< frames absent in those gaps (lost on the line or on the board)
  std::uint64_t device_dropped = 0;   ///< of those, frames the board reported it could not take or send
  std::uint64_t duplicates = 0;       ///< frames repeating the previous sequence number (ignored)
  std::uint64_t resets = 0;           ///< board restarts: a banner after data, or the device clock going back
};

/// Stream decoder. Feed it bytes in chunks of any size; it calls back for each frame and banner.
class Decoder {
 public:
  /// Decodes `size` bytes and calls `on_frame(const Sample&)` / `on_banner(const Banner&)` for
  /// each intact frame / banner, in stream order.
  template <class OnFrame, class OnBanner>
  void feed(const std::uint8_t* data, std::size_t size, OnFrame&& on_frame, OnBanner&& on_banner);

  /// The stream broke (port closed or cable pulled): the bytes of an unfinished frame or banner
  /// are counted as skipped. Sequence tracking continues, so a board that kept running shows its
  /// lost frames as a gap, and one that restarted shows a reset.
  void end_of_stream();

  const DecoderStats& stats() const { return stats_; }
  /// Bytes held for an unfinished frame or banner.
  std::size_t pending() const { return buffer_.size() - head_; }
  /// The last banner decoded, if any (`banner_seen()`).
  const Banner& banner() const { return banner_; }
  bool banner_seen() const { return stats_.banners > 0; }

 private:
  enum class Parse { kNeedMore, kConsumed, kRejected };
  Parse try_frame(const std::uint8_t* at, std::size_t available, Sample& sample);
  Parse try_banner(const std::uint8_t* at, std::size_t available, std::size_t& length);
  void skip_one();
  void accepted();
  bool track(Sample& sample);  // sequence and time bookkeeping; false for a duplicate

  std::vector<std::uint8_t> buffer_;
  std::size_t head_ = 0;
  bool skipping_ = false;
  DecoderStats stats_;
  Banner banner_;
  // sequence tracking
  bool have_last_ = false;
  bool any_data_ = false;
  bool after_banner_ = false;
  std::uint32_t boot_ = 0;
  std::uint16_t last_seq_ = 0;
  std::uint32_t last_time_us_ = 0;
  std::uint64_t boot_time_us_ = 0;  // unwrapped device time of the last frame
  std::uint32_t period_us_ = 0;     // from the banner, 0 if unknown
};

/// Parses a banner line (without "\r\n"). Returns false if the tag, a required key or the CRC is
/// wrong. Keys it does not know are ignored, so newer firmware stays readable.
bool parse_banner(const char* line, std::size_t length, Banner& banner);

}  // namespace pamkit::logger

#include "pamkit/logger/decoder.hxx"
