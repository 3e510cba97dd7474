// End to end: the real sketch, built with avr-gcc against Debian's Arduino core, runs in simavr as
// an ATmega2560 (simavr_harness.c); the harness drives A0/A1 with known voltages and exposes UART0
// on a pty; the host Reader reads it into a CSV. Checked against what the harness did:
//   - every frame the firmware sent arrives, except exactly the ones the harness damaged;
//   - each frame's counts are those of the voltages served to its conversions: exactly as
//     simavr converts (V * 1023 / Vref, truncated), and within 1 count of a real ATmega
//     (V * 1024 / Vref, truncated);
//   - each injected fault is detected and counted by kind.
// PAMKIT_SIMAVR_HARNESS and the PAMKIT_FIRMWARE_* paths come from tests/firmware/CMakeLists.txt.

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <catch2/catch.hpp>

#include "pamkit/logger/reader.hpp"

extern char** environ;

namespace fs = std::filesystem;
using namespace pamkit::logger;

namespace {

constexpr double kVref_mV = 5000.0;  // the harness's AVCC

double wall() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }

/// The simulated board: a harness process and its files in a fresh temporary folder.
class SimulatedBoard {
 public:
  SimulatedBoard(const std::string& firmware, double seconds, const std::vector<std::string>& extra = {}) {
    char pattern[] = "/tmp/pamkit-simavr-XXXXXX";
    REQUIRE(::mkdtemp(pattern) != nullptr);
    dir = pattern;
    link = dir / "ttyPAMKIT";
    truth = dir / "truth.txt";
    summary = dir / "summary.txt";
    csv = dir / "log.csv";
    std::vector<std::string> args = {
        PAMKIT_SIMAVR_HARNESS,   "--firmware", firmware,       "--link",    link.string(),   "--seconds",
        std::to_string(seconds), "--truth",    truth.string(), "--summary", summary.string()};
    args.insert(args.end(), extra.begin(), extra.end());
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    const std::string log = (dir / "harness.log").string();
    posix_spawn_file_actions_addopen(&actions, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_adddup2(&actions, 1, 2);
    REQUIRE(posix_spawn(&pid_, argv[0], &actions, nullptr, argv.data(), environ) == 0);
    posix_spawn_file_actions_destroy(&actions);
    const double until = wall() + 20;
    while (!fs::exists(link) && wall() < until) std::this_thread::sleep_for(std::chrono::milliseconds(5));
    REQUIRE(fs::exists(link));
  }
  ~SimulatedBoard() {
    if (pid_ > 0) {
      ::kill(pid_, SIGTERM);
      ::waitpid(pid_, nullptr, 0);
    }
    std::error_code ignored;
    if (std::getenv("PAMKIT_KEEP_SIMAVR") == nullptr) fs::remove_all(dir, ignored);
  }
  bool finished() const { return fs::exists(summary); }
  int wait() {
    int status = 0;
    ::waitpid(pid_, &status, 0);
    pid_ = -1;
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  }
  std::map<std::string, double> totals() const {
    std::map<std::string, double> out;
    std::ifstream in(summary);
    std::string line;
    while (std::getline(in, line)) {
      const auto eq = line.find('=');
      if (eq != std::string::npos) out[line.substr(0, eq)] = std::stod(line.substr(eq + 1));
    }
    return out;
  }
  std::string log() const {
    std::ifstream in(dir / "harness.log");
    return std::string(std::istreambuf_iterator<char>(in), {});
  }

  fs::path dir, link, truth, summary, csv;

 private:
  pid_t pid_ = -1;
};

/// What the harness did, from its truth file.
struct Truth {
  std::map<unsigned, std::vector<unsigned>> conversions[2];  // boot -> mV served, per channel, in order
  std::vector<std::pair<unsigned, unsigned>> intact;         // (boot, seq) of frames sent undamaged
};

Truth read_truth(const fs::path& path) {
  Truth t;
  std::ifstream in(path);
  std::string kind;
  while (in >> kind) {
    if (kind == "C") {
      unsigned boot, channel, mV;
      in >> boot >> channel >> mV;
      t.conversions[channel][boot].push_back(mV);
    } else if (kind == "F") {
      unsigned boot, seq;
      int damaged;
      in >> boot >> seq >> damaged;
      if (!damaged) t.intact.emplace_back(boot, seq);
    } else {
      std::string rest;
      std::getline(in, rest);
    }
  }
  return t;
}

struct Row {
  double time_s, pressure_kPa, temperature_C, pressure_V, temperature_V;
  unsigned boot, seq;
};

std::vector<Row> read_csv(const fs::path& path) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  REQUIRE(line == "time_s,pressure_kPa,temperature_C,pressure_V,temperature_V,boot,seq");
  std::vector<Row> rows;
  while (std::getline(in, line)) {
    Row r{};
    char comma;
    std::istringstream s(line);
    s >> r.time_s >> comma >> r.pressure_kPa >> comma >> r.temperature_C >> comma >> r.pressure_V >> comma >>
        r.temperature_V >> comma >> r.boot >> comma >> r.seq;
    REQUIRE(!s.fail());
    rows.push_back(r);
  }
  return rows;
}

