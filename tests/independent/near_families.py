"""The near-model world: bench tests written by the thesis's own muscle model
(:mod:`.thesis_muscle`), made to differ from it as real muscles do, with a catalog cause hidden
at three strengths, and nulls. Never imports pamkit; the files reach it as a user's would.

A dataset's **base** is the build its file declares (thesis PAM 2, its length and braid diameter
varied within ±1 mm and ±0.1 mm and written as measured) with its own friction and bladder levels
(×0.7-1.4 and ×0.8-1.25: a baseline calibrates both) and one or two **departures** drawn from
:data:`DEPARTURE_RANGES` — a wall that keeps its thickness, a braid wound otherwise than declared,
flatter or steeper end cones, another membrane law, Dahl or Coulomb friction — sized so that
pamkit's calibrated baseline is left about 1-3x the force noise on a null (bench/README.md gives
the measured distribution). The **cause** is implemented here from its physical meaning
(docs/effects.md), at a strength of :data:`STRENGTHS`: weak (near what the sampling resolves),
medium and strong (plainly visible). Two-cause families hide two at once.

Protocols are pamkit synth's ranges (docs/effects.md, "Synthetic datasets"): sealed cyclic tests
inflated to 35-276 kPa, 5-10 triangle cycles to 80-95 % of the free contraction at 2.5-50 mm/s
(log-uniform), a 5-20 s hold at the top in a third of them, 20 Hz (50 Hz when a stretch would get
fewer than 25 samples), load cell noise 0.5-2 N RMS in 0.2 N steps, the Arduino's 10-bit pressure
and TMP36 channels; supplied isometric sweeps hold a length and step the regulator's pressure up
and down. Each family and seed draws its own build, departures, protocol and noise (three
independent streams), the same at every strength, so that the strengths differ by the cause's
size only; `Family.without_cause` writes the same test with nothing hidden.
"""

from __future__ import annotations

import math
import zlib
from collections.abc import Callable
from dataclasses import asdict, dataclass, field, replace
from pathlib import Path

import numpy as np
from scipy.optimize import brentq

from . import bench
from .physics import Build, Motion
from .thesis_muscle import Departures, Effects, SealedTest, ThesisMuscle, fixture_play, supplied_force

STRENGTHS = ("weak", "medium", "strong")
SEALED, SUPPLIED = "sealed", "supplied"

INFLATION_KPA = (35.0, 276.0)
AMBIENT_C = (20.0, 25.0)
STRETCH_FRACTION = (0.80, 0.95)
SPEED_M_PER_S = (2.5e-3, 50e-3)
CYCLES = (5, 10)
HOLD_PROBABILITY = 1.0 / 3.0
HOLD_S = (5.0, 20.0)
REST_BEFORE_S = (1.0, 3.0)
REST_AFTER_S = 1.0
MIN_SAMPLES_PER_STRETCH = 25
FORCE_NOISE_N = (0.5, 2.0)
LENGTH_VARIATION_M = 1e-3
DIAMETER_VARIATION_M = 0.1e-3
FRICTION_LEVEL = (0.7, 1.4)  # log-uniform
BLADDER_LEVEL = (0.8, 1.25)  # log-uniform
LAG_GRID = 10  # a lagged channel is filtered on a grid this much finer than the samples
ZERO_RUN_S = 10.0  # a zero run's length, at the test's sampling rate

# Departures from the thesis's model: (low, high) of each dial's size as drawn (uniformly, the sign
# at random where a dial has one) ...
DEPARTURE_RANGES = {
    "wall_held": (0.5, 1.0),  # share of the wall keeping its thickness
    "wind": (0.02, 0.05),  # relative error of the declared turns, either sign
    "end_flattening": (0.05, 0.12),  # relative change of the cones' slant, either sign
    "membrane_share": (0.5, 1.0),  # Mooney-Rivlin or neo-Hookean share of the bladder law
    "friction_share": (0.5, 1.0),  # Dahl or smooth Coulomb share of the friction
    "dahl_length_m": (0.2e-3, 1.0e-3),
    "coulomb_velocity_m_per_s": (0.2e-3, 1.0e-3),
}
DEPARTURES = ("wall_held", "wind", "end_flattening", "membrane_share", "friction_share")
# ... and then shrunk together, where needed, so that the force they change before any calibration
# is at most this many times the dataset's force noise (RMS over the test; drawn uniformly). The
# wall, the wind and the cones change the force in proportion to the pressure: sizes that a 35 kPa
# test shows at 1-3x its noise leave a 276 kPa test at 4-5x. A baseline's calibration absorbs part
# of the change (on 66 datasets as drawn, the model error left after it was 0-1.0 of the change,
# median 0.5), so that a null is left at about 1-3x the noise.
MISFIT_NOISE_MULTIPLES = (2.0, 5.0)

