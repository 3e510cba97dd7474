// The logger's host reader: serial port -> decoder -> calibration -> CSV, written as whole lines
// after every read.

#include "pamkit/logger/reader.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <thread>

#include "pamkit/error.hpp"

namespace pamkit::logger {

using pamkit::detail::message;

Reader::Reader(ReaderOptions options, LoggerCalibration calibration, bool pressure_calibrated,
               const std::string& csv_path)
    : options_(std::move(options)),
      calibration_(calibration),
      pressure_calibrated_(pressure_calibrated),
      csv_path_(csv_path) {
  calibration_.validate();
  if (options_.port.empty()) throw InvalidInput("logger: no serial port given");
  if (!(options_.banner_timeout_s >= 0) || !(options_.reconnect_interval_s > 0)) {
    throw InvalidInput(message("logger: banner_timeout_s = ", options_.banner_timeout_s,
                               " must be >= 0 and reconnect_interval_s = ", options_.reconnect_interval_s, " > 0"));
  }
  if (!(options_.fsync_interval_s >= 0)) {
    throw InvalidInput(
        message("logger: fsync_interval_s = ", options_.fsync_interval_s, " must be >= 0 (infinity: never)"));
  }
  // O_EXCL: the check for an existing file and the creation are one step, so a recording that
  // appears in between is not overwritten either.
  const int flags = O_WRONLY | O_CREAT | O_CLOEXEC | (options_.replace_existing ? O_TRUNC : O_EXCL);
  csv_fd_ = ::open(csv_path.c_str(), flags, 0666);
  if (csv_fd_ < 0) {
    if (errno == EEXIST) throw InvalidInput(message("logger: ", csv_path, " exists already; not overwriting it"));
    throw Error(message("logger: cannot create ", csv_path, ": ", std::strerror(errno)));
  }
  try {
    write_lines(pressure_calibrated_ ? "time_s,pressure_kPa,temperature_C,pressure_V,temperature_V,boot,seq\n"
                                     : "time_s,temperature_C,pressure_V,temperature_V,boot,seq\n");
  } catch (...) {
    ::close(csv_fd_);
    throw;
  }
  start_ = clock();
  last_sync_ = start_;
}

Reader::~Reader() { close(); }

void Reader::close() {
  port_.reset();
  if (csv_fd_ >= 0) {
    // Best effort: close() runs in the destructor and must not throw; every row is already written.
    if (std::isfinite(options_.fsync_interval_s)) ::fsync(csv_fd_);
    ::close(csv_fd_);
    csv_fd_ = -1;
  }
}

void Reader::write_lines(const std::string& lines) {
  // pwrite at the file's known length: after a failed write the file is cut back to its last
  // whole line and the next write starts there, leaving no hole.
  std::size_t done = 0;
  while (done < lines.size()) {
    const ssize_t count =
        ::pwrite(csv_fd_, lines.data() + done, lines.size() - done, static_cast<off_t>(csv_bytes_ + done));
    if (count < 0 && errno == EINTR) continue;
    if (count <= 0) {
      const int code = count < 0 ? errno : ENOSPC;
      if (done > 0 && ::ftruncate(csv_fd_, static_cast<off_t>(csv_bytes_)) != 0) {
        throw Error(message("logger: writing ", csv_path_, " failed (", std::strerror(code),
                            ") and cutting it back to its last whole line failed too (", std::strerror(errno), ")"));
      }
      throw Error(message("logger: writing ", csv_path_, " failed: ", std::strerror(code),
                          "; the file ends at its last whole line"));
    }
    done += static_cast<std::size_t>(count);
  }
  csv_bytes_ += lines.size();
}

void Reader::write_pending(double now) {
  if (pending_rows_ == 0) return;
  try {
    write_lines(pending_);
  } catch (...) {
    pending_.clear();
    pending_rows_ = 0;
    throw;
  }
  stats_.rows += pending_rows_;
  pending_.clear();
  pending_rows_ = 0;
  if (now - last_sync_ >= options_.fsync_interval_s) {
    // EINVAL: the output is a device or pipe (/dev/null...), which has nothing to sync.
    if (::fsync(csv_fd_) != 0 && errno != EINVAL) {
      throw Error(message("logger: fsync of ", csv_path_, " failed: ", std::strerror(errno)));
    }
    last_sync_ = now;
  }
}

double Reader::clock() const {
  using namespace std::chrono;
  return duration<double>(steady_clock::now().time_since_epoch()).count();
}

std::optional<Banner> Reader::banner() const {
  if (!decoder_.banner_seen()) return std::nullopt;
  return decoder_.banner();
}

void Reader::try_open(double now) {
  try {
    port_ = std::make_unique<SerialPort>(options_.port, options_.baud, options_.assert_dtr);
    ++stats_.opens;
    last_error_.clear();
    waiting_for_banner_ = true;
    banner_deadline_ = now + options_.banner_timeout_s;
  } catch (const Error& error) {
    last_error_ = error.what();
    next_open_ = now + options_.reconnect_interval_s;
  }
}

void Reader::on_banner(const Banner& banner) {
  if (banner.frame_version != PAMKIT_FRAME_VERSION) {
    const bool newer = banner.frame_version > PAMKIT_FRAME_VERSION;
    throw Error(message("logger on ", options_.port, ": the board sends frame format ", banner.frame_version,
                        " (firmware ", banner.firmware_version, "), this reader knows format ", PAMKIT_FRAME_VERSION,
                        newer ? ": update pamkit, or flash the sketch that comes with this pamkit"
                              : ": flash the sketch that comes with this pamkit"));
  }
  if (waiting_for_banner_) {
    stats_.stale_frames += held_.size();
    held_.clear();
    waiting_for_banner_ = false;
  }
}

void Reader::on_frame(const Sample& sample, double now) {
  if (waiting_for_banner_) {
    held_.emplace_back(sample, now);
    return;
  }
  append_row(sample, now);
}

void Reader::append_row(const Sample& sample, double arrival) {
  // One time base for the whole file: the device clock within a boot; a new boot is placed by
  // the host clock at its first frame's arrival (never before the previous row).
  if (!have_offset_ || sample.boot != offset_boot_) {
    if (!have_offset_) {
      offset_s_ = -sample.device_time_s;
    } else {
      const double previous = last_ ? last_->time_s : 0.0;
      const double host = last_ ? previous + std::max(arrival - last_arrival_, 0.0) : arrival - start_;
      offset_s_ = std::max(host, previous + 1e-6) - sample.device_time_s;
    }
    have_offset_ = true;
    offset_boot_ = sample.boot;
  }
  Reading row;
  row.time_s = sample.device_time_s + offset_s_;
  row.pressure_V = calibration_.volts(sample.mean_counts(PAMKIT_CHANNEL_PRESSURE));
  row.temperature_V = calibration_.volts(sample.mean_counts(PAMKIT_CHANNEL_TEMPERATURE));
  row.pressure_kPa =
      pressure_calibrated_ ? calibration_.pressure_kPa(row.pressure_V) : std::numeric_limits<double>::quiet_NaN();
  row.temperature_C = calibration_.temperature_C(row.temperature_V);
  row.boot = sample.boot;
  row.seq = sample.frame.seq;
  // Bounded by the validated calibration (|kPa| < 1e6, |degC| < 1e5): far below the buffer.
  char line[256];
  const int length =
      pressure_calibrated_
          ? std::snprintf(line, sizeof line, "%.6f,%.4f,%.3f,%.6f,%.6f,%u,%u\n", row.time_s, row.pressure_kPa,
                          row.temperature_C, row.pressure_V, row.temperature_V, row.boot,
                          static_cast<unsigned>(row.seq))
          : std::snprintf(line, sizeof line, "%.6f,%.3f,%.6f,%.6f,%u,%u\n", row.time_s, row.temperature_C,
                          row.pressure_V, row.temperature_V, row.boot, static_cast<unsigned>(row.seq));
  if (length < 0 || static_cast<std::size_t>(length) >= sizeof line) {
    throw Error(message("logger: a row at seq ", row.seq, " does not fit ", sizeof line, " characters"));
  }
  pending_.append(line, static_cast<std::size_t>(length));
  ++pending_rows_;
  last_ = row;
  last_arrival_ = arrival;
}

std::size_t Reader::poll(double timeout_s) {
  if (csv_fd_ < 0) throw Error("logger: poll() after close()");
  const std::uint64_t rows_before = stats_.rows;
  double now = clock();
  if (!port_) {
    if (now >= next_open_) try_open(now);
    if (!port_) {
      const double wait = std::min(timeout_s, std::max(next_open_ - now, 0.0));
      std::this_thread::sleep_for(std::chrono::duration<double>(wait));
      stats_.seconds = clock() - start_;
      return 0;
    }
  }
  std::uint8_t buffer[kReadBytes];
  std::size_t count = 0;
  const int timeout_ms = static_cast<int>(std::lround(std::max(timeout_s, 0.0) * 1000));
  const SerialPort::Status status = port_->read(buffer, sizeof buffer, timeout_ms, count);
  now = clock();
  if (status == SerialPort::Status::kDisconnected) {
    decoder_.end_of_stream();
    port_.reset();
    ++stats_.disconnects;
    next_open_ = now + options_.reconnect_interval_s;
    // Frames held for a banner that will not come from this connection are real data.
    for (const auto& [sample, arrival] : held_) append_row(sample, arrival);
    held_.clear();
    waiting_for_banner_ = false;
  } else if (count > 0) {
    try {
      decoder_.feed(
          buffer, count, [&](const Sample& sample) { on_frame(sample, now); },
          [&](const Banner& banner) { on_banner(banner); });
    } catch (...) {
      write_pending(now);  // the frames before a banner in a format this reader refuses
      throw;
    }
  }
  if (waiting_for_banner_ && now >= banner_deadline_) {
    // No reset on open (a pty, or a board without auto-reset): what came is current data.
    ++stats_.no_banner;
    waiting_for_banner_ = false;
    for (const auto& [sample, arrival] : held_) append_row(sample, arrival);
    held_.clear();
  }
  write_pending(now);
  stats_.decoder = decoder_.stats();
  stats_.seconds = now - start_;
  return static_cast<std::size_t>(stats_.rows - rows_before);
}

}  // namespace pamkit::logger
