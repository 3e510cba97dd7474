// The logger's host reader: serial port -> decoder -> calibration -> CSV, flushed as it goes.

#include "pamkit/logger/reader.hpp"

#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>
#include <thread>

#include "pamkit/error.hpp"

namespace pamkit::logger {

using pamkit::detail::message;

Reader::Reader(ReaderOptions options, LoggerCalibration calibration, bool pressure_calibrated,
               const std::string& csv_path)
    : options_(std::move(options)), calibration_(calibration), pressure_calibrated_(pressure_calibrated) {
  calibration_.validate();
  if (options_.port.empty()) throw InvalidInput("logger: no serial port given");
  if (!(options_.banner_timeout_s >= 0) || !(options_.reconnect_interval_s > 0)) {
    throw InvalidInput(message("logger: banner_timeout_s = ", options_.banner_timeout_s,
                               " must be >= 0 and reconnect_interval_s = ", options_.reconnect_interval_s, " > 0"));
  }
  file_ = std::fopen(csv_path.c_str(), "w");
  if (!file_) throw Error(message("logger: cannot create ", csv_path, ": ", std::strerror(errno)));
  std::fputs(pressure_calibrated_ ? "time_s,pressure_kPa,temperature_C,pressure_V,temperature_V,boot,seq\n"
                                  : "time_s,temperature_C,pressure_V,temperature_V,boot,seq\n",
             file_);
  std::fflush(file_);
  start_ = clock();
}

Reader::~Reader() { close(); }

void Reader::close() {
  port_.reset();
  if (file_) {
    std::fclose(file_);
    file_ = nullptr;
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
    throw Error(message("logger on ", options_.port, ": the board sends frame format ", banner.frame_version,
                        " (firmware ", banner.firmware_version, "), this reader knows format ", PAMKIT_FRAME_VERSION,
                        ": flash the sketch from this pamkit"));
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
  write(sample, now);
}

void Reader::write(const Sample& sample, double arrival) {
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
  if (pressure_calibrated_) {
    std::fprintf(file_, "%.6f,%.4f,%.3f,%.6f,%.6f,%u,%u\n", row.time_s, row.pressure_kPa, row.temperature_C,
                 row.pressure_V, row.temperature_V, row.boot, static_cast<unsigned>(row.seq));
  } else {
    std::fprintf(file_, "%.6f,%.3f,%.6f,%.6f,%u,%u\n", row.time_s, row.temperature_C, row.pressure_V, row.temperature_V,
                 row.boot, static_cast<unsigned>(row.seq));
  }
  ++stats_.rows;
  last_ = row;
  last_arrival_ = arrival;
}

std::size_t Reader::poll(double timeout_s) {
  if (!file_) throw Error("logger: poll() after close()");
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
  std::uint8_t buffer[4096];
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
    for (const auto& [sample, arrival] : held_) write(sample, arrival);
    held_.clear();
    waiting_for_banner_ = false;
  } else if (count > 0) {
    decoder_.feed(
        buffer, count, [&](const Sample& sample) { on_frame(sample, now); },
        [&](const Banner& banner) { on_banner(banner); });
  }
  if (waiting_for_banner_ && now >= banner_deadline_) {
    // No reset on open (a pty, or a board without auto-reset): what came is current data.
    ++stats_.no_banner;
    waiting_for_banner_ = false;
    for (const auto& [sample, arrival] : held_) write(sample, arrival);
    held_.clear();
  }
  if (stats_.rows != rows_before) std::fflush(file_);
  stats_.decoder = decoder_.stats();
  stats_.seconds = now - start_;
  return static_cast<std::size_t>(stats_.rows - rows_before);
}

}  // namespace pamkit::logger
