"""The calibrated baseline and the candidate extensions, as functions from a parameter vector
to predicted channels.

Baseline parameters (the model's own uncertainty, not a cause):
  - the inflation pressure, within the transducer's tolerance (sealed tests only);
  - a scale on both friction coefficients (eqs. 3.1.19-3.1.24 are the least certain part);
  - a scale on the bladder stress law (eqs. 3.1.12-13 were fitted to one rubber sample);
  - the build fields `[uncertain]` declares, each within its tolerance (by default the braid's wind
    within what counting it by hand allows), unless `[calibrate]` declares them unknown: no build is
    exactly as its file declares it, and a cause is judged against the build as it may be.
An effect adds its own physical parameters, fitted in a space where they move smoothly
(log for time constants, rates for "infinite means off" constants).
"""

from __future__ import annotations

import functools
import math
import threading
from dataclasses import dataclass, field

import numpy as np

from pamkit._core import (
    BladderLaw,
    Effect,
    EffectParameter,
    EffectStage,
    ElongationTrajectory,
    FitScale,
    GasMode,
    InitialState,
    Measurement,
    MuscleModel,
    MuscleParams,
    ShapeTable,
    Simulator,
    SimulatorConfig,
    fiber_revolutions_for_braid_angle,
    simulate_measurement,
    simulate_supplied_measurement,
)
from pamkit.diagnosis.series.motion import measured_motion, programmed_motion
from pamkit.io.columns import SERIES_COLUMNS
from pamkit.io.experiment import Experiment
from pamkit.io.sections import BRAID_ANGLE_KEY, declared_value
from pamkit.simulation import initial_length, muscle_params, sealed_start

PRESSURE_TOLERANCE = 0.05  # relative: a hand-calibrated transducer read at inflation
# [calibrate] unknowns whose declared range spans more than this ratio are searched on a log scale.
LOG_SPAN = 20.0


def _identity(x: float) -> float:
    return x


def _reciprocal(x: float) -> float:
    return 1.0 / x if x > 0 else math.inf if x == 0 else -math.inf


# A fitted coordinate within this share of its interval's width from an end is "at a bound".
AT_BOUND = 1e-3


@dataclass(frozen=True)
class Coordinate:
    """One fitted coordinate: its bounds and start, how it maps to a parameter's value, and the
    parameter's physically plausible range (in value units) with its source."""

    name: str
    lower: float
    upper: float
    start: float
    to_value: callable = _identity
    from_value: callable = _identity
    plausible: tuple[float, float] = (-math.inf, math.inf)
    source: str = ""

    def value(self, x: float) -> float:
        return self.to_value(x)

    def of(self, value: float) -> float:
        return self.from_value(value)

    def at_bound(self, x: float) -> str | None:
        """ "lower" or "upper" when x ended at an end of the search interval, else None."""
        margin = AT_BOUND * (self.upper - self.lower)
        if x <= self.lower + margin:
            return "lower"
        if x >= self.upper - margin:
            return "upper"
        return None

    def bound_value(self, side: str) -> float:
        return float(self.value(self.lower if side == "lower" else self.upper))

    def implausible(self, value: float) -> bool:
        return not (self.plausible[0] <= value <= self.plausible[1])


def _log(name, lower, upper, start, plausible=(-math.inf, math.inf), source=""):
    return Coordinate(name, math.log(lower), math.log(upper), math.log(start), math.exp, math.log, plausible, source)


def _linear(name, lower, upper, start, plausible=(-math.inf, math.inf), source=""):
    return Coordinate(name, lower, upper, start, plausible=plausible, source=source)


def _rate(name, largest_rate, start_value, plausible=(-math.inf, math.inf), source=""):
    """Fits 1/value in [0, largest_rate]: 0 is 'infinite', the effect switched off."""
    return Coordinate(name, 0.0, largest_rate, 1.0 / start_value, _reciprocal, _reciprocal, plausible, source)


def parameter_coordinate(p: EffectParameter) -> Coordinate:
    """The fit coordinate of an effect parameter, from what the effect declares (its search
    scale, interval and start, its plausible range: catalog.hpp, or a Python effect's
    EffectParameter)."""
    plausible = (p.plausible_min, p.plausible_max)
    if p.fit_scale == FitScale.log:
        return _log(p.name, p.fit_min, p.fit_max, p.fit_start, plausible, p.plausible_source)
    if p.fit_scale == FitScale.reciprocal:
        return _rate(p.name, 1.0 / p.fit_min, p.fit_start, plausible, p.plausible_source)
    return _linear(p.name, p.fit_min, p.fit_max, p.fit_start, plausible, p.plausible_source)


