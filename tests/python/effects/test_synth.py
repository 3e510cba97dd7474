"""Synthetic bench tests (pamkit.synth.dataset) and the instruments that read them (pamkit.synth.instruments).

Where the numbers come from:
- the ADC: ATmega2560, 10 bits, 5 V reference -> 1024 counts over 5 V (thesis appendix B; datasheet);
- the pressure calibration: appendix G.2's ``psi = 25 V - 14``; 1 psi = 6.894757 kPa;
- the TMP36: 10 mV/°C with 500 mV at 0 °C (datasheet, appendix B);
- the protocol ranges: pamkit.synth.dataset's (the thesis's bench tests and faster ones);
- noise sizes: the instrument settings each dataset's manifest records.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from scipy import stats

import pamkit
from pamkit._core.logger import ADC_FULL_SCALE, LoggerCalibration
from pamkit.cli import main as pamkit_main
from pamkit.effects import catalog
from pamkit.io.columns import LOGGER_CHANNELS
from pamkit.io.experiment import load_experiment
from pamkit.io.series import read_series
from pamkit.simulation import simulate_experiment
from pamkit.synth.dataset import configure_effect, hideable_effects, synthesize
from pamkit.synth.instruments import (
    TMP36,
    ArduinoLogger,
    ArduinoLoggerSettings,
    LoadCell,
    PressureTransducer,
    TensileMachine,
    TensileMachineSettings,
    merge_logs,
)

KPA_PER_PSI = 6.894757293168  # 1 psi in kPa (NIST SP 811: 6894.757293168 Pa)
VOLTS_PER_COUNT = 5.0 / 1024  # 10-bit ADC, 5 V reference
EFFECTS = hideable_effects()


class Truth:
    """A dense 'true' record on the machine's clock, SI, for the instruments to read; a channel
    not given is zero (the temperature 0 °C)."""

    def __init__(self, time_s, **channels):
        self.time_s = np.asarray(time_s, dtype=float)
        zero = {"temperature_K": 273.15}
        for name in ("elongation_m", "force_N", "gauge_pressure_Pa", "temperature_K"):
            default = np.full_like(self.time_s, zero.get(name, 0.0))
            setattr(self, name, np.asarray(channels.get(name, default), dtype=float))


def manifest(files) -> dict:
    return json.loads(files.manifest.read_text())


def on_grid(values: np.ndarray, tolerance: float = 1e-5) -> np.ndarray:
    """Whether each value is a whole number (of counts) to within `tolerance`."""
    return np.abs(values - np.round(values)) < tolerance


def pressure_counts(pressure_kPa: np.ndarray, calibration: dict) -> np.ndarray:
    """Invert the host's conversion kPa = offset + slope x counts x 5 V / 1024 (LoggerCalibration's fields)."""
    volts = (np.asarray(pressure_kPa) - calibration["pressure_offset_kPa"]) / calibration["pressure_kPa_per_V"]
    return volts / VOLTS_PER_COUNT


def temperature_counts(temperature_C: np.ndarray) -> np.ndarray:
    """Invert the TMP36's datasheet line: V = 0.5 V + 10 mV/°C x T."""
    return (0.5 + 0.01 * np.asarray(temperature_C)) / VOLTS_PER_COUNT


def in_file_units(columns: dict) -> tuple[np.ndarray, np.ndarray]:
    """An experiment's pressure [kPa] and temperature [°C], as its CSV holds them."""
    return columns["gauge_pressure_Pa"] / 1e3, columns["temperature_K"] - 273.15


# ----------------------------------------------------------------------------------------------
# the dataset and its files


def test_synth_output_loads_and_pamkit_simulate_accepts_it(tmp_path):
    files = synthesize("none", 1, tmp_path / "none")
    experiment = load_experiment(files.experiment)
    truth = manifest(files)
    # A time series' columns, all five, on one time base, SI as read.
    assert list(experiment.columns) == ["time_s", "elongation_m", "force_N", "gauge_pressure_Pa", "temperature_K"]
    # No initial_length_m: the test starts at the free inflated length (load_experiment's default).
    assert experiment.initial_length_m is None
    assert experiment.gas == pamkit.GasMode.sealed
    assert experiment.inflation_gauge_pressure_Pa == truth["protocol"]["inflation_pressure_kPa"] * 1e3
    assert experiment.build.to_dict() == truth["muscle"]
    # The machine's record: samples every 1 / rate from 0.
    rate = truth["instruments"]["tensile_machine"]["sample_rate_Hz"]
    np.testing.assert_allclose(np.diff(experiment.time_s), 1.0 / rate, rtol=1e-9)
    # The crosshead reaches the protocol's top (to the 1 µm displacement resolution).
    assert experiment.elongation_m.max() == pytest.approx(truth["protocol"]["max_elongation_m"], abs=1e-6)

    out = tmp_path / "predicted.csv"
    assert pamkit_main(["simulate", str(files.experiment), "-o", str(out)]) == 0
    predicted = read_series(out)
    np.testing.assert_array_equal(predicted["time_s"], experiment.time_s)