LoggerCalibration test_calibration() {
  // 0.5 V at 0 psi to 4.5 V at 80 psi: a typical ratiometric transducer, as a user would fill it in.
  std::vector<double> psi, volts;
  for (int i = 0; i <= 8; ++i) {
    psi.push_back(10.0 * i);
    volts.push_back(0.5 + 0.5 * i);
  }
  const PressureFit fit = fit_pressure(psi, volts);
  LoggerCalibration c;
  c.pressure_kPa_per_V = fit.kPa_per_V;
  c.pressure_offset_kPa = fit.offset_kPa;
  return c;
}

/// Runs the reader on the board until the harness is done and the line has been quiet for 1 s.
ReaderStats run_reader(SimulatedBoard& board, const LoggerCalibration& calibration, std::optional<Banner>& banner) {
  ReaderOptions options;
  options.port = board.link.string();
  options.banner_timeout_s = 2.0;
  options.reconnect_interval_s = 0.05;
  Reader reader(options, calibration, true, board.csv.string());
  const double start = wall();
  double quiet_since = wall();
  std::uint64_t bytes = 0;
  for (;;) {
    reader.poll(0.05);
    if (reader.stats().decoder.bytes != bytes) {
      bytes = reader.stats().decoder.bytes;
      quiet_since = wall();
    }
    if (board.finished() && wall() - quiet_since > 1.0) break;
    if (wall() - start > 240) FAIL("the simulated run did not finish within 240 s; harness log:\n" << board.log());
  }
  banner = reader.banner();
  const ReaderStats stats = reader.stats();
  reader.close();
  const int status = board.wait();
  INFO(board.log());
  REQUIRE(status == 0);
  return stats;
}

