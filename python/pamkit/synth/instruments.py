"""The instruments of the thesis's bench, as they read a test: each on its own clock and at its
own sample rate, with its own noise and resolution (thesis section 3.2 and appendix B).

- :class:`TensileMachine`: the Instron 4482 with its 100 kN load cell. It records crosshead
  displacement and force at its own rate; its clock is the reference (machine time).
- :class:`ArduinoLogger`: the Arduino Mega 2560 reading the 61CP pressure transducer (A0) and
  the TMP36 inside the muscle (A1) through its 10-bit ADC with a 5 V reference, on its own
  clock (an offset and a drift in ppm against the machine's), at its own rate. Its host
  software is the real logger's: ``pamkit._core.logger.LoggerCalibration`` (C++) turns counts
  into volts and volts into kPa (gauge) and °C, the units of the CSV ``pamkit log`` writes,
  and ``fit_pressure`` fits appendix B's calibration, as ``pamkit log`` does with a real board.
  What stays here is the synthetic instrument's physics: what the transducer and the TMP36 put
  out, the ADC's noise and rounding, the clocks.
- :func:`merge_logs`: the hand synchronisation of the two logs after the test (thesis appendix
  G.2 aligns them by hand) and the merge onto the machine's time base by linear
  interpolation, into the columns of a measured time series, SI (pamkit.io.columns).

Every random draw takes a ``numpy.random.Generator``; nothing here holds global state. The
"truth" an instrument reads is a dense record on the machine's clock (``time_s`` and the true
channels in SI, e.g. a :class:`pamkit.Measurement`), linear between its samples; instruments
sample it at their own instants.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from pamkit._core.logger import ADC_FULL_SCALE, LoggerCalibration, fit_pressure
from pamkit.io.columns import to_si, value_from_si
from pamkit.units import KILOPASCAL_PER_PSI, PASCAL_PER_KILOPASCAL

# The host's defaults, declared in C++ (include/pamkit/logger/calibration.hpp): the nominal 5 V
# reference and the TMP36's datasheet line. The synthetic sensors and ADC start from them.
_HOST = LoggerCalibration()
# Appendix G.2's conversion of the 61CP's volts, psi = 25 V - 14 (the thesis's calibration at
# 30-40 psi): the host's line before appendix B's calibration, and the nominal unit's inverse.
G2_PSI_PER_V = 25.0
G2_OFFSET_PSI = -14.0

# ----------------------------------------------------------------------------------------------
# Tensile machine


@dataclass(frozen=True)
class LoadCell:
    """A strain-gauge load cell and its conditioning, reading a force far below its capacity.

    Thesis section 3.2: the Instron 4482 measured the muscle's force on a 100 kN load cell
    while the muscle pulled a few hundred newtons, i.e. below 1 % of the cell's range, where its
    noise and resolution (fixed fractions of capacity) matter.
    """

    capacity_N: float = 100e3
    """full scale of the cell [N] (thesis 3.2: 100 kN)"""
    noise_rms_N: float = 1.0
    """white noise on each sample [N], RMS; about 1e-5 of a 100 kN cell's capacity, the noise
    floor of a strain-gauge cell and its 5500-series conditioning at a few tens of Hz"""
    resolution_N: float = 0.2
    """step of the recorded force [N]: 2 x capacity / 2^20, a 20-bit conversion of +-100 kN"""
    zero_offset_N: float = 0.0
    """reading at zero force left after taring [N]"""

    def validate(self) -> None:
        _check_positive("LoadCell.capacity_N", self.capacity_N)
        _check_nonnegative("LoadCell.noise_rms_N", self.noise_rms_N)
        _check_nonnegative("LoadCell.resolution_N", self.resolution_N)


@dataclass(frozen=True)
class TensileMachineSettings:
    """The Instron 4482's acquisition: one clock (the reference), one rate for both channels."""

    sample_rate_Hz: float = 20.0
    """samples per second of displacement and force [Hz]; Bluehill logs at 10-50 Hz for a
    test of a few minutes"""
    displacement_resolution_m: float = 1e-6
    """step of the recorded crosshead displacement [m]: the export's mm with 3 decimals (the
    4400 series' encoder resolves finer); the thesis converts that column from mm (appendix G.2)"""
    load_cell: LoadCell = field(default_factory=LoadCell)

    def validate(self) -> None:
        _check_positive("TensileMachineSettings.sample_rate_Hz", self.sample_rate_Hz)
        _check_nonnegative("TensileMachineSettings.displacement_resolution_m", self.displacement_resolution_m)
        self.load_cell.validate()