def test_protocol_within_design_ranges(tmp_path):
    for seed in range(6):
        truth = manifest(synthesize("none", seed, tmp_path / str(seed)))
        p = truth["protocol"]
        assert 35.0 <= p["inflation_pressure_kPa"] <= 276.0  # synth's INFLATION_KPA: the thesis's 35-276 kPa
        # 80-95 % of the free contraction, the top rounded to 0.1 mm as the machine is programmed.
        assert 0.80 * p["free_contraction_m"] - 5e-5 <= p["max_elongation_m"] <= 0.95 * p["free_contraction_m"] + 5e-5
        assert 2.5e-3 <= p["speed_m_per_s"] <= 50e-3
        assert 5 <= p["cycles"] <= 10
        # free contraction = deflated length (PAM 2: 0.225 m +- 1 mm) minus free inflated length.
        assert abs(truth["muscle"]["length_m"] - 0.225) <= 1e-3 + 1e-12
        assert p["free_contraction_m"] == pytest.approx(truth["muscle"]["length_m"] - p["free_length_m"], abs=1e-12)


def test_same_seed_gives_identical_files_and_another_seed_another_protocol(tmp_path):
    first = synthesize("heat_transfer", 11, tmp_path / "a")
    again = synthesize("heat_transfer", 11, tmp_path / "b")
    for name in ("experiment", "data", "manifest"):
        assert getattr(first, name).read_bytes() == getattr(again, name).read_bytes(), name
    other = synthesize("heat_transfer", 12, tmp_path / "c")
    assert manifest(other)["protocol"] != manifest(first)["protocol"]
    assert other.data.read_bytes() != first.data.read_bytes()


def test_protocol_build_and_instruments_do_not_depend_on_the_effect(tmp_path):
    none = manifest(synthesize("none", 21, tmp_path / "none"))
    leak = manifest(synthesize("leak", 21, tmp_path / "leak"))
    for key in ("protocol", "muscle", "instruments"):
        assert none[key] == leak[key], key


def test_manifest_holds_the_truth_and_the_experiment_does_not_mention_it(tmp_path):
    files = synthesize("sensor_offset:gain=1.05", 4, tmp_path / "x")
    truth = manifest(files)["effect"]
    assert truth["name"] == "sensor_offset"
    assert truth["parameters"]["gain"] == 1.05  # given
    assert truth["drawn"] == ["offset_Pa"]
    assert -12e3 <= truth["parameters"]["offset_Pa"] <= 12e3  # realistic range, sensor_offset.hpp
    text = (files.experiment.read_text() + files.data.read_text()).lower()
    for word in ("sensor_offset", "offset", "gain", "effect", "manifest"):
        assert word not in text, word
    # Only an experiment file's keys: load_experiment rejects unknown ones, and no [effect] section.
    assert "[muscle]" in files.experiment.read_text() and "[test]" in files.experiment.read_text()


@pytest.mark.parametrize("name", ["none"] + EFFECTS)
def test_each_catalog_effect_and_none_synthesize(tmp_path, name):
    files = synthesize(name, 5, tmp_path / name)
    truth = manifest(files)
    load_experiment(files.experiment)
    assert truth["effect"]["name"] == name
    if name == "none":
        assert truth["effect"]["largest_change"] == {"force_N": 0.0, "gauge_pressure_Pa": 0.0, "temperature_K": 0.0}
        return
    # The effect acted: the true channels moved, and since the seed fixes protocol and noise,
    # the files differ from the same seed's "none" only because of it.
    assert max(truth["effect"]["largest_change"].values()) > 0.0
    baseline = synthesize("none", 5, tmp_path / "none")
    assert files.data.read_bytes() != baseline.data.read_bytes()
    for parameter in catalog().make(name).parameters():
        value = truth["effect"]["parameters"][parameter.name]
        magnitude = abs(value) if parameter.either_sign else value  # the sign is drawn too
        assert parameter.realistic_min <= magnitude <= parameter.realistic_max, parameter.name