def effect_space(effect: Effect) -> list[Coordinate]:
    """The fit coordinates of an effect, one per numeric parameter it lets a diagnosis search
    (a parameter whose search interval is one point is held at it)."""
    return [parameter_coordinate(p) for p in effect.parameters() if p.fit_min != p.fit_max]


def unknown_coordinate(name: str, bounds: tuple[float, float], experiment: Experiment) -> Coordinate:
    """The fit coordinate of a `[calibrate]` field (an unknown of the build): its declared
    bounds are both its search interval and its plausible range; it starts at the declared value
    when that lies inside, else mid-interval. `name` may carry a test's suffix (`load_N[a]`)."""
    lower, upper = bounds
    declared = declared_value(name.split("[", 1)[0], experiment.build, experiment.bladder, experiment.load_N)
    start = declared if lower < declared < upper else 0.5 * (lower + upper)
    source = "the [calibrate] bounds the experiment file declares"
    if lower > 0 and upper / lower > LOG_SPAN:
        return _log(name, lower, upper, start, (lower, upper), source)
    return _linear(name, lower, upper, start, (lower, upper), source)


@functools.cache
def _build_fields(build_type: type) -> frozenset[str]:
    return frozenset(build_type.fields())


def with_unknowns(params: MuscleParams, values: dict[str, float]) -> MuscleParams:
    """`params` with the `[calibrate]` build and bladder fields in `values` set (other names,
    such as the baseline's scales, are left to the caller)."""
    build = params.build
    fields = _build_fields(type(build))
    for name, value in values.items():
        if name in fields:
            setattr(build, name, value)
    if BRAID_ANGLE_KEY in values:
        build.fiber_revolutions = fiber_revolutions_for_braid_angle(build, values[BRAID_ANGLE_KEY])
    params.build = build
    if "bladder.shear_modulus_Pa" in values:
        params.bladder = BladderLaw.neo_hookean(values["bladder.shear_modulus_Pa"])
    return params


def configure(effect: Effect, space: list[Coordinate], x: np.ndarray) -> Effect:
    for coordinate, value in zip(space, x):
        effect.set(coordinate.name, float(coordinate.value(value)))
    return effect


@dataclass
class Baseline:
    """Maps baseline coordinates to model inputs: the inflation pressure (sealed tests), the
    friction and bladder scales, the build fields `[uncertain]` declares, each within its tolerance,
    and the fields `[calibrate]` declares unknown. Names in `fixed` are
    held at the given values instead of fitted (a campaign's jointly calibrated muscle)."""

    experiment: Experiment
    fixed: dict[str, float] = field(default_factory=dict)
    params: MuscleParams = field(init=False)
    space: list[Coordinate] = field(init=False)

    def __post_init__(self):
        self.params = muscle_params(self.experiment)
        self.space = [c for c in self.coordinates(self.experiment) if c.name not in self.fixed]

    @staticmethod
    def coordinates(experiment: Experiment) -> list[Coordinate]:
        """Every coordinate a test's baseline may calibrate."""
        p0 = experiment.inflation_gauge_pressure_Pa
        space = []
        if experiment.gas == GasMode.sealed:
            space.append(
                _linear(
                    "inflation_gauge_pressure_Pa",
                    p0 * (1 - PRESSURE_TOLERANCE),
                    p0 * (1 + PRESSURE_TOLERANCE),
                    p0,
                    (p0 * (1 - PRESSURE_TOLERANCE), p0 * (1 + PRESSURE_TOLERANCE)),
                    "the declared inflation pressure within the hand-read transducer's 5 %",
                )
            )
        space.append(
            _linear(
                "friction_scale",
                0.0,
                20.0,
                1.0,
                (0.1, 10.0),
                "eqs. 3.1.19-24 with the thesis's coefficients; a tenfold error either way is another "
                "friction mechanism, not a coefficient",
            )
        )
        if "bladder.shear_modulus_Pa" not in experiment.calibrate:  # the modulus is the scale then
            space.append(
                _linear(
                    "bladder_scale",
                    0.0,
                    5.0,
                    1.0,
                    (0.33, 3.0),
                    "eqs. 3.1.12-13 fitted to one butyl sample; rubbers of one nominal grade differ in modulus "
                    "by well under 3x",
                )
            )
        space += [uncertain_coordinate(name, experiment) for name in uncertain_fields(experiment)]
        space += [unknown_coordinate(name, bounds, experiment) for name, bounds in experiment.calibrate.items()]
        return space

    def values(self, x: np.ndarray) -> dict[str, float]:
        """Every baseline value: the fitted coordinates' and the fixed ones."""
        return self.fixed | {c.name: float(c.value(v)) for c, v in zip(self.space, x)}

    def model_params(self, x: np.ndarray) -> tuple[MuscleParams, float]:
        """Model parameters and inflation gauge pressure [Pa] at baseline coordinates x."""
        values = self.values(x)
        params = with_unknowns(muscle_params(self.experiment), values)
        friction = params.friction
        friction.fiber_fiber_coefficient *= values["friction_scale"]
        friction.fiber_bladder_coefficient *= values["friction_scale"]
        params.friction = friction
        params.bladder = scaled_law(params.bladder, values.get("bladder_scale", 1.0))
        return params, values.get("inflation_gauge_pressure_Pa", self.experiment.inflation_gauge_pressure_Pa)