@dataclass
class MachineLog:
    """What the tensile machine exports: its own time, crosshead displacement and force."""

    time_s: np.ndarray
    """machine time [s], from the start of the record"""
    displacement_m: np.ndarray
    """crosshead displacement from its position at the start [m] (the muscle's elongation)"""
    force_N: np.ndarray
    """load cell [N]"""


class TensileMachine:
    """The Instron 4482 reading a test: samples at k / rate on its own (reference) clock."""

    def __init__(self, settings: TensileMachineSettings | None = None):
        self.settings = settings if settings is not None else TensileMachineSettings()
        self.settings.validate()

    def sample_times(self, duration_s: float) -> np.ndarray:
        """The machine's sample instants over [0, duration_s] [s]."""
        count = int(np.floor(duration_s * self.settings.sample_rate_Hz + 1e-9)) + 1
        return np.arange(count) / self.settings.sample_rate_Hz

    def record(self, truth, rng: np.random.Generator, duration_s: float | None = None) -> MachineLog:
        """Samples the true crosshead elongation and force of `truth` (time_s, elongation_m,
        force_N on the machine's clock) over [0, duration_s] (default: the truth's end).

        Force: truth + zero offset + N(0, noise_rms_N), rounded to resolution_N.
        Displacement: rounded to displacement_resolution_m (the encoder has no noise to speak of).
        """
        time = np.asarray(truth.time_s, dtype=float)
        end = time[-1] if duration_s is None else duration_s
        if time[0] > 0.0 or end > time[-1] + 1e-9:
            raise ValueError(
                f"TensileMachine.record: the truth spans [{time[0]}, {time[-1]}] s, the record needs [0, {end}] s"
            )
        t = self.sample_times(end)
        cell = self.settings.load_cell
        force = np.interp(t, time, np.asarray(truth.force_N, dtype=float))
        force = force + cell.zero_offset_N + rng.normal(0.0, cell.noise_rms_N, t.size)
        displacement = np.interp(t, time, np.asarray(truth.elongation_m, dtype=float))
        return MachineLog(
            time_s=t,
            displacement_m=_quantise(displacement, self.settings.displacement_resolution_m),
            force_N=_quantise(force, cell.resolution_N),
        )


# ----------------------------------------------------------------------------------------------
# Arduino logger


@dataclass(frozen=True)
class PressureTransducer:
    """The 61CP ceramic capacitive pressure transducer (appendix B): a linear voltage output.

    The defaults are the inverse of appendix G.2's conversion ``psi = 25 V - 14`` (the thesis's
    calibration at 30-40 psi): 0.04 V/psi, 0.56 V at zero gauge pressure. A real unit differs
    from them a little, which is why appendix B calibrates it.
    """

    offset_V: float = -G2_OFFSET_PSI / G2_PSI_PER_V
    """output at zero gauge pressure [V] (0.56)"""
    sensitivity_V_per_psi: float = 1.0 / G2_PSI_PER_V
    """output per psi of gauge pressure [V/psi] (0.04)"""
    noise_rms_V: float = 2e-3
    """electrical noise at the ADC input [V], RMS (supply ripple, USB ground): about 0.4 of a count"""

    def validate(self) -> None:
        _check_positive("PressureTransducer.sensitivity_V_per_psi", self.sensitivity_V_per_psi)
        _check_nonnegative("PressureTransducer.noise_rms_V", self.noise_rms_V)

    def voltage(self, gauge_pressure_Pa: np.ndarray) -> np.ndarray:
        """Noise-free output for a gauge pressure [Pa] [V]: the unit's line, which its
        datasheet and appendix B give per psi."""
        kilopascals = value_from_si("gauge_pressure_Pa", np.asarray(gauge_pressure_Pa, dtype=float))
        return self.offset_V + self.sensitivity_V_per_psi * kilopascals / KILOPASCAL_PER_PSI


@dataclass(frozen=True)
class TMP36:
    """The TMP36 inside the muscle (appendix B): by default the datasheet's line, 10 mV/°C with
    500 mV at 0 °C, as the host's LoggerCalibration declares it."""

    offset_V: float = _HOST.tmp36_offset_V
    """output at 0 °C [V] (datasheet: 500 mV)"""
    sensitivity_V_per_C: float = _HOST.tmp36_V_per_C
    """output per °C [V/°C] (datasheet: 10 mV/°C)"""
    noise_rms_V: float = 2e-3
    """electrical noise at the ADC input [V], RMS: about 0.4 of a count, 0.2 °C"""

    def validate(self) -> None:
        _check_positive("TMP36.sensitivity_V_per_C", self.sensitivity_V_per_C)
        _check_nonnegative("TMP36.noise_rms_V", self.noise_rms_V)

    def voltage(self, temperature_K: np.ndarray) -> np.ndarray:
        """Noise-free output for a temperature [K] [V]: the datasheet's line, in °C."""
        celsius = value_from_si("temperature_K", np.asarray(temperature_K, dtype=float))
        return self.offset_V + self.sensitivity_V_per_C * celsius