def test_drawn_strengths_follow_the_realistic_ranges():
    rng = np.random.default_rng(0)
    # Time constants log-uniformly: log(tau) uniform over the log of heat_transfer's 0.5-10 s.
    taus = np.array([configure_effect("heat_transfer", rng)[1]["parameters"]["time_constant_s"] for _ in range(400)])
    assert stats.kstest(np.log(taus), "uniform", args=(math.log(0.5), math.log(10.0 / 0.5))).pvalue > 1e-3
    # ... which a uniform draw would fail: its median would be 5.25 s, not sqrt(0.5 x 10) = 2.24 s.
    assert np.median(taus) == pytest.approx(math.sqrt(0.5 * 10.0), rel=0.2)
    # Other parameters uniformly: dead_volume's volume_fraction over 0.03-0.3.
    fractions = [configure_effect("dead_volume", rng)[1]["parameters"]["volume_fraction"] for _ in range(400)]
    assert stats.kstest(fractions, "uniform", args=(0.03, 0.27)).pvalue > 1e-3
    # Channel and sign at random unless given.
    skews = [configure_effect("time_skew", rng)[1] for _ in range(200)]
    assert {s["options"]["channel"] for s in skews} == set(LOGGER_CHANNELS)
    signs = {math.copysign(1.0, s["parameters"]["offset_s"]) for s in skews}
    assert signs == {-1.0, 1.0}
    given = configure_effect("time_skew:channel=force_N,offset_s=2", rng)[1]
    assert given["options"] == {"channel": "force_N"} and given["parameters"] == {"offset_s": 2.0}


def test_a_channel_effect_lands_on_a_channel_that_moves(tmp_path):
    # The baseline's gas is isothermal (polytropic n = 1): its temperature is constant, so a
    # lag or skew of it could not be seen. The drawn channel is one that moves.
    for seed in range(4):
        truth = manifest(synthesize("sensor_lag", seed, tmp_path / str(seed)))["effect"]
        assert truth["options"]["channel"] == "gauge_pressure_Pa"
        assert truth["largest_change"]["gauge_pressure_Pa"] > 0.0
    # Given explicitly, the channel is honoured, even where it changes nothing.
    truth = manifest(synthesize("sensor_lag:channel=temperature_K", 0, tmp_path / "t"))["effect"]
    assert truth["options"]["channel"] == "temperature_K"
    assert truth["largest_change"]["temperature_K"] == 0.0


# ----------------------------------------------------------------------------------------------
# quantisation and noise, in the files


def test_pressure_and_temperature_in_the_file_lie_on_the_adc_grid(tmp_path):
    files = synthesize("none", 2, tmp_path / "x")
    calibration = manifest(files)["instruments"]["pressure_calibration"]
    experiment = load_experiment(files.experiment)
    # The merge interpolates the logger's samples at the machine's times: wherever two logger
    # samples in a row read the same count the value stays on the grid. Seeds 0-11 give
    # 20-55 % of pressures and about half the temperatures on it; 10 % is the floor checked.
    pressure_kPa, temperature_C = in_file_units(experiment.columns)
    pressure = on_grid(pressure_counts(pressure_kPa, calibration))
    temperature = on_grid(temperature_counts(temperature_C))
    assert pressure.mean() > 0.10
    assert temperature.mean() > 0.10
    # Control: the model's noise-free prediction of the same test is (almost) never on the grid.
    predicted = simulate_experiment(experiment)
    assert on_grid(pressure_counts(in_file_units(predicted)[0], calibration)).mean() < 0.01
    # The grid's step: one count, 5 V / 1024 x about 25 psi/V x 6.894757 kPa/psi = 0.84 kPa.
    step = manifest(files)["instruments"]["pressure_step_Pa"]
    assert step == pytest.approx(calibration["pressure_kPa_per_V"] * VOLTS_PER_COUNT * 1e3)
    assert step == pytest.approx(25 * VOLTS_PER_COUNT * KPA_PER_PSI * 1e3, rel=0.05)


