// Bindings of include/pamkit/logger: the logger's calibration, the serial ports and the Reader
// that `pamkit log` drives. Reader.poll() releases the GIL while it waits for the port, so Ctrl-C
// reaches Python between polls (rows already written are on disk: the reader flushes each read).
// The calibration's conversions are vectorised (a float gives a float, an array an array): the
// synthetic logger (pamkit.instruments) turns its counts into kPa and degC through them too.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "bind_fields.hpp"
#include "pamkit/logger/reader.hpp"

namespace py = pybind11;

namespace pamkit::python {
namespace {

py::dict stats_dict(const logger::ReaderStats& s) {
  py::dict d;
  d["bytes"] = s.decoder.bytes;
  d["frames"] = s.decoder.frames;
  d["banners"] = s.decoder.banners;
  d["skipped_bytes"] = s.decoder.skipped_bytes;
  d["resyncs"] = s.decoder.resyncs;
  d["checksum_errors"] = s.decoder.checksum_errors;
  d["banner_errors"] = s.decoder.banner_errors;
  d["gaps"] = s.decoder.gaps;
  d["missing_frames"] = s.decoder.missing_frames;
  d["device_dropped"] = s.decoder.device_dropped;
  d["duplicates"] = s.decoder.duplicates;
  d["resets"] = s.decoder.resets;
  d["rows"] = s.rows;
  d["stale_frames"] = s.stale_frames;
  d["no_banner"] = s.no_banner;
  d["opens"] = s.opens;
  d["disconnects"] = s.disconnects;
  d["seconds"] = s.seconds;
  return d;
}

py::object banner_dict(const std::optional<logger::Banner>& banner) {
  if (!banner) return py::none();
  py::dict d;
  d["firmware_version"] = banner->firmware_version;
  d["frame_version"] = banner->frame_version;
  d["rate_hz"] = banner->rate_hz;
  d["period_us"] = banner->period_us;
  d["oversample"] = banner->oversample;
  d["baud"] = banner->baud;
  d["vref_V"] = banner->vref_V;
  d["line"] = banner->line;
  return std::move(d);
}

}  // namespace

void bind_logger(py::module_& m) {
  py::module_ lm = m.def_submodule("logger", "The Arduino Mega logger's host side (firmware/pamkit_logger).");

  py::class_<logger::LoggerCalibration> calibration(
      lm, "LoggerCalibration", "Counts to volts (ADC reference), volts to gauge kPa (61CP fit) and to degC (TMP36).");
  bind_fields(calibration);
  calibration
      .def("volts", py::vectorize(&logger::LoggerCalibration::volts), py::arg("mean_counts"),
           "V at the pin for a mean conversion [counts] (a frame's sum of conversions / oversample); float or array")
      .def("pressure_kPa", py::vectorize(&logger::LoggerCalibration::pressure_kPa), py::arg("volts"),
           "gauge pressure [kPa] for the transducer's V; float or array")
      .def("temperature_C", py::vectorize(&logger::LoggerCalibration::temperature_C), py::arg("volts"),
           "TMP36 temperature [degC] for its V; float or array");

  lm.def(
      "fit_pressure",
      [](const std::vector<double>& psi, const std::vector<double>& volts) {
        const logger::PressureFit fit = logger::fit_pressure(psi, volts);
        return py::dict(py::arg("kPa_per_V") = fit.kPa_per_V, py::arg("offset_kPa") = fit.offset_kPa,
                        py::arg("max_residual_kPa") = fit.max_residual_kPa);
      },
      py::arg("applied_psi"), py::arg("measured_V"),
      "Least-squares line gauge kPa = offset + slope V through the calibration points (appendix B: 0-80 psi "
      "every 10 psi). Returns {kPa_per_V, offset_kPa, max_residual_kPa}; ValueError naming the problem.");

  lm.def(
      "list_ports",
      [] {
        py::list out;
        for (const auto& p : logger::list_ports()) {
          out.append(py::dict(py::arg("path") = p.path, py::arg("description") = p.description,
                              py::arg("usb_vid") = p.usb_vid, py::arg("usb_pid") = p.usb_pid,
                              py::arg("by_id") = p.by_id));
        }
        return out;
      },
      "Serial ports (libserialport) with their /dev/serial/by-id names, which survive re-plugging.");

  lm.attr("ADC_FULL_SCALE") = PAMKIT_ADC_FULL_SCALE;  // counts of one conversion: ADC = Vin 1024 / Vref
  lm.attr("FRAME_SIZE") = PAMKIT_FRAME_SIZE;
  lm.attr("FRAME_VERSION") = PAMKIT_FRAME_VERSION;
  lm.attr("FIRMWARE_VERSION") = PAMKIT_FIRMWARE_VERSION;
  // The most a killed reader can have taken from the port and not written (besides frames held
  // for the banner): one read.
  lm.attr("READ_BYTES") = logger::Reader::kReadBytes;

  py::class_<logger::Reader>(lm, "Reader",
                             "Reads the logger on `port` into the CSV `output` (time_s, [pressure_kPa,] temperature_C, "
                             "pressure_V, temperature_V, boot, seq), whole lines written after every read; "
                             "fsync_interval_s [s]: fsync at most this often (0: every read, inf: never); an "
                             "existing output is refused (ValueError) unless replace_existing.")
      .def(py::init([](const std::string& port, const std::string& output, const logger::LoggerCalibration& calibration,
                       bool pressure_calibrated, unsigned baud, bool assert_dtr, double banner_timeout_s,
                       double reconnect_interval_s, double fsync_interval_s, bool replace_existing) {
             logger::ReaderOptions options;
             options.port = port;
             options.baud = baud;
             options.assert_dtr = assert_dtr;
             options.banner_timeout_s = banner_timeout_s;
             options.reconnect_interval_s = reconnect_interval_s;
             options.fsync_interval_s = fsync_interval_s;
             options.replace_existing = replace_existing;
             return std::make_unique<logger::Reader>(options, calibration, pressure_calibrated, output);
           }),
           py::arg("port"), py::arg("output"), py::arg("calibration"), py::arg("pressure_calibrated") = true,
           py::arg("baud") = 115200, py::arg("assert_dtr") = true, py::arg("banner_timeout_s") = 3.0,
           py::arg("reconnect_interval_s") = 0.25, py::arg("fsync_interval_s") = 1.0,
           py::arg("replace_existing") = false)
      .def("poll", &logger::Reader::poll, py::arg("timeout_s"), py::call_guard<py::gil_scoped_release>(),
           "Waits up to timeout_s [s] for data, writes the rows; reopens a lost port. Returns rows written.")
      .def(
          "stats", [](const logger::Reader& r) { return stats_dict(r.stats()); },
          "Counters: bytes, frames, skipped_bytes, resyncs, checksum_errors, gaps, missing_frames, resets, "
          "disconnects, ...")
      .def(
          "last",
          [](const logger::Reader& r) -> py::object {
            if (!r.last()) return py::none();
            const auto& x = *r.last();
            return py::dict(py::arg("time_s") = x.time_s, py::arg("pressure_kPa") = x.pressure_kPa,
                            py::arg("temperature_C") = x.temperature_C, py::arg("pressure_V") = x.pressure_V,
                            py::arg("temperature_V") = x.temperature_V, py::arg("boot") = x.boot,
                            py::arg("seq") = x.seq);
          },
          "The last row written, or None.")
      .def(
          "banner", [](const logger::Reader& r) { return banner_dict(r.banner()); }, "The board's banner, or None.")
      .def_property_readonly("connected", &logger::Reader::connected)
      .def_property_readonly("last_error", &logger::Reader::last_error, "why the last open failed, '' if it did not")
      .def("close", &logger::Reader::close)
      .def(
          "__enter__", [](logger::Reader& r) -> logger::Reader& { return r; }, py::return_value_policy::reference)
      .def("__exit__", [](logger::Reader& r, py::args) { r.close(); });
}

}  // namespace pamkit::python