# Supplied isometric sweeps
REGULATOR_TIME_CONSTANT_S = 0.4  # a proportional regulator's settling, first order
SUPPLIED_RATE_HZ = 20.0
ENCODER_NOISE_M = 2e-6  # a held crosshead dithers by a couple of encoder counts
TAUT_FLOOR_N = 10.0  # a sweep that must stay taut vents to the pressure where the muscle pulls this


@dataclass
class NearDataset:
    """One written test and what is hidden in it (never in the files)."""

    experiment: Path
    hidden: tuple[str, ...]  # catalog names of the hidden causes; () for a null
    strength: str | None  # one of STRENGTHS; None for a null
    truth: dict = field(default_factory=dict)
    # catalog names of physics the base model has and this dataset shows: right if named
    present: tuple[str, ...] = ()


@dataclass(frozen=True)
class Family:
    """A family of datasets: `make(seed, folder, strength)` writes one into `folder` (with
    `variant`, another test of the same muscle: sealed_test);
    `without_cause(seed, folder)` the same test (build, departures, protocol, noise) with nothing
    hidden, the yardstick of a cause's signature."""

    name: str
    hidden: tuple[str, ...]
    kind: str  # SEALED or SUPPLIED
    levels: dict  # strength -> cause -> its parameters there (LEVELS)
    make: Callable[..., NearDataset]  # (seed, folder, strength, variant=None): sealed_test's variant
    without_cause: Callable[[int, Path], NearDataset]


@dataclass
class Draws:
    protocol: np.random.Generator
    departures: np.random.Generator
    noise: np.random.Generator


def draws(seed: int, family: str) -> Draws:
    """A family's own streams for `seed`: each family and seed its own build, departures, protocol
    and noise (the same at every strength)."""
    key = zlib.crc32(family.encode())
    return Draws(*(np.random.default_rng(s) for s in np.random.SeedSequence([seed, key]).spawn(3)))


def _log_uniform(rng, low, high):
    return math.exp(rng.uniform(math.log(low), math.log(high)))


def _sign(rng):
    return float(rng.choice([-1.0, 1.0]))


def draw_build(rng: np.random.Generator) -> Build:
    """PAM 2 with its measured length and diameter varied, written as measured (0.1 mm, 0.01 mm)."""
    nominal = Build()
    return replace(
        nominal,
        length_m=round(nominal.length_m + rng.uniform(-LENGTH_VARIATION_M, LENGTH_VARIATION_M), 4),
        diameter_m=round(nominal.diameter_m + rng.uniform(-DIAMETER_VARIATION_M, DIAMETER_VARIATION_M), 5),
    )


def draw_departures(rng: np.random.Generator, kind: str) -> tuple[Departures, float]:
    """One or two departures at sizes from DEPARTURE_RANGES, this muscle's friction and bladder
    levels, and the multiple of the force noise their misfit is limited to
    (:data:`MISFIT_NOISE_MULTIPLES`). A supplied sweep does not move, so no friction law."""
    friction_scale = _log_uniform(rng, *FRICTION_LEVEL)
    bladder_scale = _log_uniform(rng, *BLADDER_LEVEL)
    pool = [d for d in DEPARTURES if kind == SEALED or d != "friction_share"]
    count = 1 + int(rng.uniform() < 0.5)
    chosen = [pool[i] for i in rng.choice(len(pool), size=count, replace=False)]
    # every size is drawn whatever is chosen: one departure's size does not depend on the others
    sizes = {name: rng.uniform(*DEPARTURE_RANGES[name]) for name in DEPARTURE_RANGES}
    signs = {name: _sign(rng) for name in ("wind", "end_flattening")}
    membrane = str(rng.choice(["mooney_rivlin", "neo_hookean"]))
    friction = str(rng.choice(["dahl", "coulomb"]))
    d = Departures(friction_scale=friction_scale, bladder_scale=bladder_scale)
    if "wall_held" in chosen:
        d = replace(d, wall_held=sizes["wall_held"])
    if "wind" in chosen:
        d = replace(d, wind=signs["wind"] * sizes["wind"])
    if "end_flattening" in chosen:
        d = replace(d, end_flattening=signs["end_flattening"] * sizes["end_flattening"])
    if "membrane_share" in chosen:
        d = replace(d, membrane=membrane, membrane_share=sizes["membrane_share"])
    if "friction_share" in chosen:
        d = replace(
            d,
            friction_law=friction,
            friction_share=sizes["friction_share"],
            dahl_length_m=sizes["dahl_length_m"],
            coulomb_velocity_m_per_s=sizes["coulomb_velocity_m_per_s"],
        )
    return d, rng.uniform(*MISFIT_NOISE_MULTIPLES)


