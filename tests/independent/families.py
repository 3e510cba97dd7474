"""Families of bench tests that hide a cause, made by the independent model (docs/validation.md).

Each family is a function ``make(seed, folder) -> Dataset``: it writes ``test.toml`` and
``test.csv`` into `folder` and returns what was hidden and the verdict expected. ``expected`` is
a catalog effect's name when the cause is in pamkit's catalog, or ``HONEST`` when it is not (or
is below what the sampling resolves): then ``none`` within the noise or ``unexplained`` are the
acceptable verdicts and any catalog name is wrong.

One seed draws the same protocol, build and instrument noise in every family (three independent
streams spawned from it), so that families differ by their cause only.
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass, field, replace
from pathlib import Path

import numpy as np

from . import bench, dmsp
from .physics import Build, Geometry, Motion, Physics, SealedMuscle, supplied_tension

HONEST = "honest"
INFLATION_KPA = (35.0, 276.0)  # gauge, the thesis's range (tables 3.4, C.1-C.3)
AMBIENT_C = (20.0, 25.0)
STRETCH_FRACTION = (0.8, 0.95)  # of the free contraction (thesis tables 3.5, C.1-C.3)
SPEED_M_PER_S = (2.5e-3, 50e-3)  # log-uniform
CYCLES = (5, 10)
ALTERNATING_SPEEDS_M_PER_S = (4e-3, 25e-3)
MIN_SAMPLES_PER_RAMP = 25


@dataclass
class Dataset:
    experiment: Path
    expected: str
    truth: dict = field(default_factory=dict)
    # catalog names of physics the independent model has built in and this dataset shows (its
    # braid goes slack where its force would turn negative): right if named, though not hidden
    present: tuple[str, ...] = ()


@dataclass
class Draws:
    protocol: np.random.Generator
    effect: np.random.Generator
    noise: np.random.Generator


def draws(seed: int) -> Draws:
    return Draws(*(np.random.default_rng(s) for s in np.random.SeedSequence(seed).spawn(3)))


def _muscle_toml(build: Build) -> dict:
    return asdict(build)


# ----------------------------------------------------------------------------------------------
# sealed cyclic tests


@dataclass
class SealedPlan:
    gauge_kPa: float
    ambient_C: float
    fraction: float
    speeds: list  # per cycle [m/s]
    rest_before_s: float
    rest_after_s: float = 1.0


def draw_sealed_plan(rng: np.random.Generator) -> SealedPlan:
    speed = math.exp(rng.uniform(math.log(SPEED_M_PER_S[0]), math.log(SPEED_M_PER_S[1])))
    cycles = int(rng.integers(CYCLES[0], CYCLES[1] + 1))
    return SealedPlan(
        gauge_kPa=round(rng.uniform(*INFLATION_KPA), 2),
        ambient_C=round(rng.uniform(*AMBIENT_C), 2),
        fraction=rng.uniform(*STRETCH_FRACTION),
        speeds=[round(speed, 5)] * cycles,
        rest_before_s=round(rng.uniform(1.0, 3.0), 1),
    )


def sample_rate(top_m: float, speeds) -> float:
    """20 Hz unless a stretch would get fewer than 25 samples, then 50 Hz (a lab sets the rate
    so that a stretch is a curve)."""
    return 20.0 if top_m / max(speeds) * 20.0 >= MIN_SAMPLES_PER_RAMP else 50.0


def crosshead(plan: SealedPlan, top_m: float, rate: float) -> Motion:
    """Triangle cycles with every corner on a sample (ramps a whole number of periods)."""
    period = 1.0 / rate
    t, x = [0.0, round(plan.rest_before_s / period) * period], [0.0, 0.0]
    for speed in plan.speeds:
        ramp = max(1, round(top_m / speed / period)) * period
        t += [t[-1] + ramp, t[-1] + 2 * ramp]
        x += [top_m, 0.0]
    t.append(t[-1] + plan.rest_after_s)
    x.append(0.0)
    return Motion(np.asarray(t), np.asarray(x))


def sealed_test(
    seed: int,
    folder: Path,
    *,
    physics: Physics | None = None,
    plan_change=None,
    record=None,
    expected: str = HONEST,
    truth: dict | None = None,
    muscle_change: dict | None = None,
) -> Dataset:
    """One sealed test. `plan_change(plan, rng)` alters the protocol; `record(muscle, motion,
    times, rate, rngs)` turns the truth into the columns (default: the bench's instruments);
    `muscle_change` overrides [muscle] keys in the TOML only (a declared build that is off)."""
    rng = draws(seed)
    build = Build()
    plan = draw_sealed_plan(rng.protocol)
    if plan_change is not None:
        plan = plan_change(plan, rng.effect)
    muscle = SealedMuscle(build, physics or Physics(), plan.gauge_kPa, plan.ambient_C)
    top = round(plan.fraction * (build.length_m - muscle.free_length_m), 4)  # programmed in 0.1 mm
    rate = sample_rate(top, plan.speeds)
    motion = crosshead(plan, top, rate)
    times = np.arange(0.0, motion.corner_t[-1] + 1e-9, 1.0 / rate)
    columns = (record or record_sealed)(muscle, motion, times, rate, rng)
    muscle_toml = {**_muscle_toml(build), **(muscle_change or {})}
    test = {
        "description": "independent model, sealed cyclic test",
        "inflation_pressure_kPa": plan.gauge_kPa,
        "ambient_temperature_C": plan.ambient_C,
        "initial_length_m": round(muscle.free_length_m, 4),
    }
    path = bench.write_experiment(
        folder,
        "test",
        muscle_toml,
        test,
        columns,
        "Written by tests/independent (not pamkit): a sealed muscle stretched on a tensile machine.",
    )
    info = {
        "gauge_kPa": plan.gauge_kPa,
        "speeds_mm_per_s": sorted({round(s * 1e3, 3) for s in plan.speeds}),
        "cycles": len(plan.speeds),
        "top_mm": top * 1e3,
        "rate_Hz": rate,
        **(truth or {}),
    }
    return Dataset(path, expected, info)


def record_sealed(muscle, motion, times, rate, rng, *, force=None, pressure_times=None, elongation=None):
    run = muscle.run(motion, times)
    logged = run if pressure_times is None else muscle.run(motion, pressure_times)
    return {
        "time_s": times,
        "elongation_m": bench.encoder(run.elongation_m if elongation is None else elongation(run.elongation_m)),
        "force_N": bench.load_cell(run.force_N if force is None else force(run.force_N), rng.noise),
        "pressure_kPa": bench.pressure_logger(logged.gauge_kPa, rng.noise),
        "temperature_C": bench.temperature_logger(logged.temperature_C, rng.noise),
    }


def _signed(rng, low, high):
    return float(rng.choice([-1.0, 1.0]) * rng.uniform(low, high))


# the families ---------------------------------------------------------------------------------


def independent_null(seed, folder):
    return sealed_test(seed, folder)


def independent_heat_transfer(seed, folder):
    tau = math.exp(np.random.default_rng([seed, 1]).uniform(math.log(0.5), math.log(10.0)))
    return sealed_test(
        seed,
        folder,
        physics=Physics(heat_time_constant_s=tau),
        expected="heat_transfer",
        truth={"time_constant_s": tau},
    )


def independent_dead_volume(seed, folder):
    fraction = np.random.default_rng([seed, 2]).uniform(0.03, 0.3)
    return sealed_test(
        seed,
        folder,
        physics=Physics(dead_volume_fraction=fraction),
        expected="dead_volume",
        truth={"volume_fraction": fraction},
    )


def independent_dead_volume_two_inflations(seed, folder):
    """independent_dead_volume's muscle and test, run again inflated half as high again: a
    campaign of the two (the second test is the one a tie on the first names)."""
    first = independent_dead_volume(seed, folder / "first")
    gauge_kPa = round(1.5 * first.truth["gauge_kPa"], 2)
    sealed_test(
        seed,
        folder / "second",
        physics=Physics(dead_volume_fraction=first.truth["volume_fraction"]),
        plan_change=lambda plan, rng: replace(plan, gauge_kPa=gauge_kPa),
    )
    campaign = folder / "campaign.toml"
    campaign.write_text('[campaign]\ntests = ["first/test.toml", "second/test.toml"]\n')
    return Dataset(campaign, "dead_volume", {**first.truth, "second_gauge_kPa": gauge_kPa})


def independent_leak(seed, folder):
    tau = math.exp(np.random.default_rng([seed, 3]).uniform(math.log(100.0), math.log(3000.0)))
    return sealed_test(
        seed, folder, physics=Physics(leak_time_constant_s=tau), expected="leak", truth={"time_constant_s": tau}
    )


def load_cell_tare(seed, folder):
    tare = _signed(np.random.default_rng([seed, 4]), 2.0, 6.0)
    return sealed_test(
        seed,
        folder,
        record=lambda *a: record_sealed(*a, force=lambda f: f + tare),
        expected="load_cell",
        truth={"tare_N": tare},
    )


def load_cell_nonlinear(seed, folder):
    """Reads F + k F², k set so that the error at 300 N is 2-5 % of the reading."""
    k = _signed(np.random.default_rng([seed, 5]), 0.02, 0.05) / 300.0
    return sealed_test(
        seed,
        folder,
        record=lambda *a: record_sealed(*a, force=lambda f: f + k * f * f),
        expected="load_cell",
        truth={"k_per_N": k},
    )


def load_cell_drift(seed, folder):
    """The load cell's zero creeps by 2-6 N over the test, linearly in time (a strain gauge
    warming up): in no catalog effect (the load cell's own is an offset held through the test)."""
    drift = _signed(np.random.default_rng([seed, 15]), 2.0, 6.0)

    def record(muscle, motion, times, rate, rng):
        ramp = drift * (times - times[0]) / (times[-1] - times[0])
        return record_sealed(muscle, motion, times, rate, rng, force=lambda f: f + ramp)

    return sealed_test(seed, folder, record=record, truth={"drift_N": drift})


def travel_scale(seed, folder):
    scale = 1.0 + _signed(np.random.default_rng([seed, 6]), 0.02, 0.04)
    return sealed_test(
        seed, folder, record=lambda *a: record_sealed(*a, elongation=lambda x: x * scale), truth={"scale": scale}
    )


def declared_length(seed, folder):
    error = _signed(np.random.default_rng([seed, 7]), 1e-3, 2e-3)
    return sealed_test(
        seed, folder, muscle_change={"length_m": round(Build().length_m + error, 4)}, truth={"error_m": error}
    )


def declared_diameter(seed, folder):
    """The TOML's braid diameter 0.3-0.6 mm off (a caliper on a soft braid)."""
    error = _signed(np.random.default_rng([seed, 14]), 0.3e-3, 0.6e-3)
    return sealed_test(
        seed, folder, muscle_change={"diameter_m": round(Build().diameter_m + error, 5)}, truth={"error_m": error}
    )


def mullins(seed, folder):
    eta = np.random.default_rng([seed, 8]).uniform(0.2, 0.4)
    return sealed_test(seed, folder, physics=Physics(mullins_softening=eta), truth={"softening": eta})


def coulomb_alternating(seed, folder):
    """Rate-independent friction, twice to three times the null's, on cycles alternating 4 and
    25 mm/s: a viscous-like law cannot follow both rates."""
    factor = np.random.default_rng([seed, 9]).uniform(2.0, 3.0)

    def alternate(plan, _):
        plan.speeds = [ALTERNATING_SPEEDS_M_PER_S[i % 2] for i in range(len(plan.speeds))]
        return plan

    base = Physics()
    physics = Physics(friction_m2=base.friction_m2 * factor, friction_velocity_m_per_s=2e-4)
    return sealed_test(seed, folder, physics=physics, plan_change=alternate, truth={"friction_factor": factor})


def dahl(seed, folder):
    rng = np.random.default_rng([seed, 10])
    factor, length = rng.uniform(1.5, 3.0), rng.uniform(1e-3, 3e-3)
    physics = Physics(friction_m2=Physics().friction_m2 * factor, dahl_length_m=length)
    return sealed_test(seed, folder, physics=physics, truth={"friction_factor": factor, "presliding_m": length})


def subsample_skew(seed, folder):
    """The Arduino's channels read 0.2-0.8 of a sample interval early or late."""
    fraction = _signed(np.random.default_rng([seed, 11]), 0.2, 0.8)

    def record(muscle, motion, times, rate, rng):
        shifted = np.clip(times + fraction / rate, 0.0, times[-1])
        return record_sealed(muscle, motion, times, rate, rng, pressure_times=shifted)

    return sealed_test(seed, folder, record=record, truth={"skew_samples": fraction})


def subsample_lag(seed, folder):
    """The pressure channel lags through a first-order filter of 0.2-0.8 sample intervals."""
    fraction = np.random.default_rng([seed, 12]).uniform(0.2, 0.8)

    def record(muscle, motion, times, rate, rng):
        fine = np.arange(0.0, times[-1] + 1e-9, 1.0 / (rate * 20))
        run = muscle.run(motion, fine)
        tau = fraction / rate
        decay = math.exp(-(fine[1] - fine[0]) / tau)
        lagged = np.empty_like(run.gauge_kPa)
        lagged[0] = run.gauge_kPa[0]
        for i in range(1, fine.size):
            lagged[i] = decay * lagged[i - 1] + (1 - decay) * run.gauge_kPa[i]
        columns = record_sealed(muscle, motion, times, rate, rng)
        columns["pressure_kPa"] = bench.pressure_logger(np.interp(times, fine, lagged), rng.noise)
        return columns

    return sealed_test(seed, folder, record=record, truth={"lag_samples": fraction})


def subsample_slack(seed, folder):
    """A slack link in the fixture: the muscle is stretched max(0, x − s) by a crosshead at x,
    s 0.2-0.8 of the crosshead's travel per sample."""
    fraction = np.random.default_rng([seed, 13]).uniform(0.2, 0.8)

    def record(muscle, motion, times, rate, rng):
        slack = fraction * max(abs(np.diff(motion.corner_x) / np.diff(motion.corner_t))) / rate
        t_fine = np.union1d(motion.corner_t, _crossings(motion, slack))
        muscle_motion = Motion(t_fine, np.maximum(motion.elongation(t_fine) - slack, 0.0))
        columns = record_sealed(muscle, muscle_motion, times, rate, rng)
        columns["elongation_m"] = bench.encoder(motion.elongation(times))
        return columns

    return sealed_test(seed, folder, record=record, truth={"slack_samples": fraction})


def _crossings(motion: Motion, level: float) -> np.ndarray:
    """Instants where the piecewise-linear crosshead passes `level`."""
    t, x = motion.corner_t, motion.corner_x
    out = []
    for k in range(t.size - 1):
        if (x[k] - level) * (x[k + 1] - level) < 0:
            out.append(t[k] + (level - x[k]) / (x[k + 1] - x[k]) * (t[k + 1] - t[k]))
    return np.asarray(out)


# ----------------------------------------------------------------------------------------------
# isometric supplied-pressure sweeps


REGULATOR_TIME_CONSTANT_S = 0.4  # a proportional regulator's settling, first order
ISOMETRIC_RATE_HZ = 20.0
ENCODER_NOISE_M = 2e-6  # a held crosshead still dithers by a couple of encoder counts


def isometric_sweep(seed, folder, *, transducer=None, expected=HONEST, truth=None, encoder_noise_m=ENCODER_NOISE_M):
    """Length held at 92-97 % of the deflated length; pressure stepped up to 150-300 kPa in
    5-8 plateaus of 5-10 s, then down the same steps and vented to 0; force measured."""
    rng = draws(seed)
    build = Build()
    held = round(build.length_m * rng.protocol.uniform(0.92, 0.97), 4)
    steps = int(rng.protocol.integers(5, 9))
    top = rng.protocol.uniform(150.0, 300.0)
    dwell = rng.protocol.uniform(5.0, 10.0)
    ambient = round(rng.protocol.uniform(*AMBIENT_C), 2)
    levels = np.concatenate([np.linspace(0, top, steps + 1), np.linspace(top, 0, steps + 1)[1:]])
    times = np.arange(0.0, dwell * levels.size + 1e-9, 1.0 / ISOMETRIC_RATE_HZ)
    command = levels[np.minimum((times // dwell).astype(int), levels.size - 1)]
    pressure = np.empty_like(command)  # the regulator's exact first-order response to each step
    pressure[0] = command[0]
    decay = math.exp(-1.0 / ISOMETRIC_RATE_HZ / REGULATOR_TIME_CONSTANT_S)
    for i in range(1, times.size):
        pressure[i] = decay * pressure[i - 1] + (1 - decay) * command[i - 1]
    force = supplied_tension(build, Physics(), held, pressure)
    pushing = int(np.sum(Geometry(build).static_tension(held, pressure * 1e3, Physics().shear_modulus_Pa) < 0))
    read = pressure if transducer is None else transducer(pressure)
    columns = {
        "time_s": times,
        "elongation_m": bench.encoder(np.zeros_like(times), rng.noise, encoder_noise_m),
        "force_N": bench.load_cell(force, rng.noise),
        "pressure_kPa": bench.pressure_logger(read, rng.noise),
    }
    test = {
        "description": "independent model, isometric supplied-pressure sweep",
        "gas": "supplied",
        "inflation_pressure_kPa": 0.0,
        "ambient_temperature_C": ambient,
        "initial_length_m": held,
    }
    path = bench.write_experiment(
        folder,
        "test",
        _muscle_toml(build),
        test,
        columns,
        "Written by tests/independent (not pamkit): a muscle held by the rig, supplied pressure swept.",
    )
    present = ("braid_slack",) if pushing else ()
    truth = {"held_m": held, "top_kPa": top, "steps": steps, "slack_samples": pushing, **(truth or {})}
    return Dataset(path, expected, truth, present)


def isometric_null(seed, folder):
    return isometric_sweep(seed, folder)


def isometric_held_exactly(seed, folder):
    """The null sweep with the elongation column exactly 0 (an export of the commanded position)."""
    return isometric_sweep(seed, folder, encoder_noise_m=0.0)


def isometric_transducer_offset(seed, folder):
    """The supplied pressure's transducer reads 0.96 p − 10 kPa."""
    return isometric_sweep(
        seed, folder, transducer=lambda p: 0.96 * p - 10.0, truth={"gain": 0.96, "offset_kPa": -10.0}
    )


# ----------------------------------------------------------------------------------------------
# a commercial muscle's settled tables (dmsp.py: fibres in the membrane, flat flanges, friction
# with memory in 400 elements)


def _dmsp_truth(seed: int, friction: bool = True) -> dmsp.DmspTruth:
    """A DMSP-10-like muscle: its braid angle, end zones and friction drawn per seed."""
    rng = np.random.default_rng([seed, 16])
    return dmsp.DmspTruth(
        braid_angle_deg=float(rng.uniform(20.0, 25.0)),
        end_zone_m=float(rng.uniform(0.006, 0.010)),
        slip_force_N=float(rng.uniform(60.0, 200.0)) if friction else 0.0,
        slip_distance_m=float(rng.uniform(0.01, 0.025)),
    )


def dmsp_map_one_within(seed, folder):
    """An isometric map at four held lengths of which one (5 mm short of rest) contracts less than
    the friction's break-away distance: held out, it is predicted with a distance only it tells."""
    truth = _dmsp_truth(seed)
    path = dmsp.write_dmsp_isometric(folder, truth, lengths_m=[0.25, 0.245, 0.215, 0.205], top_kPa=600, seed=seed)
    return Dataset(path, "slip_hysteresis", asdict(truth))


def dmsp_map_frictionless(seed, folder):
    """The same map of a muscle without friction: its braid only goes slack, as an embedded one must."""
    truth = _dmsp_truth(seed, friction=False)
    path = dmsp.write_dmsp_isometric(folder, truth, lengths_m=[0.25, 0.245, 0.215, 0.205], top_kPa=600, seed=seed)
    return Dataset(path, HONEST, asdict(truth))


def dmsp_isotonic(seed, folder):
    """Three isotonic sweeps to 6 bar under a weighed 120 N, settled steps, the length by laser."""
    truth = _dmsp_truth(seed)
    path = dmsp.write_dmsp_isotonic(folder, truth, load_N=120.0, top_kPa=600, sweeps=3, seed=seed)
    return Dataset(path, "slip_hysteresis", asdict(truth))


# A lab's first tests of a cut muscle: one held length, one or two isotonic sweeps.
CUT_M = (0.10, 0.40)
MOUNTED_SHORT = 0.015  # kinked, or the clamps' play: the muscle contracts slack until taut


def _cut(seed: int, friction: bool = True) -> dmsp.DmspTruth:
    return replace(_dmsp_truth(seed, friction), rest_length_m=CUT_M[seed % 2])


def dmsp_one_length_short(seed, folder):
    """A cut muscle held 1.5 % short of its rest length, pressurised to 6 bar and vented once:
    it contracts slack until taut, and its friction keeps what it took up."""
    truth = _cut(seed)
    held = [truth.rest_length_m * (1.0 - MOUNTED_SHORT)]
    path = dmsp.write_dmsp_isometric(folder, truth, lengths_m=held, top_kPa=600, seed=seed, sweeps=1)
    return Dataset(path, "slip_hysteresis", asdict(truth))


def dmsp_one_length_straight(seed, folder):
    """The same muscle held straight at its rest length: its braid never moves, nothing to name."""
    truth = _cut(seed)
    path = dmsp.write_dmsp_isometric(folder, truth, lengths_m=[truth.rest_length_m], top_kPa=600, seed=seed, sweeps=1)
    return Dataset(path, HONEST, asdict(truth))


def dmsp_isotonic_one_sweep(seed, folder):
    """One isotonic sweep to 6 bar and back under a weighed 120 N."""
    truth = _dmsp_truth(seed)
    path = dmsp.write_dmsp_isotonic(folder, truth, load_N=120.0, top_kPa=600, sweeps=1, seed=seed)
    return Dataset(path, "slip_hysteresis", asdict(truth))


def dmsp_isotonic_two_sweeps(seed, folder):
    """Two isotonic sweeps under a weighed 120 N: the first from rest."""
    truth = _dmsp_truth(seed)
    path = dmsp.write_dmsp_isotonic(folder, truth, load_N=120.0, top_kPa=600, sweeps=2, seed=seed)
    return Dataset(path, "slip_hysteresis", asdict(truth))


def dmsp_isotonic_frictionless(seed, folder):
    """Two sweeps of a muscle without friction, from 2 bar (vented, nothing would hold the load)."""
    truth = _dmsp_truth(seed, friction=False)
    path = dmsp.write_dmsp_isotonic(folder, truth, load_N=120.0, top_kPa=600, sweeps=2, seed=seed, bottom_kPa=200.0)
    return Dataset(path, HONEST, asdict(truth))


def dmsp_map_transducer_offset(seed, folder):
    """The frictionless map, its pressure read 10 kPa high (within the catalog's realistic 12 kPa):
    every held length's line shifted."""
    truth = _dmsp_truth(seed, friction=False)
    path = dmsp.write_dmsp_isometric(
        folder, truth, lengths_m=[0.25, 0.245, 0.215, 0.205], top_kPa=600, seed=seed, pressure_offset_kPa=10.0
    )
    return Dataset(path, "sensor_offset", {**asdict(truth), "offset_kPa": 10.0})


FAMILIES = {
    f.__name__: f
    for f in (
        independent_null,
        independent_heat_transfer,
        independent_dead_volume,
        independent_dead_volume_two_inflations,
        independent_leak,
        load_cell_tare,
        load_cell_nonlinear,
        load_cell_drift,
        travel_scale,
        declared_length,
        declared_diameter,
        mullins,
        coulomb_alternating,
        dahl,
        subsample_skew,
        subsample_lag,
        subsample_slack,
        isometric_null,
        isometric_held_exactly,
        isometric_transducer_offset,
        dmsp_map_one_within,
        dmsp_map_frictionless,
        dmsp_isotonic,
        dmsp_one_length_short,
        dmsp_one_length_straight,
        dmsp_isotonic_one_sweep,
        dmsp_isotonic_two_sweeps,
        dmsp_isotonic_frictionless,
        dmsp_map_transducer_offset,
    )
}