def uncertain_fields(experiment: Experiment) -> list[str]:
    """The build fields `[uncertain]` declares that `[calibrate]` does not already fit (the wind
    and the braid angle are one number)."""
    known = set(experiment.calibrate)
    if {"fiber_revolutions", BRAID_ANGLE_KEY} & known:
        known |= {"fiber_revolutions", BRAID_ANGLE_KEY}
    return [name for name in experiment.uncertain if name not in known]


def uncertain_coordinate(name: str, experiment: Experiment) -> Coordinate:
    """A build field free within its `[uncertain]` tolerance of its declared value: its search
    interval is its plausible range, so that ending at an end is the base model straining."""
    declared = declared_value(name, experiment.build, experiment.bladder)
    tolerance = experiment.uncertain[name]
    bounds = (declared - tolerance, declared + tolerance)
    return _linear(name, *bounds, declared, bounds, f"[uncertain] {name} = {tolerance:g}: the build as it may be")


def muscle_signature(params: MuscleParams) -> tuple:
    """Every number of a MuscleParams that belongs to the muscle, to tell two muscles apart (the
    room's temperature belongs to the test)."""
    law = params.bladder
    gas = {k: v for k, v in params.gas.to_dict().items() if k != "ambient_temperature_K"}
    return (
        *(part.to_dict() for part in (params.build, params.friction, params.extensions)),
        params.build.construction,
        gas,
        params.gas.process,
        law.form,
        *law.longitudinal_Pa,
        *law.hoop_Pa,
        law.shear_modulus_Pa,
    )


def scaled_law(law: BladderLaw, scale: float) -> BladderLaw:
    """The membrane law with every stress multiplied by `scale` (a stiffer or softer bladder)."""
    if law.form == BladderLaw.Form.neo_hookean:
        return BladderLaw.neo_hookean(scale * law.shear_modulus_Pa)
    scaled = BladderLaw()
    scaled.longitudinal_Pa = [scale * c for c in law.longitudinal_Pa]
    scaled.hoop_Pa = [scale * c for c in law.hoop_Pa]
    return scaled