def scaled(d: Departures, factor: float) -> Departures:
    """Every departure dial times `factor` (the friction and bladder levels kept)."""
    return replace(
        d,
        wall_held=d.wall_held * factor,
        wind=d.wind * factor,
        end_flattening=d.end_flattening * factor,
        membrane_share=d.membrane_share * factor,
        friction_share=d.friction_share * factor,
    )


def limit_departures(d: Departures, misfit: Callable[[Departures], float], limit_N: float):
    """The departures shrunk together (one factor for every dial) until `misfit` (the RMS force
    they change against the thesis's model of the same test [N]) is at most `limit_N`; as drawn if
    it already is. Returns them, the factor and their misfit."""
    factor, change = 1.0, misfit(d)
    for _ in range(5):
        if change <= limit_N:
            break
        factor *= 0.97 * limit_N / change
        change = misfit(scaled(d, factor))
    return scaled(d, factor), factor, change


def thesis_model_of(d: Departures) -> Departures:
    """The thesis's model with this muscle's friction and bladder levels (which a baseline calibrates)."""
    return Departures(friction_scale=d.friction_scale, bladder_scale=d.bladder_scale)


def departures_truth(d: Departures) -> dict:
    """The departures that are on, and the levels, for a dataset's truth."""
    neutral = Departures()
    out = {k: v for k, v in asdict(d).items() if k in ("friction_scale", "bladder_scale") or v != asdict(neutral)[k]}
    if d.membrane_share == 0:
        out.pop("membrane", None)
    unused = {"tanh": (), "dahl": ("coulomb_velocity_m_per_s",), "coulomb": ("dahl_length_m",)}[d.friction_law]
    if d.friction_share == 0:
        unused = ("friction_law", "dahl_length_m", "coulomb_velocity_m_per_s")
    for k in unused:
        out.pop(k, None)
    return out


# ----------------------------------------------------------------------------------------------
# sealed cyclic tests


@dataclass(frozen=True)
class SealedPlan:
    gauge_kPa: float
    ambient_C: float
    fraction: float
    speed_m_per_s: float
    cycles: int
    hold_s: float
    rest_before_s: float
    noise_N: float


def draw_sealed_plan(rng: np.random.Generator) -> SealedPlan:
    hold = rng.uniform(*HOLD_S)
    holds = rng.uniform() < HOLD_PROBABILITY
    return SealedPlan(
        gauge_kPa=round(rng.uniform(*INFLATION_KPA), 2),
        ambient_C=round(rng.uniform(*AMBIENT_C), 2),
        fraction=rng.uniform(*STRETCH_FRACTION),
        speed_m_per_s=_log_uniform(rng, *SPEED_M_PER_S),
        cycles=int(rng.integers(CYCLES[0], CYCLES[1] + 1)),
        hold_s=round(hold, 1) if holds else 0.0,
        rest_before_s=rng.uniform(*REST_BEFORE_S),
        noise_N=round(rng.uniform(*FORCE_NOISE_N), 3),
    )


def crosshead(plan: SealedPlan, top_m: float, rate_Hz: float) -> Motion:
    """Triangle cycles (a hold at the top if planned), every corner on a sample."""
    period = 1.0 / rate_Hz
    ramp = max(1, round(top_m / plan.speed_m_per_s / period))
    hold = round(plan.hold_s / period)
    steps, x = [0, max(1, round(plan.rest_before_s / period))], [0.0, 0.0]
    for _ in range(plan.cycles):
        steps.append(steps[-1] + ramp)
        x.append(top_m)
        if hold:
            steps.append(steps[-1] + hold)
            x.append(top_m)
        steps.append(steps[-1] + ramp)
        x.append(0.0)
    steps.append(steps[-1] + round(REST_AFTER_S / period))
    x.append(0.0)
    return Motion(np.asarray(steps) * period, np.asarray(x))


