"""Synthetic measured datasets with one effect hidden in them: a random bench protocol, the
model extended by the effect at a random realistic strength, read by the bench's instruments
(:mod:`pamkit.synth.instruments`) and written as an experiment (TOML + CSV, as load_experiment
reads them). What was hidden goes to a separate ``manifest.json`` that nothing in diagnosis may
read.

Random draws (one seeded ``numpy.random.Generator`` per concern, spawned from the seed, so
that the same seed gives the same protocol, build and instrument noise whatever the effect):

- build: PAM 2 of table 3.4 / C.4 (pamkit.MuscleBuild's defaults) with the two dimensions
  measured per muscle varied within what building "identical" muscles gives: deflated length
  +-1 mm (table 3.4's two muscles differ by 2 mm) and braid diameter +-0.1 mm; both are
  written as measured (0.1 mm ruler, 0.01 mm calipers) and the simulation uses exactly the
  written values, so the experiment file describes the muscle truly;
- protocol: inflation 35-276 kPa gauge, stretch to 80-95 % of the free contraction (deflated
  length minus free inflated length), 2.5-50 mm/s (log-uniform: equal weight to each decade
  of rate), 5-10 triangle cycles from the free inflated length, ambient 20-25 °C; a rest of
  1-3 s before the first stretch and 1 s after the last; in one dataset out of three a hold
  of 5-20 s at the top of every stretch (bench programs often dwell there, and a hold is where
  heat exchange, which settles, and a leak, which does not, tell themselves apart; the other
  two thirds keep the thesis's hold-free protocol so that diagnosis cannot rely on holds);
- effect strength: each parameter not given uniformly in the effect's realistic range,
  log-uniformly where that range spans more than a decade (the time constants); for effects
  acting on a channel, the channel at random among gauge_pressure_Pa and temperature_K (the
  Arduino's), and the sign at random where the effect declares `either_sign` (time_skew),
  unless given. Only channels that move by more than one ADC count in the test are drawn:
  the baseline's gas is isothermal (polytropic n = 1), so its temperature is constant, and a
  lag or skew of a constant leaves the data bit for bit as without the effect;
- instruments: see :func:`draw_instruments`.
"""

from __future__ import annotations

import json
import math
from collections.abc import Callable, Sequence
from dataclasses import asdict, dataclass, replace
from pathlib import Path

import numpy as np

import pamkit
from pamkit._core import (
    BladderLaw,
    BraidGeometry,
    EffectCatalog,
    ElongationTrajectory,
    GasMode,
    GasParams,
    MuscleBuild,
    MuscleParams,
    Simulator,
    free_inflation,
    inflated_and_sealed,
    simulate_measurement,
)
from pamkit.effects import catalog as builtin_catalog
from pamkit.io.columns import LOGGER_CHANNELS, OPTIONAL_COLUMNS, value_to_si
from pamkit.io.experiment import experiment_of
from pamkit.io.writers import write_experiment
from pamkit.simulation import muscle_params, sealed_start
from pamkit.synth.instruments import (
    ArduinoLogger,
    ArduinoLoggerSettings,
    LoadCell,
    PressureTransducer,
    TensileMachine,
    TensileMachineSettings,
    merge_logs,
)

NONE = "none"
LOG_DRAW_SPAN = 10.0  # a realistic range wider than this ratio is drawn log-uniformly