@pytest.mark.parametrize("seed", [0, 3, 7])
def test_force_in_the_file_has_the_load_cell_noise_stated_in_the_manifest(tmp_path, seed):
    files = synthesize("none", seed, tmp_path / "x")
    cell = manifest(files)["instruments"]["tensile_machine"]["load_cell"]
    experiment = load_experiment(files.experiment)
    residual = experiment.columns["force_N"] - simulate_experiment(experiment)["force_N"]
    # The model driven by the file's own elongation reproduces the true force, so what is left
    # is the load cell: white noise plus rounding to its resolution (variance step^2 / 12).
    expected = math.sqrt(cell["noise_rms_N"] ** 2 + cell["resolution_N"] ** 2 / 12)
    assert np.std(residual) == pytest.approx(expected, rel=0.12)  # 12 %: > 3 standard errors at >= 350 samples
    assert abs(np.mean(residual)) < 4 * expected / math.sqrt(residual.size) + 0.05
    # The recorded force is on the resolution's grid.
    assert on_grid(experiment.columns["force_N"] / cell["resolution_N"], 1e-6).all()


# ----------------------------------------------------------------------------------------------
# the instruments on known inputs


def test_load_cell_noise_and_resolution():
    settings = TensileMachineSettings(sample_rate_Hz=50.0, load_cell=LoadCell(noise_rms_N=1.5, resolution_N=0.2))
    t = np.linspace(0.0, 400.0, 11)
    log = TensileMachine(settings).record(
        Truth(t, force_N=np.full(t.size, 300.0), elongation_m=t * 1e-4), np.random.default_rng(3)
    )
    assert log.time_s.size == 20001  # 400 s at 50 Hz, both ends included
    expected = math.sqrt(1.5**2 + 0.2**2 / 12)
    # The standard deviation of a standard deviation of n normal samples is sigma / sqrt(2 n): 0.5 %.
    assert np.std(log.force_N) == pytest.approx(expected, rel=0.03)
    assert np.mean(log.force_N) == pytest.approx(300.0, abs=4 * expected / math.sqrt(log.time_s.size))
    assert on_grid(log.force_N / 0.2, 1e-6).all()
    # Displacement: exact up to its 1 µm resolution.
    np.testing.assert_allclose(log.displacement_m, log.time_s * 1e-4, atol=0.5e-6 + 1e-12)


def test_logger_reads_the_adc_grid_and_the_appendix_b_calibration():
    logger = ArduinoLogger(ArduinoLoggerSettings(sample_rate_Hz=50.0, clock_offset_s=0.0))
    calibration = logger.calibrate(np.random.default_rng(1))
    # A nominal 61CP calibrates to appendix G.2's line, psi = 25 V - 14, to within the ADC's
    # resolution (one count is 0.12 psi).
    assert calibration.pressure_kPa_per_V == pytest.approx(25.0 * KPA_PER_PSI, rel=0.005)
    assert calibration.pressure_offset_kPa == pytest.approx(-14.0 * KPA_PER_PSI, abs=0.15 * KPA_PER_PSI)
    t = np.linspace(0.0, 20.0, 201)
    truth = Truth(t, gauge_pressure_Pa=(100.0 + 10.0 * t) * 1e3, temperature_K=23.0 + 0.1 * t + 273.15)
    log = logger.record(truth, np.random.default_rng(2), 0.0, 20.0)
    assert on_grid(pressure_counts(log.pressure_kPa, calibration.to_dict())).all()
    assert on_grid(temperature_counts(log.temperature_C)).all()
    np.testing.assert_array_equal(temperature_counts(log.temperature_C).round(), log.temperature_counts)
    # Readings follow the truth to within half a count plus the 2 mV noise (4 sigma).
    when = logger.machine_time(log.time_s)
    half_count_kPa = 0.5 * 25 * VOLTS_PER_COUNT * KPA_PER_PSI
    noise_kPa = 4 * 2e-3 / 0.04 * KPA_PER_PSI
    assert np.abs(log.pressure_kPa - (100.0 + 10.0 * when)).max() < half_count_kPa + noise_kPa + 0.2
    # TMP36: half a count is 0.24 °C, the noise 0.2 °C RMS.
    assert np.abs(log.temperature_C - (23.0 + 0.1 * when)).max() < 0.5 * VOLTS_PER_COUNT / 0.01 + 4 * 0.2