@dataclass(frozen=True)
class Instruments:
    """What the instruments do beyond their noise: the catalog's measurement causes."""

    pressure_lag_s: float = 0.0  # first-order lag of the pressure channel (a long hose)
    pressure_skew_s: float = 0.0  # the pressure written at t is the muscle's at t + this
    pressure_offset_kPa: float = 0.0  # the transducer's calibration: offset ...
    pressure_gain: float = 1.0  # ... and gain
    force_offset_N: float = 0.0  # the load cell's tare ...
    force_per_kN: float = 0.0  # ... and nonlinearity: reading = offset + F (1 + c F)
    temperature_offset_C: float = 0.0  # the TMP36's offset


def first_order_lag(times: np.ndarray, values: np.ndarray, tau_s: float) -> np.ndarray:
    """y' = (u − y)/τ from y = u at the start, exact for u linear between the given instants."""
    y = np.empty_like(values)
    y[0] = values[0]
    for i in range(1, values.size):
        h = times[i] - times[i - 1]
        a = math.exp(-h / tau_s)
        y[i] = a * y[i - 1] + (1 - a) * values[i - 1] + (values[i] - values[i - 1]) * (1 - tau_s * (1 - a) / h)
    return y


def sealed_test(
    seed: int,
    folder: Path,
    family: str,
    *,
    causes: dict | None = None,
    hidden: tuple[str, ...] = (),
    strength: str | None = None,
    variant: dict | None = None,
) -> NearDataset:
    """One sealed cyclic test of the family's muscle for `seed` with `causes` (catalog name -> its
    parameters, :func:`resolve` for those set relative to the test) in its physics, its fixture or
    its instruments. `variant` runs another test on the same muscle and rig: ``gauge_kPa`` inflates
    it freely to that pressure instead (and seals it at the length it takes there), ``time_scale``
    multiplies the crosshead's times (10: the same stretches ten times slower), ``zero_run`` writes
    the same test with the instruments' zero run beside it (ZERO_RUN_S of the muscle vented and
    unloaded, named by ``[test] zero``); the muscle, its departures and the causes are the test's as
    drawn."""
    rng = draws(seed, family)
    build = draw_build(rng.protocol)
    plan = draw_sealed_plan(rng.protocol)
    drawn, multiple = draw_departures(rng.departures, SEALED)

    def protocol(d: Departures):
        free = ThesisMuscle(build, d).free_length(plan.gauge_kPa * 1e3)
        top = round(plan.fraction * (build.length_m - free), 4)  # the machine is programmed in 0.1 mm
        rate = 20.0 if top / plan.speed_m_per_s * 20.0 >= MIN_SAMPLES_PER_STRETCH else 50.0
        return free, top, rate, crosshead(plan, top, rate)

    _, _, rate, motion = protocol(drawn)
    times = np.arange(int(round(motion.corner_t[-1] * rate)) + 1) / rate

    def misfit(d: Departures) -> float:
        initial = round(ThesisMuscle(build, d).free_length(plan.gauge_kPa * 1e3), 4)
        truth, thesis = (
            SealedTest(ThesisMuscle(build, m), plan.gauge_kPa, plan.ambient_C, initial).run(motion, times).force_N
            for m in (d, thesis_model_of(d))
        )
        return float(np.sqrt(np.mean((truth - thesis) ** 2)))

    departures, shrink, change = limit_departures(drawn, misfit, multiple * plan.noise_N)
    _, top, rate, motion = protocol(departures)
    resolved = resolve(causes or {}, duration_s=motion.corner_t[-1], ramp_s=motion.corner_t[2] - motion.corner_t[1])
    arguments = physics_of(resolved)
    effects, slack_m, instruments = arguments["effects"], arguments["slack_m"], arguments["instruments"]
    gauge_kPa = (variant or {}).get("gauge_kPa", plan.gauge_kPa)
    if (variant or {}).get("time_scale", 1.0) != 1.0:
        motion = Motion(motion.corner_t * variant["time_scale"], motion.corner_x)
    muscle = ThesisMuscle(build, departures, effects)
    initial = round(muscle.free_length(gauge_kPa * 1e3), 4)  # measured with a ruler, and sealed there
    muscle_motion = fixture_play(motion, slack_m)
    n = int(round(motion.corner_t[-1] * rate)) + 1
    times = np.arange(n) / rate
    test = SealedTest(muscle, gauge_kPa, plan.ambient_C, initial)
    run = test.run(muscle_motion, times)
    pressure, temperature = run.gauge_kPa, run.temperature_C
    if instruments.pressure_skew_s:
        shifted = test.run(muscle_motion, np.clip(times + instruments.pressure_skew_s, 0.0, times[-1]))
        pressure = shifted.gauge_kPa
    if instruments.pressure_lag_s:
        fine = np.arange((n - 1) * LAG_GRID + 1) / (rate * LAG_GRID)
        lagged = first_order_lag(fine, test.run(muscle_motion, fine).gauge_kPa, instruments.pressure_lag_s)
        pressure = lagged[::LAG_GRID]
    force = run.force_N
    force = instruments.force_offset_N + force * (1.0 + instruments.force_per_kN * 1e-3 * force)
    pressure = instruments.pressure_offset_kPa + instruments.pressure_gain * pressure
    columns = {
        "time_s": times,
        "elongation_m": bench.encoder(motion.elongation(times)),
        "force_N": bench.load_cell(force, rng.noise, plan.noise_N),
        "pressure_kPa": bench.pressure_logger(pressure, rng.noise),
        "temperature_C": bench.temperature_logger(temperature + instruments.temperature_offset_C, rng.noise),
    }
    described = {
        "description": "near-model world, sealed cyclic test",
        "inflation_pressure_kPa": gauge_kPa,
        "ambient_temperature_C": plan.ambient_C,
        "initial_length_m": initial,
    }
    if (variant or {}).get("zero_run"):
        # Vented and unloaded, at the room's temperature: the instruments read their own errors.
        quiet = np.arange(int(round(ZERO_RUN_S * rate)) + 1) / rate
        nothing = np.zeros_like(quiet)
        bench.write_columns(
            folder / "zero.csv",
            {
                "time_s": quiet,
                "elongation_m": nothing,
                "force_N": bench.load_cell(nothing + instruments.force_offset_N, rng.noise, plan.noise_N),
                "pressure_kPa": bench.pressure_logger(nothing + instruments.pressure_offset_kPa, rng.noise),
                "temperature_C": bench.temperature_logger(
                    nothing + plan.ambient_C + instruments.temperature_offset_C, rng.noise
                ),
            },
        )
        described["zero"] = "zero.csv"
    path = bench.write_experiment(
        folder,
        "test",
        asdict(build),
        described,
        columns,
        "Written by tests/independent (not pamkit): a sealed muscle stretched on a tensile machine.",
    )
    info = {
        "seed": seed,
        "kind": SEALED,
        "gauge_kPa": gauge_kPa,
        "speed_mm_per_s": round(top / (motion.corner_t[2] - motion.corner_t[1]) * 1e3, 3),
        "cycles": plan.cycles,
        "hold_s": plan.hold_s,
        "top_mm": top * 1e3,
        "rate_Hz": rate,
        "force_noise_N": plan.noise_N,
        "departures": departures_truth(departures),
        "departures_shrunk_by": shrink,
        "departures_force_rms_N": change,
        "cause": resolved,
    }
    if variant:
        info["variant"] = dict(variant)
    return NearDataset(path, hidden, strength, info)


