#pragma once
/// \file
/// The host side of the logger: reads the board through a SerialPort, decodes frames, converts
/// them with a LoggerCalibration and appends them to a CSV file as they arrive.
///
/// What reaches the file, and when (docs/logger.md, "What a kill or a power cut can lose"): the
/// rows of one read of the port are formatted into one buffer and handed to the kernel by POSIX
/// write() calls of whole lines before the next read; no stdio buffer stands between, so no line
/// is ever split across two flushes. A killed or crashed program therefore loses at most the
/// frames of the read it was handling (kReadBytes bytes: 256 frames) and frames held while
/// waiting for the banner just after opening. The file is fsync()ed at most every
/// ReaderOptions::fsync_interval_s, which bounds what a power cut or a kernel crash can lose.
///
/// It survives what happens on a bench: the board's reset when the port is opened (it waits for
/// the banner, and drops frames that arrived before it: they come from before the reset),
/// garbage and damaged frames, gaps, the board restarting, and the cable being pulled and
/// plugged back in (it reopens the same path, e.g. a /dev/serial/by-id/ name).
///
/// CSV columns (units in their names): time_s, pressure_kPa (gauge; only with a pressure calibration),
/// temperature_C, pressure_V, temperature_V, boot, seq. time_s is the device clock, starting at 0
/// with the first frame written; after a board restart it continues from the host clock.

#include <cstdint>
#include <deque>
#include <memory>
#include <optional>
#include <string>

#include "pamkit/logger/calibration.hpp"
#include "pamkit/logger/decoder.hpp"
#include "pamkit/logger/serial_port.hpp"

namespace pamkit::logger {

/// How to reach the board.
struct ReaderOptions {
  std::string port;               ///< device path, by-id name or pty
  unsigned baud = 115200;         ///< must match the sketch's PAMKIT_BAUD
  bool assert_dtr = true;         ///< raise DTR on open: resets a Mega, so the log starts at its banner
  double banner_timeout_s = 3.0;  ///< wait this long for the banner after opening before trusting frames without one
  double reconnect_interval_s = 0.25;  ///< retry period while the port is gone
  /// fsync() the CSV at most this often [s], and on close(): what a power cut or a kernel crash can
  /// lose (a killed program loses nothing that was written, whatever this is). 0: after every
  /// read; infinity: never (the kernel writes back on its own, within about 30 s on Linux).
  double fsync_interval_s = 1.0;
  bool replace_existing = false;  ///< truncate an existing CSV instead of refusing to open it
};

/// One row of the CSV.
struct Reading {
  double time_s = 0;         ///< [s] since the first row
  double pressure_kPa = 0;   ///< gauge [kPa] (NaN without a pressure calibration)
  double temperature_C = 0;  ///< [degC]
  double pressure_V = 0;     ///< A0 [V]
  double temperature_V = 0;  ///< A1 [V]
  std::uint32_t boot = 0;    ///< board start (0 = first)
  std::uint16_t seq = 0;     ///< the frame's sequence number
};

/// The decoder's counters plus the reader's own.
struct ReaderStats {
  DecoderStats decoder;            ///< bytes, frames, checksum errors, gaps, resets...
  std::uint64_t rows = 0;          ///< rows written to the CSV
  std::uint64_t stale_frames = 0;  ///< frames received before a banner right after opening (from before the reset)
  std::uint64_t no_banner = 0;     ///< opens after which no banner came within the timeout
  std::uint64_t opens = 0;         ///< successful opens of the port
  std::uint64_t disconnects = 0;   ///< times the port went away
  double seconds = 0;              ///< wall time since the reader started [s]
};

/// Reads one logger into one CSV file. Call poll() in a loop; everything happens in there.
class Reader {
 public:
  /// Bytes taken from the port by one read: the most a killed reader can have read and not written
  /// (kReadBytes / PAMKIT_FRAME_SIZE = 256 frames), besides frames held for the banner.
  static constexpr std::size_t kReadBytes = 4096;

  /// \param calibration validated; `pressure_calibrated` false writes no pressure_kPa column.
  /// \param csv_path created at once, header written; an existing file is refused (InvalidInput)
  ///        unless `options.replace_existing`, which truncates it.
  /// \throws InvalidParameter for a bad calibration, InvalidInput for bad options or an existing
  ///         file, Error if the CSV cannot be created.
  Reader(ReaderOptions options, LoggerCalibration calibration, bool pressure_calibrated, const std::string& csv_path);
  ~Reader();

  /// Waits up to `timeout_s` for data (one read of at most kReadBytes), decodes it and writes the
  /// rows as whole lines before returning; opens or reopens the port when needed. Returns the
  /// number of rows written by this call.
  /// \throws Error if the board speaks another frame version than this reader, or if the CSV
  ///         cannot be written (disk full...: the file is cut back to its last whole line).
  std::size_t poll(double timeout_s);

  const ReaderStats& stats() const { return stats_; }
  /// The last row written, if any.
  const std::optional<Reading>& last() const { return last_; }
  /// The board's last banner, if one came.
  std::optional<Banner> banner() const;
  bool connected() const { return port_ != nullptr; }
  /// Why the last open failed ("" if it did not).
  const std::string& last_error() const { return last_error_; }
  /// Closes the port and the file, fsync()ing it first unless fsync_interval_s is infinite
  /// (every row is already written).
  void close();

 private:
  void try_open(double now);
  void on_frame(const Sample& sample, double now);
  void on_banner(const Banner& banner);
  void append_row(const Sample& sample, double arrival);
  void write_lines(const std::string& lines);
  void write_pending(double now);
  double clock() const;

  ReaderOptions options_;
  LoggerCalibration calibration_;
  bool pressure_calibrated_;
  std::string csv_path_;
  int csv_fd_ = -1;
  std::uint64_t csv_bytes_ = 0;  // the file's length: whole lines only
  std::string pending_;          // rows of the current poll, written at its end
  std::uint64_t pending_rows_ = 0;
  double last_sync_ = 0;
  std::unique_ptr<SerialPort> port_;
  Decoder decoder_;
  ReaderStats stats_;
  std::optional<Reading> last_;
  std::string last_error_;
  double start_ = 0;
  double next_open_ = 0;
  double banner_deadline_ = 0;
  bool waiting_for_banner_ = false;
  std::deque<std::pair<Sample, double>> held_;  // frames waiting for the banner, with arrival time
  // time base: per boot, time_s = device_time_s + offset
  bool have_offset_ = false;
  std::uint32_t offset_boot_ = 0;
  double offset_s_ = 0;
  double last_arrival_ = 0;
};

}  // namespace pamkit::logger