# The ranges a dataset draws from: the thesis's bench tests and faster ones (module docstring).
INFLATION_KPA = (35.0, 276.0)
STRETCH_FRACTION = (0.80, 0.95)
SPEED_M_PER_S = (2.5e-3, 50e-3)
CYCLES = (5, 10)
# Choices of this module (see the module docstring).
AMBIENT_C = (20.0, 25.0)
REST_BEFORE_S = (1.0, 3.0)
REST_AFTER_S = 1.0
HOLD_PROBABILITY = 1.0 / 3.0
HOLD_S = (5.0, 20.0)
LENGTH_VARIATION_M = 1e-3
DIAMETER_VARIATION_M = 0.1e-3
# Instrument choices (see draw_instruments).
MACHINE_RATES_HZ = (10.0, 20.0, 25.0, 50.0)
LOGGER_RATES_HZ = (20.0, 50.0, 100.0)
MIN_SAMPLES_PER_STRETCH = 25
FORCE_NOISE_RMS_N = (0.5, 2.0)
CLOCK_OFFSET_S = (2.0, 30.0)
CLOCK_DRIFT_PPM = 50.0
SYNC_ERROR_S = 0.005
LOGGER_MARGIN_S = 1.0


@dataclass(frozen=True)
class Protocol:
    """A bench test's plan: inflation, and triangle cycles of the crosshead. The inflation and
    the room are as the experiment file states them, to the digits a person writes there; the
    model reads them from the file (pamkit.io.experiment), as a diagnosis will."""

    inflation_pressure_kPa: float  #: gauge, after inflation, as the file states it [kPa]
    ambient_temperature_C: float  #: the room, as the file states it [°C]
    free_length_m: float  #: free inflated length, where the test starts [m]
    free_contraction_m: float  #: deflated length minus free inflated length [m]
    stretch_fraction: float  #: of the free contraction [1]
    max_elongation_m: float  #: top of each stretch [m]
    speed_m_per_s: float  #: crosshead speed [m/s]
    cycles: int  #: stretch-return cycles [1]
    hold_top_s: float  #: hold at the top of each stretch [s] (0: none)
    rest_before_s: float  #: at rest before the first stretch [s]
    rest_after_s: float  #: at rest after the last return [s]

    def breakpoints(self) -> tuple[np.ndarray, np.ndarray]:
        """The crosshead's corners: times [s] and elongations [m], linear in between."""
        ramp = self.max_elongation_m / self.speed_m_per_s
        t, e = [0.0, self.rest_before_s], [0.0, 0.0]
        for _ in range(self.cycles):
            t.append(t[-1] + ramp)
            e.append(self.max_elongation_m)
            if self.hold_top_s > 0:
                t.append(t[-1] + self.hold_top_s)
                e.append(self.max_elongation_m)
            t.append(t[-1] + ramp)
            e.append(0.0)
        t.append(t[-1] + self.rest_after_s)
        e.append(0.0)
        return np.asarray(t), np.asarray(e)

    @property
    def duration_s(self) -> float:
        return float(self.breakpoints()[0][-1])

    def on_samples(self, sample_rate_Hz: float) -> Protocol:
        """The same protocol with every corner on a sample of a machine logging at
        `sample_rate_Hz`: ramp, hold and rests whole numbers of sample periods, the speed
        adjusted (by less than half a period per ramp, kept within SPEED_M_PER_S).

        A machine's controller reverses where it is told, not on a logging tick; but a corner
        between two samples is cut by the data's straight line, and the model driven by the
        data then meets a different velocity there than the muscle did (friction changes sign
        at the corner): a difference in force that is the sampling's, not the muscle's.
        """
        period = 1.0 / sample_rate_Hz
        steps = max(1, round(self.max_elongation_m / self.speed_m_per_s / period))
        while self.max_elongation_m / (steps * period) > SPEED_M_PER_S[1]:
            steps += 1
        while self.max_elongation_m / (steps * period) < SPEED_M_PER_S[0] and steps > 1:
            steps -= 1
        return replace(
            self,
            speed_m_per_s=self.max_elongation_m / (steps * period),
            hold_top_s=round(self.hold_top_s / period) * period,
            rest_before_s=max(1, round(self.rest_before_s / period)) * period,
            rest_after_s=max(1, round(self.rest_after_s / period)) * period,
        )


@dataclass(frozen=True)
class SynthFiles:
    """What :func:`synthesize` wrote."""

    experiment: Path  #: the experiment TOML
    data: Path  #: its CSV
    manifest: Path  #: the hidden truth (JSON); not for diagnosis