def appendix_g2_calibration() -> LoggerCalibration:
    """The host's calibration by appendix G.2's line, psi = 25 V - 14: the exact inverse of the
    nominal transducer, before appendix B's calibration of a unit."""
    return LoggerCalibration(
        pressure_kPa_per_V=G2_PSI_PER_V * KILOPASCAL_PER_PSI, pressure_offset_kPa=G2_OFFSET_PSI * KILOPASCAL_PER_PSI
    )


@dataclass(frozen=True)
class ArduinoLoggerSettings:
    """The Arduino Mega 2560 logger: its clock, its ADC, and the two sensors on A0 and A1."""

    sample_rate_Hz: float = 50.0
    """samples per second of both channels, on the logger's own clock [Hz]"""
    clock_offset_s: float = 10.0
    """the logger clock's reading at machine time 0 [s]: it was started before the machine"""
    clock_drift_ppm: float = 0.0
    """how much faster the logger clock runs than the machine's [ppm] (positive: fast)"""
    timestamp_resolution_s: float = 1e-3
    """step of the logged time stamps [s]: millis() (appendix G.2 divides them by 1000)"""
    adc_reference_V: float = _HOST.adc_reference_V
    """the ADC's actual reference, AVCC [V] (the host assumes its calibration's adc_reference_V)"""
    oversample: int = 1
    """conversions summed per channel and sample (1: one analogRead, as the thesis's
    CoolTerm logging; the pamkit firmware sums 16)"""
    pressure: PressureTransducer = field(default_factory=PressureTransducer)
    temperature: TMP36 = field(default_factory=TMP36)

    def validate(self) -> None:
        _check_positive("ArduinoLoggerSettings.sample_rate_Hz", self.sample_rate_Hz)
        _check_nonnegative("ArduinoLoggerSettings.timestamp_resolution_s", self.timestamp_resolution_s)
        _check_positive("ArduinoLoggerSettings.adc_reference_V", self.adc_reference_V)
        if not 1 <= self.oversample <= 64:
            raise ValueError(f"ArduinoLoggerSettings.oversample = {self.oversample} is outside [1, 64]")
        if not abs(self.clock_drift_ppm) < 1e5:
            raise ValueError(f"ArduinoLoggerSettings.clock_drift_ppm = {self.clock_drift_ppm} is outside (-1e5, 1e5)")
        self.pressure.validate()
        self.temperature.validate()


@dataclass
class LoggerLog:
    """What the logger's host software writes in its CSV: its own time stamps, raw counts,
    calibrated values in the CSV's units (kPa gauge, °C)."""

    time_s: np.ndarray
    """logger clock at each sample [s] (millis() / 1000)"""
    pressure_counts: np.ndarray
    """A0: sum of `oversample` conversions [counts]"""
    temperature_counts: np.ndarray
    """A1: sum of `oversample` conversions [counts]"""
    pressure_kPa: np.ndarray
    """gauge pressure from the calibration [kPa]"""
    temperature_C: np.ndarray
    """TMP36 temperature [°C]"""


