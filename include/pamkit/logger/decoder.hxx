#pragma once

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>

namespace pamkit::logger {

namespace detail {
/// Value of `key=` in a banner line, as text up to the next space ("" if absent).
inline std::string banner_value(const std::string& line, const char* key) {
  const std::string needle = std::string(" ") + key + "=";
  const std::size_t at = line.find(needle);
  if (at == std::string::npos) return {};
  const std::size_t begin = at + needle.size();
  return line.substr(begin, line.find(' ', begin) - begin);
}

/// Decimal unsigned number, all of `text`; false if empty, not a number or above `max`.
inline bool banner_number(const std::string& text, unsigned long max, unsigned long& value) {
  if (text.empty() || text.size() > 10) return false;
  value = 0;
  for (char c : text) {
    if (c < '0' || c > '9') return false;
    value = value * 10 + static_cast<unsigned long>(c - '0');
  }
  return value <= max;
}
}  // namespace detail

inline bool parse_banner(const char* line, std::size_t length, Banner& banner) {
  const std::size_t tag = std::strlen(PAMKIT_BANNER_TAG);
  static constexpr char kCrcKey[] = " crc=";
  const std::size_t crc_field = sizeof(kCrcKey) - 1 + 4;
  if (length < tag + crc_field || std::memcmp(line, PAMKIT_BANNER_TAG, tag) != 0 ||
      (length > tag && line[tag] != ' ')) {
    return false;
  }
  const std::size_t body = length - crc_field;
  if (std::memcmp(line + body, kCrcKey, sizeof(kCrcKey) - 1) != 0) return false;
  unsigned crc = 0;
  for (std::size_t i = body + sizeof(kCrcKey) - 1; i < length; ++i) {
    const char c = line[i];
    const int digit = c >= '0' && c <= '9' ? c - '0' : c >= 'A' && c <= 'F' ? c - 'A' + 10 : -1;
    if (digit < 0) return false;
    crc = crc * 16 + static_cast<unsigned>(digit);
  }
  if (crc != pamkit_crc16(reinterpret_cast<const std::uint8_t*>(line), body)) return false;

  Banner parsed;
  parsed.line.assign(line, length);
  const std::string text(line, body);
  parsed.firmware_version = detail::banner_value(text, "version");
  unsigned long frame = 0, rate = 0, period = 0, oversample = 0, baud = 0, vref = 0;
  if (parsed.firmware_version.empty() || !detail::banner_number(detail::banner_value(text, "frame"), 255, frame) ||
      !detail::banner_number(detail::banner_value(text, "rate_hz"), 1000000, rate) ||
      !detail::banner_number(detail::banner_value(text, "period_us"), 100000000, period) ||
      !detail::banner_number(detail::banner_value(text, "oversample"), PAMKIT_OVERSAMPLE_MAX, oversample) ||
      !detail::banner_number(detail::banner_value(text, "baud"), 10000000, baud) ||
      !detail::banner_number(detail::banner_value(text, "vref_mV"), 10000, vref)) {
    return false;
  }
  parsed.frame_version = static_cast<unsigned>(frame);
  parsed.rate_hz = static_cast<double>(rate);
  parsed.period_us = static_cast<std::uint32_t>(period);
  parsed.oversample = static_cast<unsigned>(oversample);
  parsed.baud = static_cast<std::uint32_t>(baud);
  parsed.vref_V = static_cast<double>(vref) / 1000.0;
  banner = std::move(parsed);
  return true;
}

inline void Decoder::skip_one() {
  ++head_;
  ++stats_.skipped_bytes;
  skipping_ = true;
}

inline void Decoder::accepted() {
  if (skipping_) ++stats_.resyncs;
  skipping_ = false;
}

inline Decoder::Parse Decoder::try_frame(const std::uint8_t* at, std::size_t available, Sample& sample) {
  if (available < 2) return Parse::kNeedMore;
  if (at[1] != PAMKIT_FRAME_SYNC1) return Parse::kRejected;
  if (available < PAMKIT_FRAME_SIZE) return Parse::kNeedMore;
  if (!pamkit_frame_decode(at, &sample.frame)) {
    ++stats_.checksum_errors;
    return Parse::kRejected;
  }
  return Parse::kConsumed;
}

inline Decoder::Parse Decoder::try_banner(const std::uint8_t* at, std::size_t available, std::size_t& length) {
  // A banner is printable ASCII ended by "\r\n". Anything else (a frame's 0xA5 above all) ends
  // the candidate at once, so a false '#' never hides the frame that follows it.
  const std::size_t limit = std::min<std::size_t>(available, PAMKIT_BANNER_MAX);
  for (std::size_t i = 1; i < limit; ++i) {
    const std::uint8_t c = at[i];
    if (c == '\n') {
      if (at[i - 1] != '\r') return Parse::kRejected;
      length = i + 1;
      return Parse::kConsumed;
    }
    if (c == '\r') {
      if (i + 1 < limit && at[i + 1] != '\n') return Parse::kRejected;
      continue;
    }
    if (c < 0x20 || c > 0x7E) return Parse::kRejected;
  }
  return available < PAMKIT_BANNER_MAX ? Parse::kNeedMore : Parse::kRejected;
}

inline bool Decoder::track(Sample& sample) {
  const pamkit_frame& f = sample.frame;
  if (have_last_) {
    const std::uint32_t dt = f.time_us - last_time_us_;  // modulo 2^32: micros() wraps
    if (dt > 0x80000000u) {
      // The device clock went back: the board restarted and its banner was lost.
      ++stats_.resets;
      ++boot_;
      have_last_ = false;
    } else {
      const std::uint16_t delta = static_cast<std::uint16_t>(f.seq - last_seq_);
      if (delta == 0) {
        ++stats_.duplicates;
        return false;
      }
      std::uint64_t missing = delta - 1u;
      // More than 65535 frames lost cannot show in a 16-bit sequence number; the clock can.
      if (period_us_ > 0) {
        const std::uint64_t by_time = static_cast<std::uint64_t>(std::llround(static_cast<double>(dt) / period_us_));
        if (by_time > missing + 32768u) missing += ((by_time - 1 - missing) / 65536u) * 65536u;
      }
      if (missing > 0) {
        ++stats_.gaps;
        stats_.missing_frames += missing;
        stats_.device_dropped += std::min<std::uint64_t>(missing, f.dropped);
      }
      sample.missing_before = static_cast<std::uint32_t>(std::min<std::uint64_t>(missing, 0xFFFFFFFFu));
      boot_time_us_ += dt;
    }
  }
  if (!have_last_) {
    boot_time_us_ = f.time_us;
    // Right after its banner the board numbers its samples from 0: frames before this one are lost.
    sample.missing_before = after_banner_ ? f.seq : 0u;
    if (sample.missing_before > 0) {
      ++stats_.gaps;
      stats_.missing_frames += sample.missing_before;
      stats_.device_dropped += std::min<std::uint32_t>(sample.missing_before, f.dropped);
    }
  }
  after_banner_ = false;
  have_last_ = true;
  any_data_ = true;
  last_seq_ = f.seq;
  last_time_us_ = f.time_us;
  sample.boot = boot_;
  sample.device_time_s = static_cast<double>(boot_time_us_) * 1e-6;
  return true;
}

template <class OnFrame, class OnBanner>
void Decoder::feed(const std::uint8_t* data, std::size_t size, OnFrame&& on_frame, OnBanner&& on_banner) {
  stats_.bytes += size;
  if (head_ > 0 && head_ == buffer_.size()) {
    buffer_.clear();
    head_ = 0;
  }
  buffer_.insert(buffer_.end(), data, data + size);
  for (;;) {
    const std::size_t available = buffer_.size() - head_;
    if (available == 0) break;
    const std::uint8_t* at = buffer_.data() + head_;
    Parse result = Parse::kRejected;
    if (at[0] == PAMKIT_FRAME_SYNC0) {
      Sample sample;
      result = try_frame(at, available, sample);
      if (result == Parse::kConsumed) {
        head_ += PAMKIT_FRAME_SIZE;
        ++stats_.frames;
        accepted();
        if (track(sample)) on_frame(static_cast<const Sample&>(sample));
        continue;
      }
    } else if (at[0] == '#') {
      std::size_t length = 0;
      result = try_banner(at, available, length);
      if (result == Parse::kConsumed) {
        Banner banner;
        if (parse_banner(reinterpret_cast<const char*>(at), length - 2, banner)) {
          head_ += length;
          ++stats_.banners;
          accepted();
          if (any_data_) {  // a banner after data: the board restarted
            ++stats_.resets;
            ++boot_;
          }
          any_data_ = true;
          have_last_ = false;
          after_banner_ = true;
          period_us_ = banner.period_us;
          banner_ = std::move(banner);
          on_banner(static_cast<const Banner&>(banner_));
          continue;
        }
        ++stats_.banner_errors;
        result = Parse::kRejected;
      }
    }
    if (result == Parse::kNeedMore) break;
    skip_one();
  }
  // Keep the unfinished tail only; compact once the consumed part dominates.
  if (head_ > 4096 && head_ * 2 > buffer_.size()) {
    buffer_.erase(buffer_.begin(), buffer_.begin() + static_cast<std::ptrdiff_t>(head_));
    head_ = 0;
  }
}

inline void Decoder::end_of_stream() {
  const std::size_t left = pending();
  if (left > 0) {
    stats_.skipped_bytes += left;
    skipping_ = true;
  }
  buffer_.clear();
  head_ = 0;
}

}  // namespace pamkit::logger