def test_the_host_side_is_the_logger_readers_calibration():
    # ATmega2560 datasheet: ADC = Vin 1024 / Vref, so 512 counts at 5 V are 2.5 V; the TMP36 reads
    # 0.75 V, 153.6 counts, as 25 °C (datasheet: 0.5 V + 10 mV/°C x T).
    logger = ArduinoLogger()
    assert ADC_FULL_SCALE == 1024
    np.testing.assert_array_equal(logger.volts(np.array([0, 512, 1023])), [0.0, 2.5, 1023 * VOLTS_PER_COUNT])
    assert logger.temperature_C(np.array([153.6]))[0] == pytest.approx(25.0, abs=1e-12)
    # Before appendix B's calibration the host reads appendix G.2's psi = 25 V - 14, the nominal
    # transducer's exact inverse.
    nominal = PressureTransducer()
    gauge_kPa = np.linspace(0.0, 600.0, 13)
    host = logger.calibration
    np.testing.assert_allclose(host.pressure_kPa(nominal.voltage(gauge_kPa * 1e3)), gauge_kPa, rtol=0, atol=1e-12)
    # The C++ conversions take arrays and floats alike, and agree with themselves.
    assert isinstance(host.volts(512.0), float)
    volts = np.linspace(0.0, 5.0, 11)
    np.testing.assert_array_equal(host.pressure_kPa(volts), [host.pressure_kPa(float(v)) for v in volts])
    # The calibration is the one `pamkit log` loads from a real unit's calibration file.
    assert isinstance(host, LoggerCalibration)


def test_oversampled_sums_read_as_their_mean():
    # The pamkit firmware sums 16 conversions per sample and the host divides by 16 before turning
    # counts into volts (decoder.hpp's mean_counts): noise-free, a sum of 16 conversions of one
    # voltage is 16 single conversions, and reads as one.
    voltage = np.linspace(0.3, 4.5, 50)
    one = ArduinoLogger(ArduinoLoggerSettings(oversample=1))
    sixteen = ArduinoLogger(ArduinoLoggerSettings(oversample=16))
    single = one.counts(voltage, 0.0, np.random.default_rng(0))
    summed = sixteen.counts(voltage, 0.0, np.random.default_rng(0))
    np.testing.assert_array_equal(summed, 16 * single)
    np.testing.assert_array_equal(sixteen.pressure_kPa(summed), one.pressure_kPa(single))
    np.testing.assert_array_equal(sixteen.temperature_C(summed), one.temperature_C(single))
    # One count of the sum is a sixteenth of one conversion's count: 5 V / 1024 / 16.
    assert sixteen.pressure_step_Pa() == pytest.approx(one.pressure_step_Pa() / 16, rel=1e-15)
    assert one.temperature_step_K() == pytest.approx(VOLTS_PER_COUNT / 0.01, rel=1e-15)


def test_calibration_absorbs_the_units_own_offset_and_sensitivity():
    unit = PressureTransducer(offset_V=0.58, sensitivity_V_per_psi=0.0392, noise_rms_V=0.0)
    logger = ArduinoLogger(ArduinoLoggerSettings(pressure=unit))
    calibration = logger.calibrate(np.random.default_rng(0))
    # psi = (V - 0.58) / 0.0392: slope 25.51 psi/V, intercept -14.80 psi; 9 points 10 psi apart
    # read to a count (0.12 psi) fit it to better than 0.5 % and 0.2 psi.
    assert calibration.pressure_kPa_per_V == pytest.approx(KPA_PER_PSI / 0.0392, rel=0.005)
    assert calibration.pressure_offset_kPa == pytest.approx(-0.58 / 0.0392 * KPA_PER_PSI, abs=0.2 * KPA_PER_PSI)