def variant_asked(test: dict | None) -> dict | None:
    """sealed_test's `variant` for the test a diagnosis report asks for (its `separation.test`, a
    plain dict: another inflation in Pa, the motion's times scaled, or its key alone for a zero
    run); None for none."""
    if not test:
        return None
    if test.get("key") == "zero_run":
        return {"zero_run": True}
    if "inflation_gauge_pressure_Pa" in test:
        return {"gauge_kPa": round(test["inflation_gauge_pressure_Pa"] / 1e3, 2)}
    if "time_scale" in test:
        return {"time_scale": float(test["time_scale"])}
    return None


# ----------------------------------------------------------------------------------------------
# supplied isometric sweeps


@dataclass(frozen=True)
class SuppliedPlan:
    held_fraction: float  # of the deflated length
    steps: int
    top_kPa: float
    dwell_s: float
    ambient_C: float
    noise_N: float


def draw_supplied_plan(rng: np.random.Generator) -> SuppliedPlan:
    return SuppliedPlan(
        held_fraction=rng.uniform(0.88, 0.97),
        steps=int(rng.integers(5, 9)),
        top_kPa=rng.uniform(150.0, 300.0),
        dwell_s=rng.uniform(5.0, 10.0),
        ambient_C=round(rng.uniform(*AMBIENT_C), 2),
        noise_N=round(rng.uniform(*FORCE_NOISE_N), 3),
    )


def pressure_for_force(muscle: ThesisMuscle, length_m: float, force_N: float) -> float:
    """The supplied gauge pressure at which the muscle held at `length_m` pulls `force_N` [kPa]
    (the thesis's braid, which may push)."""
    return brentq(lambda p: float(muscle.forces(np.array([length_m]), p * 1e3).static[0]) - force_N, -50.0, 600.0)