# ----------------------------------------------------------------------------------------------
# random draws


def draw_build(rng: np.random.Generator) -> MuscleBuild:
    """PAM 2 with its measured length and diameter varied, rounded as measured (module docstring)."""
    build = MuscleBuild()
    build.length_m = round(build.length_m + rng.uniform(-LENGTH_VARIATION_M, LENGTH_VARIATION_M), 4)
    build.diameter_m = round(build.diameter_m + rng.uniform(-DIAMETER_VARIATION_M, DIAMETER_VARIATION_M), 5)
    build.validate()
    return build


def draw_protocol(rng: np.random.Generator, build: MuscleBuild) -> Protocol:
    """A random protocol in this module's ranges (module docstring)."""
    pressure = round(rng.uniform(*INFLATION_KPA), 2)
    ambient = round(rng.uniform(*AMBIENT_C), 2)
    fraction = rng.uniform(*STRETCH_FRACTION)
    speed = math.exp(rng.uniform(math.log(SPEED_M_PER_S[0]), math.log(SPEED_M_PER_S[1])))
    cycles = int(rng.integers(CYCLES[0], CYCLES[1] + 1))
    hold = rng.uniform(*HOLD_S) if rng.uniform() < HOLD_PROBABILITY else 0.0
    rest = rng.uniform(*REST_BEFORE_S)
    gas = GasParams()
    free = free_inflation(
        BraidGeometry(build), BladderLaw.thesis(), gas.atmospheric_pressure_Pa, value_to_si("pressure_kPa", pressure)
    )
    contraction = build.length_m - free.length_m
    return Protocol(
        inflation_pressure_kPa=pressure,
        ambient_temperature_C=ambient,
        free_length_m=free.length_m,
        free_contraction_m=contraction,
        stretch_fraction=fraction,
        max_elongation_m=round(fraction * contraction, 4),  # the machine is programmed in 0.1 mm
        speed_m_per_s=round(speed, 5),
        cycles=cycles,
        hold_top_s=round(hold, 1),
        rest_before_s=round(rest, 2),
        rest_after_s=REST_AFTER_S,
    )


def draw_instruments(rng: np.random.Generator, protocol: Protocol) -> dict:
    """The bench's instruments for one dataset.

    - tensile machine: a rate among 10, 20, 25, 50 Hz giving at least 25 samples per stretch
      (a lab sets the rate so that a stretch is a curve; 50 Hz otherwise); load-cell noise
      0.5-2 N RMS (a 100 kN cell's floor, 0.5-2e-5 of capacity), 0.2 N resolution, 1 µm
      displacement resolution;
    - Arduino logger: a rate among 20, 50, 100 Hz, not below the machine's; clock started
      2-30 s before the machine's, drifting +-50 ppm; one conversion per sample as the
      thesis's CoolTerm logging; 2 mV RMS input noise; this unit's transducer offset
      0.56 V +- 20 mV and sensitivity 0.04 V/psi +- 2 %, calibrated as in appendix B before
      the test (exact reference pressures: a reference gauge's error is the catalog's
      sensor_offset); ADC reference exactly the 5 V the host assumes (an AVCC error would shift
      the TMP36's reading, an offset the catalog has no name for);
    - hand synchronisation: the operator lines up the first pressure rise with the start of
      the crosshead, both sharp, and is off by up to +-5 ms; the drift is left uncorrected.

    The clock errors are kept small on purpose: at 50 mm/s the pressure moves by up to about
    200 kPa/s, so 5 ms is one ADC count. A larger error is a real bench's time skew, which the
    catalog's time_skew (0.3-3 s) names; in a dataset without that effect it must not show.
    """
    ramp = protocol.max_elongation_m / protocol.speed_m_per_s
    machine_choices = [r for r in MACHINE_RATES_HZ if r * ramp >= MIN_SAMPLES_PER_STRETCH] or [MACHINE_RATES_HZ[-1]]
    machine_rate = float(rng.choice(machine_choices))
    logger_choices = [r for r in LOGGER_RATES_HZ if r >= machine_rate]
    logger_rate = float(rng.choice(logger_choices))
    machine = TensileMachineSettings(
        sample_rate_Hz=machine_rate,
        load_cell=LoadCell(noise_rms_N=round(rng.uniform(*FORCE_NOISE_RMS_N), 3)),
    )
    nominal = PressureTransducer()
    transducer = PressureTransducer(
        offset_V=round(nominal.offset_V + rng.uniform(-0.02, 0.02), 5),
        sensitivity_V_per_psi=round(nominal.sensitivity_V_per_psi * (1.0 + rng.uniform(-0.02, 0.02)), 7),
    )
    logger = ArduinoLoggerSettings(
        sample_rate_Hz=logger_rate,
        clock_offset_s=round(rng.uniform(*CLOCK_OFFSET_S), 6),
        clock_drift_ppm=round(rng.uniform(-CLOCK_DRIFT_PPM, CLOCK_DRIFT_PPM), 2),
        pressure=transducer,
    )
    sync_error = round(rng.uniform(-SYNC_ERROR_S, SYNC_ERROR_S), 4)
    return {"machine": machine, "logger": logger, "sync_error_s": sync_error}