class ArduinoLogger:
    """The Arduino Mega logging the transducer and the TMP36, with its host software's
    calibration (appendix B): `calibration`, the C++ LoggerCalibration ``pamkit log`` uses,
    appendix G.2's line until :meth:`calibrate` fits this unit's."""

    def __init__(self, settings: ArduinoLoggerSettings | None = None, calibration: LoggerCalibration | None = None):
        self.settings = settings if settings is not None else ArduinoLoggerSettings()
        self.settings.validate()
        self.calibration = calibration if calibration is not None else appendix_g2_calibration()
        self.calibration.validate()

    # clocks ---------------------------------------------------------------------------------

    def machine_time(self, logger_time_s: np.ndarray) -> np.ndarray:
        """Machine time at which the logger's clock reads `logger_time_s` [s]."""
        s = self.settings
        return (np.asarray(logger_time_s, dtype=float) - s.clock_offset_s) / (1.0 + s.clock_drift_ppm * 1e-6)

    def logger_time(self, machine_time_s: np.ndarray) -> np.ndarray:
        """The logger clock's reading at machine time `machine_time_s` [s]."""
        s = self.settings
        return s.clock_offset_s + (1.0 + s.clock_drift_ppm * 1e-6) * np.asarray(machine_time_s, dtype=float)

    def sample_clock_times(self, start_s: float, stop_s: float) -> np.ndarray:
        """Logger clock readings of the samples taken between machine times start_s and stop_s:
        every 1 / sample_rate_Hz of the logger's clock, from a whole number of periods [s]."""
        period = 1.0 / self.settings.sample_rate_Hz
        first, last = self.logger_time(np.array([start_s, stop_s]))
        return np.arange(np.ceil(first / period - 1e-9), np.floor(last / period + 1e-9) + 1) * period

    def sample_times(self, start_s: float, stop_s: float) -> np.ndarray:
        """The same samples' instants in machine time [s] (to simulate the truth at)."""
        return self.machine_time(self.sample_clock_times(start_s, stop_s))

    # the ADC --------------------------------------------------------------------------------

    def counts(self, volts: np.ndarray, noise_rms_V: float, rng: np.random.Generator) -> np.ndarray:
        """Sums of `oversample` conversions of `volts`, each with its own noise: per conversion,
        counts = round((V + noise) * 1024 / Vref), clipped to [0, 1023] (1024: the frame header's
        PAMKIT_ADC_FULL_SCALE). ATmega2560 datasheet, "ADC Conversion Result" (ADC = Vin 1024 /
        Vref) and "ADC Accuracy Definitions" (the ideal first transition is at 0.5 LSB, hence
        rounding, not flooring)."""
        s = self.settings
        volts = np.asarray(volts, dtype=float)
        total = np.zeros(volts.shape, dtype=np.int64)
        for _ in range(s.oversample):
            noisy = volts + rng.normal(0.0, noise_rms_V, volts.shape) if noise_rms_V > 0 else volts
            conversion = np.floor(noisy * ADC_FULL_SCALE / s.adc_reference_V + 0.5)
            total += np.clip(conversion, 0, ADC_FULL_SCALE - 1).astype(np.int64)
        return total

    def volts(self, counts: np.ndarray) -> np.ndarray:
        """What the host takes sums of `oversample` conversions to mean [V]: their mean through
        LoggerCalibration.volts, as the reader does with a frame's counts (decoder.hpp,
        ``Sample::mean_counts``)."""
        return self.calibration.volts(np.asarray(counts, dtype=float) / self.settings.oversample)

    def pressure_kPa(self, counts: np.ndarray) -> np.ndarray:
        """Host: gauge pressure from A0 counts, with the calibration [kPa]."""
        return self.calibration.pressure_kPa(self.volts(counts))

    def temperature_C(self, counts: np.ndarray) -> np.ndarray:
        """Host: temperature from A1 counts with the calibration's TMP36 line (the datasheet's,
        not the unit's) [°C]."""
        return self.calibration.temperature_C(self.volts(counts))

    def volts_per_count(self) -> float:
        """What the host takes one count of a sample's sum to be [V]: Vref / 1024 / oversample."""
        return float(self.volts(1.0))

    def pressure_step_Pa(self) -> float:
        """The calibrated pressure's quantum: one count of a sample's sum [Pa] (the
        calibration's slope is in kPa/V, as its file gives it)."""
        return self.calibration.pressure_kPa_per_V * PASCAL_PER_KILOPASCAL * self.volts_per_count()

    def temperature_step_K(self) -> float:
        """The TMP36 reading's quantum: one count of a sample's sum [K] (a step of one °C is one K)."""
        return self.volts_per_count() / self.calibration.tmp36_V_per_C

    # calibration and recording --------------------------------------------------------------

    def calibrate(
        self, rng: np.random.Generator, points_psi=tuple(range(0, 90, 10)), readings_per_point: int = 20
    ) -> LoggerCalibration:
        """Appendix B's calibration: known gauge pressures from 0 to 80 psi every 10 psi, the
        logger's mean reading at each in the host's volts, the least-squares line of
        ``fit_pressure`` (what ``pamkit log`` fits to a real unit's calibration file). The
        reference pressures are taken as exact here (a reference gauge's error is what the
        catalog's sensor_offset models). Sets and returns the calibration, whose reference and
        TMP36 line stay as they were."""
        s = self.settings
        volts = []
        for psi in points_psi:
            true = np.full(readings_per_point, s.pressure.voltage(psi * KILOPASCAL_PER_PSI * PASCAL_PER_KILOPASCAL))
            volts.append(float(self.volts(self.counts(true, s.pressure.noise_rms_V, rng)).mean()))
        fit = fit_pressure([float(psi) for psi in points_psi], volts)
        self.calibration = LoggerCalibration(
            **{
                **self.calibration.to_dict(),
                "pressure_kPa_per_V": fit["kPa_per_V"],
                "pressure_offset_kPa": fit["offset_kPa"],
            }
        )
        self.calibration.validate()
        return self.calibration

    def record(self, truth, rng: np.random.Generator, start_s: float, stop_s: float) -> LoggerLog:
        """Logs `truth` (time_s on the machine's clock, gauge_pressure_Pa, temperature_K; held
        at its ends outside its span, where the muscle rests) between machine times start_s
        and stop_s, on the logger's clock and at its rate.

        Per sample: the true values at the sample's instant -> sensor volts -> noisy, quantised
        counts -> the host's volts -> kPa and °C (LoggerCalibration); the time stamp is
        the logger clock, rounded down to timestamp_resolution_s (millis()).
        """
        s = self.settings
        clock = self.sample_clock_times(start_s, stop_s)
        when = self.machine_time(clock)
        time = np.asarray(truth.time_s, dtype=float)
        pressure = np.interp(when, time, np.asarray(truth.gauge_pressure_Pa, dtype=float))
        temperature = np.interp(when, time, np.asarray(truth.temperature_K, dtype=float))
        pressure_counts = self.counts(s.pressure.voltage(pressure), s.pressure.noise_rms_V, rng)
        temperature_counts = self.counts(s.temperature.voltage(temperature), s.temperature.noise_rms_V, rng)
        stamps = _floor(clock, s.timestamp_resolution_s)
        return LoggerLog(
            time_s=stamps,
            pressure_counts=pressure_counts,
            temperature_counts=temperature_counts,
            pressure_kPa=self.pressure_kPa(pressure_counts),
            temperature_C=self.temperature_C(temperature_counts),
        )