/// The frames' values against the voltages the harness served, conversion by conversion.
void check_values(const std::vector<Row>& rows, const Truth& truth, unsigned oversample,
                  const LoggerCalibration& calibration) {
  std::size_t checked = 0;
  double worst_hardware = 0;
  for (const Row& r : rows) {
    const double volts[2] = {r.pressure_V, r.temperature_V};
    for (int ch = 0; ch < 2; ++ch) {
      const auto& served = truth.conversions[ch].at(r.boot);
      const std::size_t first = static_cast<std::size_t>(r.seq) * oversample;
      REQUIRE(first + oversample <= served.size());
      double simavr_sum = 0, hardware_sum = 0;
      for (std::size_t i = first; i < first + oversample; ++i) {
        simavr_sum += std::floor(served[i] * 1023.0 / kVref_mV);    // simavr's avr_adc.c
        hardware_sum += std::floor(served[i] * 1024.0 / kVref_mV);  // ATmega2560 datasheet
      }
      const double counts_sum = volts[ch] / calibration.adc_reference_V * 1024.0 * oversample;
      INFO("boot " << r.boot << " seq " << r.seq << " channel " << ch);
      // exact: the CSV carries 6 decimals of volts, 1e-6 V = 2e-4 counts
      REQUIRE(std::abs(counts_sum - simavr_sum) < 1e-3 * oversample);
      // the decoded integer sum (the line above pins it to 1e-3 counts), against a real ATmega
      const double hardware_error = std::abs(std::round(counts_sum) - hardware_sum) / oversample;
      worst_hardware = std::max(worst_hardware, hardware_error);
      REQUIRE(hardware_error <= 1.0);
    }
    // calibrated columns, to the digits the CSV keeps: kPa to 4 decimals, degC to 3, and the
    // volts they are recomputed from to 6 (half a unit of each last digit, through the slope)
    REQUIRE(std::abs(r.pressure_kPa - calibration.pressure_kPa(r.pressure_V)) <=
            0.5e-4 + 0.5e-6 * std::abs(calibration.pressure_kPa_per_V));
    REQUIRE(std::abs(r.temperature_C - calibration.temperature_C(r.temperature_V)) <=
            0.5e-3 + 0.5e-6 / calibration.tmp36_V_per_C);
    ++checked;
  }
  CHECK(checked == rows.size());
  WARN("values checked in " << checked << " frames; worst mean difference to a real ATmega: " << worst_hardware
                            << " counts");
}

std::vector<std::pair<unsigned, unsigned>> received(const std::vector<Row>& rows) {
  std::vector<std::pair<unsigned, unsigned>> out;
  for (const Row& r : rows) out.emplace_back(r.boot, r.seq);
  return out;
}

}  // namespace

TEST_CASE("simavr: the shipped sketch streams 60 s at 100 Hz with no frame lost and exact values",
          "[firmware][simavr]") {
  SimulatedBoard board(PAMKIT_FIRMWARE_SHIPPED, 60.0);
  const LoggerCalibration calibration = test_calibration();
  std::optional<Banner> banner;
  const ReaderStats stats = run_reader(board, calibration, banner);
  const auto totals = board.totals();
  const Truth truth = read_truth(board.truth);
  const std::vector<Row> rows = read_csv(board.csv);

  REQUIRE(banner.has_value());
  CHECK(banner->rate_hz == 100);
  CHECK(banner->oversample == 16);
  CHECK(banner->baud == 115200);
  // 60 s at 100 Hz, less the start-up before the first sample (the banner alone is 120 bytes,
  // 11 ms at simavr's 93 us per byte): at least 5990 frames
  CHECK(totals.at("frames") >= 5990);
  CHECK(rows.size() == static_cast<std::size_t>(totals.at("frames")));
  CHECK(received(rows) == truth.intact);
  CHECK(stats.decoder.skipped_bytes == 0);
  CHECK(stats.decoder.checksum_errors == 0);
  CHECK(stats.decoder.gaps == 0);
  CHECK(stats.decoder.device_dropped == 0);
  CHECK(stats.decoder.resets == 0);
  CHECK(stats.stale_frames == 0);
  CHECK(stats.no_banner == 0);
  check_values(rows, truth, banner->oversample, calibration);
  // device time: one sample every 10 ms; micros() ticks in 4 us steps at 16 MHz and the loop
  // polls it every few us, so consecutive stamps are 10 ms within 8 us
  double worst = 0;
  for (std::size_t i = 1; i < rows.size(); ++i)
    worst = std::max(worst, std::abs(rows[i].time_s - rows[i - 1].time_s - 0.01));
  CHECK(worst <= 8e-6);
  CHECK(rows.front().time_s == 0.0);
}