def test_logger_clock_drift_shows_as_a_growing_skew_after_the_merge():
    # A logger 1 % fast (1e4 ppm, far beyond a real one, to stand above the quantisation): after
    # a hand synchronisation at the start, its reading at machine time t is the truth at
    # t / 1.01, i.e. late by t x 0.01 / 1.01. Noise-free sensors, and the default calibration,
    # which is the exact inverse of the nominal transducer (appendix G.2: 25 psi/V, -14 psi).
    settings = ArduinoLoggerSettings(
        sample_rate_Hz=100.0,
        clock_offset_s=12.0,
        clock_drift_ppm=1e4,
        pressure=PressureTransducer(noise_rms_V=0.0),
        temperature=TMP36(noise_rms_V=0.0),
    )
    logger = ArduinoLogger(settings)
    t = np.linspace(-2.0, 102.0, 105)
    slope_kPa_per_s = 2.0  # up to 252 kPa: inside the ADC's range (5 V is 111 psi, 765 kPa)
    truth = Truth(t, gauge_pressure_Pa=(50.0 + slope_kPa_per_s * np.clip(t, 0, None)) * 1e3)
    logger_log = logger.record(truth, np.random.default_rng(0), -1.0, 101.0)
    machine_log = TensileMachine(TensileMachineSettings(sample_rate_Hz=10.0)).record(
        Truth(np.linspace(0.0, 100.0, 11)), np.random.default_rng(0)
    )
    merged = merge_logs(machine_log, logger_log, logger_clock_at_machine_zero_s=12.0)
    late = merged["time_s"] > 90.0
    expected = slope_kPa_per_s * merged["time_s"][late] * (1 - 1 / 1.01)  # about 1.9 kPa
    error = 50.0 + slope_kPa_per_s * merged["time_s"][late] - merged["gauge_pressure_Pa"][late] / 1e3
    # Half a count of quantisation: 0.5 x 5 V / 1024 x 25 psi/V x 6.894757 kPa/psi = 0.42 kPa.
    assert np.abs(error - expected).max() < 0.5 * 25 * VOLTS_PER_COUNT * KPA_PER_PSI + 1e-6
    # Without the drift the same check fails: the lag is 4 times the quantisation.
    assert np.abs(error).max() > 1.5
    # Its time stamps are its own: millis() (1 ms), every 10 ms of its own clock.
    np.testing.assert_allclose(np.diff(logger_log.time_s), 0.01, atol=1.001e-3)


def test_merge_refuses_a_logger_that_does_not_cover_the_machine():
    machine = TensileMachine().record(Truth(np.linspace(0, 10, 11)), np.random.default_rng(0))
    logger = ArduinoLogger(ArduinoLoggerSettings(clock_offset_s=5.0))
    log = logger.record(Truth(np.linspace(0, 10, 11)), np.random.default_rng(0), 2.0, 10.0)
    with pytest.raises(ValueError, match="logger covers"):
        merge_logs(machine, log, 5.0)


# ----------------------------------------------------------------------------------------------
# the command line


@pytest.mark.parametrize(
    ("spec", "named"),
    [
        ("leak:tau=3", ["tau", "time_constant_s"]),  # unknown key: named, with the known ones
        ("leak:time_constant_s=abc", ["time_constant_s", "abc"]),  # not a number
        ("sensor_lag:channel=voltage", ["channel", "voltage"]),
        ("no_such_effect", ["no_such_effect", "heat_transfer"]),  # unknown effect, and the known
        ("none:seed=3", ["none", "seed"]),
        ("leak:time_constant_s", ["time_constant_s", "key=value"]),
    ],
)
def test_bad_effect_text_is_a_clear_error(tmp_path, capsys, spec, named):
    out = tmp_path / "out"
    assert pamkit_main(["synth", "--effect", spec, "--seed", "1", "-o", str(out)]) == 2
    message = capsys.readouterr().err
    assert message.startswith("pamkit synth: error: ")
    for word in named:
        assert word in message
    assert not out.exists()  # nothing written


def test_cli_writes_the_three_files_and_exits_2_on_a_bad_spec(tmp_path, run_pamkit):
    ok = run_pamkit("synth", "--effect", "dead_volume:volume_fraction=0.1", "--seed", 3, "-o", tmp_path / "dv")
    assert ok.returncode == 0, ok.stderr
    assert sorted(p.name for p in (tmp_path / "dv").iterdir()) == ["experiment.csv", "experiment.toml", "manifest.json"]
    assert json.loads((tmp_path / "dv" / "manifest.json").read_text())["effect"]["parameters"] == {
        "volume_fraction": 0.1
    }
    assert "volume_fraction" not in ok.stdout  # the truth is not printed
    bad = run_pamkit("synth", "--effect", "dead_volume:fraction=0.1", "--seed", 3, "-o", tmp_path / "bad")
    assert bad.returncode == 2
    assert "fraction" in bad.stderr and "volume_fraction" in bad.stderr


def test_version_is_recorded(tmp_path):
    assert manifest(synthesize("none", 0, tmp_path))["pamkit_version"] == pamkit.__version__