def supplied_sweep(
    seed: int,
    folder: Path,
    family: str,
    *,
    causes: dict | None = None,
    hidden: tuple[str, ...] = (),
    strength: str | None = None,
) -> NearDataset:
    """The length held at 88-97 % of the deflated length; the regulator's pressure stepped from a
    floor up to 150-300 kPa in 5-8 plateaus of 5-10 s and down the same steps to the floor. The
    floor keeps the braid taut (it pulls 10 N there) unless `causes` has braid_slack: then the floor
    is where the thesis's braid would push with its `depth_N`, and this braid, which cannot push,
    goes slack. pressure_hysteresis is the bladder-braid friction of :func:`supplied_force`;
    sensor_lag lags the muscle's pressure behind the transducer's through a hose; sensor_offset is
    the transducer's calibration."""
    causes = causes or {}
    slack_depth_N = causes.get("braid_slack", {}).get("depth_N")
    hysteresis = causes.get("pressure_hysteresis", {}).get("coefficient", 0.0)
    hose_lag_s = causes.get("sensor_lag", {}).get("time_constant_s", 0.0)
    instruments = instruments_of(causes)
    rng = draws(seed, family)
    build = draw_build(rng.protocol)
    plan = draw_supplied_plan(rng.protocol)
    drawn, multiple = draw_departures(rng.departures, SUPPLIED)
    held = round(build.length_m * plan.held_fraction, 4)
    floor_force = TAUT_FLOOR_N if slack_depth_N is None else -slack_depth_N

    def protocol(d: Departures):
        """The regulator's pressure [kPa] at each sample, from the floor this muscle needs."""
        floor = max(0.0, pressure_for_force(ThesisMuscle(build, d), held, floor_force))
        levels = np.concatenate(
            [np.linspace(floor, plan.top_kPa, plan.steps + 1), np.linspace(plan.top_kPa, floor, plan.steps + 1)[1:]]
        )
        times = np.arange(int(round(plan.dwell_s * levels.size * SUPPLIED_RATE_HZ)) + 1) / SUPPLIED_RATE_HZ
        command = levels[np.minimum((times // plan.dwell_s).astype(int), levels.size - 1)]
        regulator = np.empty_like(command)  # the regulator's exact first-order response to each step
        regulator[0] = command[0]
        decay = math.exp(-1.0 / SUPPLIED_RATE_HZ / REGULATOR_TIME_CONSTANT_S)
        for i in range(1, times.size):
            regulator[i] = decay * regulator[i - 1] + (1 - decay) * command[i - 1]
        return floor, times, regulator

    _, _, drawn_regulator = protocol(drawn)

    def misfit(d: Departures) -> float:
        truth, thesis = (
            supplied_force(ThesisMuscle(build, m), held, drawn_regulator, braid_pushes=True)
            for m in (d, thesis_model_of(d))
        )
        return float(np.sqrt(np.mean((truth - thesis) ** 2)))

    departures, shrink, change = limit_departures(drawn, misfit, multiple * plan.noise_N)
    muscle = ThesisMuscle(build, departures)
    floor, times, regulator = protocol(departures)
    inside = regulator if not hose_lag_s else first_order_lag(times, regulator, hose_lag_s)
    force = supplied_force(muscle, held, inside, hysteresis=hysteresis)
    pushing = supplied_force(muscle, held, inside, hysteresis=hysteresis, braid_pushes=True)
    slack_rows = int(np.sum(pushing < 0))
    read = instruments.pressure_offset_kPa + instruments.pressure_gain * regulator
    columns = {
        "time_s": times,
        "elongation_m": bench.encoder(np.zeros_like(times), rng.noise, ENCODER_NOISE_M),
        "force_N": bench.load_cell(force, rng.noise, plan.noise_N),
        "pressure_kPa": bench.pressure_logger(read, rng.noise),
    }
    path = bench.write_experiment(
        folder,
        "test",
        asdict(build),
        {
            "description": "near-model world, isometric supplied-pressure sweep",
            "gas": "supplied",
            "inflation_pressure_kPa": 0.0,
            "ambient_temperature_C": plan.ambient_C,
            "initial_length_m": held,
        },
        columns,
        "Written by tests/independent (not pamkit): a muscle held by the rig, supplied pressure swept.",
    )
    info = {
        "seed": seed,
        "kind": SUPPLIED,
        "held_m": held,
        "floor_kPa": floor,
        "top_kPa": plan.top_kPa,
        "steps": plan.steps,
        "force_noise_N": plan.noise_N,
        "slack_rows": slack_rows,
        "departures": departures_truth(departures),
        "departures_shrunk_by": shrink,
        "departures_force_rms_N": change,
        "cause": causes,
    }
    present = ("braid_slack",) if slack_rows and "braid_slack" not in hidden else ()
    return NearDataset(path, hidden, strength, info, present)


# ----------------------------------------------------------------------------------------------
# the families


def _signed_level(value, rng):
    """A level written ("±", x) is drawn with a random sign; the draw is made either way."""
    sign = _sign(rng)
    return sign * value[1] if isinstance(value, tuple) and value[0] == "±" else value


def _family(name: str, causes: tuple[str, ...], kind: str, level_name: dict[str, str] | None = None) -> Family:
    """A family hiding `causes` (catalog names) at the levels of LEVELS (under `level_name`'s key
    for a cause whose levels differ by kind); with no cause, a null."""
    level_name = level_name or {}
    levels = {s: {c: LEVELS[level_name.get(c, c)][s] for c in causes} for s in STRENGTHS} if causes else {}
    test = sealed_test if kind == SEALED else supplied_sweep

    def make(seed, folder, strength=None, variant=None):
        # another test of the same muscle (sealed_test's `variant`); a supplied sweep has none
        varied = {"variant": variant} if variant else {}
        if not causes:
            return test(seed, folder, name, **varied)
        if strength not in STRENGTHS:
            raise ValueError(f"family {name}: strength {strength!r}, one of {', '.join(STRENGTHS)}")
        rng = np.random.default_rng([seed, 7, STRENGTHS.index(strength)])
        drawn = {c: {k: _signed_level(v, rng) for k, v in levels[strength][c].items()} for c in causes}
        return test(seed, folder, name, causes=drawn, hidden=causes, strength=strength, **varied)

    return Family(name, causes, kind, levels, make, lambda seed, folder: test(seed, folder, name))


# The levels: weak near what the sampling resolves, medium and strong plainly visible (fitted
# held-out gains of roughly 0.5-0.95; bench/README.md gives the measured ones). ("±", x) draws the
# sign. Two are set relative to the test, because a fixed value is invisible in one protocol and
# overwhelming in another: a leak by the share of the gauge pressure it loses over the test, and
# a viscoelastic bladder's time constant at half a stretch's duration, where its loop is widest.
LEVELS = {
    "heat_transfer": {s: {"time_constant_s": v} for s, v in zip(STRENGTHS, (0.15, 1.0, 5.0))},
    "dead_volume": {s: {"volume_fraction": v} for s, v in zip(STRENGTHS, (0.02, 0.1, 0.25))},
    "leak": {s: {"pressure_loss": v} for s, v in zip(STRENGTHS, (0.005, 0.05, 0.1))},
    "bladder_viscoelasticity": {
        s: {"time_constant": "half a stretch", "strength": v} for s, v in zip(STRENGTHS, (0.2, 1.0, 2.0))
    },
    "fiber_compliance": {s: {"stiffness_N": v} for s, v in zip(STRENGTHS, (600.0, 250.0, 100.0))},
    "fixture_slack": {s: {"slack_m": v} for s, v in zip(STRENGTHS, (0.3e-3, 1.2e-3, 2.5e-3))},
    "sensor_lag": {s: {"channel": "pressure_kPa", "time_constant_s": v} for s, v in zip(STRENGTHS, (0.05, 0.7, 2.0))},
    "time_skew": {s: {"channel": "pressure_kPa", "offset_s": ("±", v)} for s, v in zip(STRENGTHS, (0.05, 0.5, 1.5))},
    "sensor_offset": {
        s: {"offset_kPa": ("±", o), "gain": g} for s, o, g in zip(STRENGTHS, (1.5, 5.0, 10.0), (1.0, 1.02, 1.05))
    },
    "load_cell": {
        s: {"offset_N": ("±", o), "nonlinearity_per_kN": ("±", c)}
        for s, o, c in zip(STRENGTHS, (1.0, 5.0, 10.0), (0.03, 0.08, 0.15))
    },
    "thermometer": {s: {"offset_C": ("±", v)} for s, v in zip(STRENGTHS, (0.15, 1.0, 2.0))},
    "braid_slack": {s: {"depth_N": v} for s, v in zip(STRENGTHS, (2.0, 8.0, 15.0))},
    "pressure_hysteresis": {s: {"coefficient": v} for s, v in zip(STRENGTHS, (0.005, 0.05, 0.15))},
    "supplied_sensor_offset": {
        s: {"offset_kPa": ("±", o), "gain": g} for s, o, g in zip(STRENGTHS, (2.0, 8.0, 12.0), (1.0, 0.97, 0.94))
    },
    "supplied_sensor_lag": {
        s: {"channel": "pressure_kPa", "time_constant_s": v} for s, v in zip(STRENGTHS, (0.05, 0.4, 1.5))
    },
}


def resolve(causes: dict, duration_s: float, ramp_s: float) -> dict:
    """Catalog parameters of `causes` for a test lasting `duration_s` with stretches of `ramp_s`:
    a leak's pressure loss over the test becomes its time constant, a viscoelastic bladder's
    "half a stretch" its time constant."""
    out = {name: dict(parameters) for name, parameters in causes.items()}
    if "pressure_loss" in out.get("leak", {}):
        loss = out["leak"].pop("pressure_loss")
        out["leak"]["time_constant_s"] = duration_s / -math.log(1.0 - loss)
    if out.get("bladder_viscoelasticity", {}).get("time_constant") == "half a stretch":
        out["bladder_viscoelasticity"].pop("time_constant")
        out["bladder_viscoelasticity"]["time_constant_s"] = ramp_s / 2.0
    return out


def instruments_of(causes: dict) -> Instruments:
    """The instruments' causes among `causes` (catalog names and parameters)."""
    return Instruments(
        pressure_lag_s=causes.get("sensor_lag", {}).get("time_constant_s", 0.0),
        pressure_skew_s=causes.get("time_skew", {}).get("offset_s", 0.0),
        pressure_offset_kPa=causes.get("sensor_offset", {}).get("offset_kPa", 0.0),
        pressure_gain=causes.get("sensor_offset", {}).get("gain", 1.0),
        force_offset_N=causes.get("load_cell", {}).get("offset_N", 0.0),
        force_per_kN=causes.get("load_cell", {}).get("nonlinearity_per_kN", 0.0),
        temperature_offset_C=causes.get("thermometer", {}).get("offset_C", 0.0),
    )


def physics_of(causes: dict) -> dict:
    """A sealed test's effects, fixture play and instruments from resolved `causes`."""
    effects = Effects(
        heat_time_constant_s=causes.get("heat_transfer", {}).get("time_constant_s"),
        dead_volume_fraction=causes.get("dead_volume", {}).get("volume_fraction", 0.0),
        leak_time_constant_s=causes.get("leak", {}).get("time_constant_s"),
        viscoelastic_time_constant_s=causes.get("bladder_viscoelasticity", {}).get("time_constant_s", 2.0),
        viscoelastic_strength=causes.get("bladder_viscoelasticity", {}).get("strength", 0.0),
        fiber_stiffness_N=causes.get("fiber_compliance", {}).get("stiffness_N"),
    )
    return {
        "effects": effects,
        "slack_m": causes.get("fixture_slack", {}).get("slack_m", 0.0),
        "instruments": instruments_of(causes),
    }


SEALED_CAUSES = (
    "heat_transfer",
    "dead_volume",
    "leak",
    "bladder_viscoelasticity",
    "fiber_compliance",
    "fixture_slack",
    "sensor_lag",
    "time_skew",
    "sensor_offset",
    "load_cell",
    "thermometer",
)
PAIRS = (("heat_transfer", "sensor_offset"), ("leak", "time_skew"), ("dead_volume", "load_cell"))


def _families() -> dict[str, Family]:
    out = {"null": _family("null", (), SEALED), "supplied_null": _family("supplied_null", (), SUPPLIED)}
    for cause in SEALED_CAUSES:
        out[cause] = _family(cause, (cause,), SEALED)
    out["braid_slack"] = _family("braid_slack", ("braid_slack",), SUPPLIED)
    out["pressure_hysteresis"] = _family("pressure_hysteresis", ("pressure_hysteresis",), SUPPLIED)
    for cause in ("sensor_offset", "sensor_lag"):
        out[f"supplied_{cause}"] = _family(f"supplied_{cause}", (cause,), SUPPLIED, {cause: f"supplied_{cause}"})
    for first, second in PAIRS:
        out[f"{first}+{second}"] = _family(f"{first}+{second}", (first, second), SEALED)
    return out


FAMILIES: dict[str, Family] = _families()

# The fast loop: every family once at medium strength and four nulls (seed 1; nulls 1-3 sealed,
# 1 supplied) - a subset the lead can run in a few minutes and later test as a rate.
QUICK = tuple((name, 1, "medium") for name, f in FAMILIES.items() if f.hidden) + (
    ("null", 1, None),
    ("null", 2, None),
    ("null", 3, None),
    ("supplied_null", 1, None),
)