class Predictor:
    """Predicted channels for baseline coordinates and a list of effects; thread-safe."""

    def __init__(
        self,
        experiment: Experiment,
        channels: list[str],
        config: SimulatorConfig | None = None,
    ):
        self.experiment = experiment
        self.channels = channels
        self.baseline = Baseline(experiment)
        self.mode = experiment.gas
        self.motion = (
            programmed_motion(experiment.time_s, experiment.elongation_m)
            if self.mode == GasMode.sealed
            else measured_motion(experiment.time_s, experiment.elongation_m)
        )
        self.trajectory = ElongationTrajectory(self.motion.time_s, self.motion.elongation_m)
        self.simulator = Simulator(
            config if config is not None else SimulatorConfig(relative_tolerance=1e-6, absolute_tolerance_K=1e-6)
        )
        self._last_run = threading.local()  # (x's bytes, the model's measurement there), per thread
        # The braid's shapes along the motion, by build and initial length, the most recent last:
        # shared by the runs of a Jacobian that leave both alone (friction, bladder law, effects).
        self._shape_tables: dict[tuple, ShapeTable] = {}
        self._shape_tables_kept = 8  # about 2 MB each for a record of 15000 samples
        self._shape_tables_lock = threading.Lock()

    def measurement(self, x: np.ndarray, effects: list[Effect]) -> Measurement:
        """The simulated measurement at baseline coordinates x with `effects`. With instrument
        effects only, the model's run at x is the last one this thread made whenever x is the
        same (a finite-difference column of an instrument's parameter), and the instruments read
        a copy of it: the same numbers as a run with them, one simulation fewer."""
        if not effects or not all(self.reads_the_model(e) for e in effects):
            return self.simulate(x, effects)
        key = np.asarray(x, dtype=float).tobytes()
        last = getattr(self._last_run, "value", None)
        if last is None or last[0] != key:
            last = (key, self.simulate(x, []))
            self._last_run.value = last
        m = Measurement()
        for name in SERIES_COLUMNS:
            setattr(m, name, getattr(last[1], name))
        for effect in effects:
            m = effect.apply_to_measurement(m)
        return m

    def reads_the_model(self, effect: Effect) -> bool:
        """Whether `effect` only reads the model's channels (an instrument), leaving the run
        itself alone; a transducer whose reading drives a supplied test does not."""
        if effect.stage() != EffectStage.measurement:
            return False
        return not (self.mode == GasMode.supplied and effect.reads_supplied_pressure())

    def simulate(self, x: np.ndarray, effects: list[Effect]) -> Measurement:
        """One run of the model with `effects` at baseline coordinates x. A sealed run whose
        effects leave the muscle's motion and fibres alone reads the braid's shapes from a table
        solved once per build and initial length (the same numbers, bit for bit, as solving them)."""
        params, pressure_Pa = self.baseline.model_params(x)
        if self.mode == GasMode.supplied:
            # The measured motion (not the programmed one): samples and pressures line up.
            return simulate_supplied_measurement(
                params,
                initial_length(self.experiment, params),
                self.trajectory,
                self.experiment.columns["gauge_pressure_Pa"],
                effects,
            )
        initial = self.initial_state(params, pressure_Pa)
        extended = params
        for effect in effects:
            extended = effect.apply_to_params(extended)
        shapes = None
        # A motion effect moves the muscle off the programmed lengths: no table applies.
        if all(e.stage() != EffectStage.motion for e in effects):
            shapes = self.shape_table(extended, initial)
        return simulate_measurement(params, initial, self.trajectory, effects, self.simulator, shapes=shapes)

    def sealed_model(self, x: np.ndarray, effects: list[Effect]) -> MuscleModel:
        """The sealed test's model at baseline coordinates x, extended by `effects`' parameters."""
        params, pressure_Pa = self.baseline.model_params(x)
        initial = self.initial_state(params, pressure_Pa)
        for effect in effects:
            params = effect.apply_to_params(params)
        return MuscleModel(params, initial)

    def shape_table(self, extended: MuscleParams, initial: InitialState) -> ShapeTable | None:
        """The braid's shapes along the programmed motion for `extended`'s build from `initial`'s
        length, solved once and kept (the most recent 8); None for compliant fibres, whose braid's
        length depends on the force (a run would ignore a table)."""
        if extended.extensions.fiber_compliance_per_N != 0:
            return None
        key = (*extended.build.to_dict().values(), initial.length_m)
        with self._shape_tables_lock:
            shapes = self._shape_tables.pop(key, None)
            if shapes is not None:
                self._shape_tables[key] = shapes  # now the most recent
        if shapes is None:
            shapes = ShapeTable(extended.build, initial.length_m, self.trajectory)  # releases the GIL
            with self._shape_tables_lock:
                self._shape_tables[key] = shapes
                while len(self._shape_tables) > self._shape_tables_kept:
                    del self._shape_tables[next(iter(self._shape_tables))]
        return shapes

    def initial_state(self, params: MuscleParams, gauge_pressure_Pa: float) -> InitialState:
        """This test's sealed start (simulate.sealed_start) at inflation gauge pressure [Pa]."""
        return sealed_start(self.experiment, params, gauge_pressure_Pa)

    def select(self, m: Measurement) -> dict[str, np.ndarray]:
        """The measured channels of a simulated measurement, at the data's samples."""
        return {
            name: self.experiment.read(name, np.asarray(getattr(m, name))[self.motion.sample_rows])
            for name in self.channels
        }

    def predict(self, x: np.ndarray, effects: list[Effect]) -> dict[str, np.ndarray]:
        return self.select(self.measurement(x, effects))