def parse_spec(spec: str, effect_catalog: EffectCatalog) -> tuple[str, dict[str, str]]:
    """The effect's name and the settings `spec` gives (``NAME[:key=value,...]``, the catalog's
    grammar), once the catalog accepts it; ``"none"`` takes none.

    Raises:
        ValueError: naming the unknown effect, the bad key or value (the catalog's message).
    """
    spec = spec.strip()
    name, settings = EffectCatalog.split(spec)
    if name == NONE:
        if settings:
            raise ValueError(f"effect 'none' takes no parameters (got {', '.join(key for key, _ in settings)})")
        return name, {}
    effect_catalog.parse(spec)  # raises ValueError naming the effect, key or value
    return name, dict(settings)


def configure_effect(
    spec: str,
    rng: np.random.Generator,
    effect_catalog: EffectCatalog | None = None,
    channels: Sequence[str] = LOGGER_CHANNELS,
):
    """The effect of `spec` with every parameter not given drawn (module docstring); a channel
    not given is drawn among `channels`.

    Returns:
        (effect or None for "none", {"name", "spec", "given", "drawn", "parameters", "options"}).
    """
    effect_catalog = effect_catalog if effect_catalog is not None else builtin_catalog()
    name, given = parse_spec(spec, effect_catalog)
    info = {"name": name, "spec": spec, "given": sorted(given), "drawn": [], "parameters": {}, "options": {}}
    if name == NONE:
        return None, info
    effect = effect_catalog.make(name)
    drawn = []
    if "channel" in effect.options() and "channel" not in given:
        given["channel"] = str(rng.choice(list(channels)))
        drawn.append("channel")
    for parameter in effect.parameters():
        if parameter.name in given:
            continue
        lo, hi = parameter.realistic_min, parameter.realistic_max
        if not (math.isfinite(lo) and math.isfinite(hi)) or hi <= lo:
            continue
        # A range spanning more than a decade has no natural scale: drawn log-uniformly.
        if lo > 0 and hi > LOG_DRAW_SPAN * lo:
            value = math.exp(rng.uniform(math.log(lo), math.log(hi)))
        else:
            value = rng.uniform(lo, hi)
        if parameter.either_sign:
            value *= rng.choice((-1.0, 1.0))
        given[parameter.name] = repr(float(value))
        drawn.append(parameter.name)
    for key, value in given.items():
        effect.set(key, value)
    info["drawn"] = drawn
    info["parameters"] = {p.name: p.value for p in effect.parameters()}
    info["options"] = dict(effect.options())
    return effect, info