TEST_CASE("simavr: 1 kHz at 1 Mbaud, no oversampling, 10 s with no frame lost", "[firmware][simavr]") {
  SimulatedBoard board(PAMKIT_FIRMWARE_FAST, 10.0);
  const LoggerCalibration calibration = test_calibration();
  std::optional<Banner> banner;
  const ReaderStats stats = run_reader(board, calibration, banner);
  const auto totals = board.totals();
  const Truth truth = read_truth(board.truth);
  const std::vector<Row> rows = read_csv(board.csv);
  REQUIRE(banner.has_value());
  CHECK(banner->rate_hz == 1000);
  CHECK(banner->baud == 1000000);
  CHECK(totals.at("frames") >= 9990);  // 10 s at 1 kHz, less the start-up
  CHECK(received(rows) == truth.intact);
  CHECK(stats.decoder.gaps == 0);
  CHECK(stats.decoder.skipped_bytes == 0);
  check_values(rows, truth, banner->oversample, calibration);
}

TEST_CASE("simavr: garbage, flipped bits, dropped bytes, resets and a pulled cable are each counted and survived",
          "[firmware][simavr][faults]") {
  SimulatedBoard board(PAMKIT_FIRMWARE_SHIPPED, 40.0, {"--fault-every", "250", "--seed", "2024"});
  const LoggerCalibration calibration = test_calibration();
  std::optional<Banner> banner;
  const ReaderStats stats = run_reader(board, calibration, banner);
  const auto t = board.totals();
  const Truth truth = read_truth(board.truth);
  const std::vector<Row> rows = read_csv(board.csv);
  const auto flips = static_cast<std::uint64_t>(t.at("fault_flip"));
  const auto drops = static_cast<std::uint64_t>(t.at("fault_drop"));
  const auto resets = static_cast<std::uint64_t>(t.at("fault_reset"));
  const auto unplugs = static_cast<std::uint64_t>(t.at("fault_unplug"));
  // 40 s at 100 Hz is about 4000 frames: 15 faults, 3 of each kind, every 250 frames
  REQUIRE(t.at("fault_garbage") >= 3);
  REQUIRE(flips >= 3);
  REQUIRE(drops >= 3);
  REQUIRE(resets >= 3);
  REQUIRE(unplugs >= 2);
  WARN("injected: garbage " << t.at("fault_garbage") << " (" << t.at("garbage_bytes") << " bytes), flips " << flips
                            << ", drops " << drops << ", resets " << resets << ", unplugs " << unplugs
                            << "; decoder: skipped " << stats.decoder.skipped_bytes << " bytes in "
                            << stats.decoder.resyncs << " resyncs, " << stats.decoder.checksum_errors
                            << " checksum errors, " << stats.decoder.banner_errors << " banner errors, "
                            << stats.decoder.gaps << " gaps, " << stats.decoder.resets << " resets, "
                            << stats.disconnects << " disconnects");

  // no intact frame lost, none invented, all in order
  CHECK(received(rows) == truth.intact);
  // every byte that was not part of an intact frame or banner is accounted for
  CHECK(stats.decoder.skipped_bytes == static_cast<std::uint64_t>(t.at("garbage_bytes") + t.at("damaged_bytes")));
  // a flipped bit or a dropped byte costs exactly its frame: one gap of one frame each
  CHECK(stats.decoder.gaps == flips + drops);
  CHECK(stats.decoder.missing_frames == flips + drops);
  CHECK(stats.decoder.checksum_errors >= flips + drops);
  CHECK(stats.decoder.device_dropped == 0);
  // resets and re-plugs restart the board: each shows as a reset, with its banner
  CHECK(stats.decoder.resets == resets + unplugs);
  CHECK(stats.decoder.banners == 1 + resets + unplugs);
  CHECK(stats.disconnects == unplugs);
  CHECK(stats.opens == 1 + unplugs);
  CHECK(stats.stale_frames == 0);
  check_values(rows, truth, banner->oversample, calibration);
  // one time base across boots: time only goes forward
  for (std::size_t i = 1; i < rows.size(); ++i) REQUIRE(rows[i].time_s > rows[i - 1].time_s);
}