# ----------------------------------------------------------------------------------------------
# Merging


def merge_logs(machine: MachineLog, logger: LoggerLog, logger_clock_at_machine_zero_s: float) -> dict[str, np.ndarray]:
    """The two logs on the machine's time base, as a measured time series' columns, SI:
    time_s, elongation_m, force_N, gauge_pressure_Pa, temperature_K (the logger's kPa and °C
    read as a reader of its CSV reads them).

    The synchronisation is the one done by hand after the test: the logger's time stamps are
    shifted by `logger_clock_at_machine_zero_s` (the logger clock's reading when the machine
    started, as the operator judged it); the logger's drift is not corrected. Its channels are
    then linearly interpolated at the machine's sample times.

    Raises:
        ValueError: if the logger's record does not cover the machine's.
    """
    shifted = np.asarray(logger.time_s, dtype=float) - logger_clock_at_machine_zero_s
    if shifted[0] > machine.time_s[0] or shifted[-1] < machine.time_s[-1]:
        raise ValueError(
            f"merge_logs: the logger covers [{shifted[0]:.3f}, {shifted[-1]:.3f}] s of machine time, "
            f"the machine's record [{machine.time_s[0]:.3f}, {machine.time_s[-1]:.3f}] s"
        )
    return to_si(
        {
            "time_s": np.asarray(machine.time_s, dtype=float),
            "elongation_m": np.asarray(machine.displacement_m, dtype=float),
            "force_N": np.asarray(machine.force_N, dtype=float),
            "pressure_kPa": np.interp(machine.time_s, shifted, logger.pressure_kPa),
            "temperature_C": np.interp(machine.time_s, shifted, logger.temperature_C),
        }
    )


# ----------------------------------------------------------------------------------------------
# helpers


def _quantise(values: np.ndarray, step: float) -> np.ndarray:
    return np.round(values / step) * step if step > 0 else np.asarray(values, dtype=float)


def _floor(values: np.ndarray, step: float) -> np.ndarray:
    # The small allowance keeps a reading that is a whole number of steps up to rounding.
    return np.floor(values / step + 1e-9) * step if step > 0 else np.asarray(values, dtype=float)


def _check_positive(name: str, value: float) -> None:
    if not (np.isfinite(value) and value > 0):
        raise ValueError(f"{name} = {value} must be > 0")


def _check_nonnegative(name: str, value: float) -> None:
    if not (np.isfinite(value) and value >= 0):
        raise ValueError(f"{name} = {value} must be >= 0")