# ----------------------------------------------------------------------------------------------
# the dataset


def hideable_effects(effect_catalog: EffectCatalog | None = None) -> list[str]:
    """The catalog's effects synth can hide: those that act in the sealed test it writes."""
    effect_catalog = effect_catalog if effect_catalog is not None else builtin_catalog()
    return [name for name in effect_catalog.names() if effect_catalog.make(name).acts_in(GasMode.sealed)[0]]


def synthesize(
    effect_spec: str,
    seed: int,
    out_dir: str | Path,
    effect_catalog: EffectCatalog | None = None,
    change_protocol: Callable[[Protocol], Protocol] | None = None,
    sample_rate_Hz: float | None = None,
    true_muscle: Callable[[MuscleParams, Protocol], tuple[MuscleParams, dict]] | None = None,
) -> SynthFiles:
    """Writes a synthetic experiment with the effect `effect_spec` (``"none"``, ``"NAME"`` or
    ``"NAME:key=value,..."``) hidden in it: ``out_dir/experiment.toml``,
    ``out_dir/experiment.csv`` and the truth in ``out_dir/manifest.json``.

    The same seed gives byte-identical files; the protocol, build and instrument noise depend
    on the seed only, not on the effect. `change_protocol` makes the test's protocol from the
    drawn one, `sample_rate_Hz` replaces both instruments' drawn rates: a long test at 1 kHz,
    say; every draw is still made, so the others stay those of the seed.

    `true_muscle(declared, protocol)` makes the muscle the data come from out of the one the file
    declares, returning it and a description for the manifest (:mod:`pamkit.synth.mismatch`): a
    real muscle is never exactly its declared build (a
    braid wound a few per cent otherwise, another end geometry, a sharper friction). The true
    muscle is inflated freely to the test's pressure and sealed at its own free length; the
    crosshead follows the protocol planned from the declared build, as a lab plans it.

    Raises:
        ValueError: for a bad effect spec (naming the effect, key or value), or an effect that
            cannot act on a sealed test.
    """
    effect_catalog = effect_catalog if effect_catalog is not None else builtin_catalog()
    seed = int(seed)
    if seed < 0:
        raise ValueError(f"seed = {seed} must be >= 0")
    build_rng, protocol_rng, effect_rng, instrument_rng = (
        np.random.default_rng(child) for child in np.random.SeedSequence(seed).spawn(4)
    )
    parse_spec(effect_spec, effect_catalog)  # a bad spec fails before any work

    build = draw_build(build_rng)
    protocol = draw_protocol(protocol_rng, build)
    if change_protocol is not None:
        protocol = change_protocol(protocol)
    instruments = draw_instruments(instrument_rng, protocol)
    if sample_rate_Hz is not None:
        instruments["machine"] = replace(instruments["machine"], sample_rate_Hz=sample_rate_Hz)
        instruments["logger"] = replace(instruments["logger"], sample_rate_Hz=sample_rate_Hz)
    protocol = protocol.on_samples(instruments["machine"].sample_rate_Hz)
    machine = TensileMachine(instruments["machine"])
    logger = ArduinoLogger(instruments["logger"])
    calibration = logger.calibrate(instrument_rng)

    # The truth, sampled where either instrument samples it (and at the crosshead's corners),
    # so that neither reads an interpolation of the simulation.
    duration = protocol.duration_s
    corners_t, corners_e = protocol.breakpoints()
    logger_times = logger.sample_times(-LOGGER_MARGIN_S, duration + LOGGER_MARGIN_S)
    times = np.concatenate(
        [machine.sample_times(duration), logger_times[(logger_times > 0) & (logger_times < duration)], corners_t]
    )
    times = np.unique(times)
    times = times[np.concatenate([[True], np.diff(times) > 1e-6])]
    crosshead = ElongationTrajectory(times, np.interp(times, corners_t, corners_e))
    out_dir = Path(out_dir)
    files = SynthFiles(out_dir / "experiment.toml", out_dir / "experiment.csv", out_dir / "manifest.json")
    sections = {
        "muscle": build.to_dict(),
        "test": {
            "description": "synthetic bench test (pamkit synth)",
            "inflation_pressure_kPa": protocol.inflation_pressure_kPa,
            "ambient_temperature_C": protocol.ambient_temperature_C,
            "data": files.data.name,
        },
    }
    # The model of the file as a reader makes it, from the state every sealed test starts in.
    experiment = experiment_of(files.experiment, sections)
    params = muscle_params(experiment)
    initial = sealed_start(experiment, params)
    mismatch = {}
    if true_muscle is not None:
        params, mismatch = true_muscle(params, protocol)
        params.validate()
        initial = inflated_and_sealed(params, initial.gauge_pressure_Pa)
    baseline = simulate_measurement(params, initial, crosshead, [], Simulator())

    # A lag or skew of a channel that does not move cannot be seen (the temperature of the
    # isothermal baseline, polytropic n = 1): the channel is drawn among those that move by
    # more than one ADC count over the test.
    step = {"gauge_pressure_Pa": logger.pressure_step_Pa(), "temperature_K": logger.temperature_step_K()}
    moving = [name for name in LOGGER_CHANNELS if np.ptp(getattr(baseline, name)) > step[name]]
    effect, effect_info = configure_effect(effect_spec, effect_rng, effect_catalog, moving or LOGGER_CHANNELS)
    effects = [effect] if effect is not None else []
    # Inflated freely, the muscle with the effect seals where it carries no force (compliant fibres
    # stretch and seal it longer); the file declares no initial length, so its reader starts there too.
    truth = baseline
    if effects:
        start = sealed_start(experiment, params, initial.gauge_pressure_Pa, effects)
        truth = simulate_measurement(params, start, crosshead, effects, Simulator())
    effect_info["largest_change"] = {
        name: float(np.max(np.abs(np.asarray(getattr(truth, name)) - np.asarray(getattr(baseline, name)))))
        for name in OPTIONAL_COLUMNS
    }

    machine_log = machine.record(truth, instrument_rng, duration)
    logger_log = logger.record(truth, instrument_rng, -LOGGER_MARGIN_S, duration + LOGGER_MARGIN_S)
    sync = instruments["logger"].clock_offset_s + instruments["sync_error_s"]
    columns = merge_logs(machine_log, logger_log, sync)

    out_dir.mkdir(parents=True, exist_ok=True)
    write_experiment(
        files.experiment,
        sections,
        columns,
        comments=[
            "A synthetic bench test (pamkit synth): PAM 2 on a tensile machine, pressure and temperature",
            "logged by an Arduino Mega, the two logs merged on the machine's time base.",
        ],
    )
    manifest = {
        "about": "the truth hidden in experiment.toml/.csv; written by pamkit synth; not for diagnosis",
        "pamkit_version": pamkit.__version__,
        "seed": seed,
        "effect": effect_info,
        "true_muscle": mismatch,
        "protocol": asdict(protocol),
        "muscle": build.to_dict(),
        "instruments": {
            "tensile_machine": asdict(instruments["machine"]),
            "arduino_logger": asdict(instruments["logger"]),
            "pressure_calibration": calibration.to_dict(),
            "pressure_step_Pa": logger.pressure_step_Pa(),
            "temperature_step_K": logger.temperature_step_K(),
            "logger_clock_at_machine_zero_s": {"true": instruments["logger"].clock_offset_s, "used_to_merge": sync},
        },
        "samples": {
            "dense": int(times.size),
            "machine": int(machine_log.time_s.size),
            "logger": int(logger_log.time_s.size),
        },
        "files": {"experiment": files.experiment.name, "data": files.data.name},
    }
    files.manifest.write_text(json.dumps(manifest, indent=2, sort_keys=True) + "\n")
    return files
