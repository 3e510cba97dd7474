"""The test that would tell two explanations apart which this one cannot.

When two candidates explain the held-out units alike (rule 6 of decide.py), naming either would be
a guess, and the user's next question is what to measure; so too when a cause is named only
narrowly ahead of a rival (decide.close_rival: to confirm it), and when an instrument's error was
refused as not needed (instruments.unfounded, .misread: to check for it, against the model without
it). Each fitted model is run on a few variants of the test the lab can run on the same muscle and rig —
inflated higher or lower (a supplied test: the supplied pressure raised or lowered), the same
motion slower or faster, the instruments read with the muscle vented and unloaded (a zero run) —
and the variant on which their predictions differ most, in units of each channel's noise, is the
one to run. Model discrimination by the largest predicted difference (Hunter and Reiner's
criterion for two rival models, with the noise as the yardstick), on protocols a lab changes
without rebuilding anything. Run, that test is diagnosed beside this one as a campaign
(series/campaign.py), which carries both candidates to each test and names the one that holds on
both.

Why these variants: the catalog's effects that tie on one test differ in how they scale. A dead
volume changes the gas's relative pressure swing whatever the pressure; stretching fibres
carry a tension that grows with it, so the two part at another inflation pressure. Heat exchange,
a leak, a viscous bladder and a lagging sensor have time constants, which a slower or faster
stretch shows. An instrument's offset is read directly where the true value is known: vented,
unloaded, at ambient.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from pamkit._core import (
    EffectStage,
    ElongationTrajectory,
    Error,
    GasMode,
    InvalidInput,
    InvalidParameter,
    Measurement,
    SolverError,
    inflated_and_sealed,
    simulate_measurement,
    simulate_supplied_measurement,
)
from pamkit.diagnosis.series.calibrate import Fit
from pamkit.diagnosis.series.kinds import Problem
from pamkit.diagnosis.significance import NONE_WITHIN_NOISE
from pamkit.io.columns import file_unit, value_from_si
from pamkit.simulation import initial_length, with_effects

PRESSURE = "gauge_pressure_Pa"
# What a variant the model cannot run raises: a length beyond the braid's range, a pressure it
# cannot inflate to, a solver that fails.
RUN_FAILURES = (Error, InvalidInput, InvalidParameter, SolverError)

# A variant separates two models when they differ on a channel by this many times its noise (RMS
# over the run): the difference the "none" rule reads as structure left, so that the model which
# is wrong would leave it.
SEPARATES = NONE_WITHIN_NOISE


@dataclass(frozen=True)
class Variant:
    """A test the lab can run on the same muscle and rig instead of this one."""

    key: str
    # a sealed test: the inflation raised until the transducer reads this share of the declared
    # pressure more, the muscle inflated freely and sealed (the thesis's protocol); a supplied
    # test: the supplied pressure raised or lowered by this share at every sample
    pressure_share: float = 0.0
    time_scale: float = 1.0  # the motion's times multiplied by this (10: ten times slower)
    zero_reading: bool = False  # the instruments read a vented, unloaded muscle at ambient

    def describe(self, declared_Pa: float | None) -> dict:
        """What the variant is, in SI (the report turns it into the file's units), for a sealed
        test inflated to `declared_Pa` or a supplied test (None)."""
        text: dict = {"key": self.key}
        if self.pressure_share and declared_Pa is not None:
            text["inflation_gauge_pressure_Pa"] = declared_Pa * (1.0 + self.pressure_share)
        elif self.pressure_share:
            text["pressure_scale"] = 1.0 + self.pressure_share
        if self.time_scale != 1.0:
            text["time_scale"] = self.time_scale
        return text


AS_RUN = Variant("as_run")
ZERO_RUN = Variant("zero_run", zero_reading=True)
VARIANTS = (
    Variant("pressure_higher", pressure_share=0.5),
    # Stretching fibres part from a dead volume by the tension the pressure puts in them: at half
    # the pressure the fibres' share shrinks under the membrane's, whose law the model knows least.
    Variant("pressure_double", pressure_share=1.0),
    Variant("pressure_lower", pressure_share=-0.5),
    Variant("slower", time_scale=10.0),
    Variant("faster", time_scale=0.2),
    ZERO_RUN,
)


@dataclass
class Separation:
    """Which variant tells two fits apart, and by how much."""

    between: tuple[str, str]
    variant: Variant | None  # the variant that separates most; None if none could be run
    declared_Pa: float | None  # a sealed test's declared inflation gauge pressure [Pa]; None: supplied
    apart: dict[str, float]  # per channel: RMS difference over the noise on that variant
    here: dict[str, float]  # the same on this test as run
    tried: dict[str, float | str] = field(default_factory=dict)  # variant key: largest ratio, or why not run
    # the two models' measurements on that variant, in `between`'s order (the report's figure)
    predictions: tuple[Measurement, Measurement] | None = field(default=None, repr=False)
    # "tie": neither could be named (decide.py, rule 6); "confirm": the first is named, the second
    # explains nearly as much (decide.close_rival), and the test would confirm the first; "check":
    # the first, an instrument's error the data did not need (instruments.unfounded), against the
    # calibrated baseline (the second), and the test would show whether it is there
    purpose: str = "tie"

    @property
    def separates(self) -> bool:
        return self.variant is not None and max(self.apart.values(), default=0.0) >= SEPARATES

    def test_phrase(self) -> str:
        """The separating variant as a lab would set it up, in the data file's units."""
        test = self.variant.describe(self.declared_Pa)
        if self.variant.zero_reading:
            return "a zero run (the instruments read with the muscle vented and unloaded)"
        if "pressure_scale" in test:
            change = "higher" if test["pressure_scale"] > 1 else "lower"
            return f"the same sweep with the supplied pressure {abs(test['pressure_scale'] - 1):.0%} {change}"
        if "inflation_gauge_pressure_Pa" in test:
            pressure = value_from_si(PRESSURE, test["inflation_gauge_pressure_Pa"])
            declared = value_from_si(PRESSURE, self.declared_Pa)
            unit = file_unit(PRESSURE)
            return (
                f"the same stretches with the muscle inflated freely to {pressure:.0f} {unit} and sealed (this "
                f"test: {declared:.0f} {unit})"
            )
        scale = test["time_scale"]
        motion = "stretches" if self.declared_Pa is not None else "sweep"
        return (
            f"the same {motion} {scale:g} times slower"
            if scale > 1
            else f"the same {motion} {1 / scale:g} times faster"
        )

    def to_json(self) -> dict:
        return {
            "purpose": self.purpose,
            "between": list(self.between),
            "test": self.variant.describe(self.declared_Pa) if self.variant else None,
            "separates": self.separates,
            "difference_over_noise": self.apart,
            "here_over_noise": self.here,
            "tried": self.tried,
            "separates_from": SEPARATES,
        }


def _steady_reading(fit: Fit, gauge_Pa: float, ambient_K: float) -> Measurement:
    """What the fit's instruments read of a muscle at rest, unloaded, at gauge pressure `gauge_Pa`:
    two readings a second apart (an instrument's lag or skew reads a constant as it is)."""
    m = Measurement()
    m.time_s = [0.0, 1.0]
    m.elongation_m = [0.0, 0.0]
    m.force_N = [0.0, 0.0]
    m.gauge_pressure_Pa = [gauge_Pa, gauge_Pa]
    m.temperature_K = [ambient_K, ambient_K]
    for effect in fit.effects:
        if effect.stage() == EffectStage.measurement:
            m = effect.apply_to_measurement(m)
    return m


def _run(problem: Problem, fit: Fit, variant: Variant) -> Measurement:
    """The fitted model's measurement on `variant` of the test."""
    predictor = problem.predictor
    params, inflation_Pa = predictor.baseline.model_params(fit.baseline_x)
    ambient_K = params.gas.ambient_temperature_K
    if variant.zero_reading:
        return _steady_reading(fit, 0.0, ambient_K)
    experiment = problem.experiment
    played = experiment.gas == GasMode.sealed and predictor.moves_muscle(fit.effects)
    motion = predictor.played_motion if played else predictor.motion
    trajectory = ElongationTrajectory(np.asarray(motion.time_s) * variant.time_scale, motion.elongation_m)
    if experiment.gas == GasMode.supplied:
        supplied = np.asarray(experiment.columns["gauge_pressure_Pa"]) * (1.0 + variant.pressure_share)
        return simulate_supplied_measurement(
            params, initial_length(experiment, params), trajectory, supplied, fit.effects
        )
    if variant.pressure_share:
        # The lab inflates until its transducer reads the new pressure: the reading moves by the
        # share of the declared pressure, and the gas by that through the fit's transducer.
        change = variant.pressure_share * experiment.inflation_gauge_pressure_Pa
        _, top = experiment.reading_range(PRESSURE)
        if experiment.inflation_gauge_pressure_Pa + change > top:
            raise InvalidInput(
                f"{experiment.inflation_gauge_pressure_Pa + change:.6g} Pa is beyond what the transducer reads"
            )
        read = [_steady_reading(fit, p, ambient_K).gauge_pressure_Pa[0] for p in (inflation_Pa, inflation_Pa + change)]
        if not (read[1] - read[0]) / change > 0.0:
            raise InvalidInput(f"the fit's transducer reads {read[0]:.6g} Pa at both pressures")
        # The muscle inflated is the muscle with its effects.
        start = inflated_and_sealed(
            with_effects(params, fit.effects), inflation_Pa + change * change / (read[1] - read[0])
        )
    else:
        start = predictor.initial_state(with_effects(params, fit.effects), inflation_Pa)
    run = simulate_measurement(params, start, trajectory, fit.effects, predictor.simulator)
    return predictor.played_measurement(run) if played else run


def _differences(problem: Problem, a: Fit, b: Fit, variant: Variant):
    """Per channel, the RMS of the two fits' difference over the channel's noise on `variant`;
    and the two measurements."""
    ma, mb = _run(problem, a, variant), _run(problem, b, variant)
    ratios = {
        c: float(np.sqrt(np.mean(((np.asarray(getattr(ma, c)) - np.asarray(getattr(mb, c))) / problem.sigma[c]) ** 2)))
        for c in problem.channels
    }
    return ratios, (ma, mb)


def separating_test(
    problem: Problem, a: Fit, b: Fit, purpose: str = "tie", variants: tuple[Variant, ...] = VARIANTS
) -> Separation:
    """The variant among `variants` on which fits `a` and `b` differ most (see the module
    docstring), for a tie, to confirm `a` against a close `b`, or to check for `a` against `b`, the
    model without it (`purpose`)."""
    experiment = problem.experiment
    declared = experiment.inflation_gauge_pressure_Pa if experiment.gas == GasMode.sealed else None
    here, _ = _differences(problem, a, b, AS_RUN)
    best = None
    tried: dict[str, float | str] = {}
    for variant in variants:
        if variant.zero_reading and experiment.zeroed:
            tried[variant.key] = "not run: the test has its zero run"
            continue
        try:
            apart, runs = _differences(problem, a, b, variant)
        except RUN_FAILURES as error:
            tried[variant.key] = f"not run: {error}"
            continue
        largest = max(apart.values())
        if not math.isfinite(largest):
            tried[variant.key] = "not run: a prediction is not finite"
            continue
        tried[variant.key] = largest
        if best is None or largest > best[0]:
            best = (largest, variant, apart, runs)
    if best is None:
        return Separation((a.name, b.name), None, declared, {}, here, tried, purpose=purpose)
    return Separation((a.name, b.name), best[1], declared, best[2], here, tried, best[3], purpose)
