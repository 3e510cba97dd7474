"""The calibrated baseline and the candidate extensions, as functions from a parameter vector
to predicted channels.

Baseline parameters (the model's own uncertainty, not a cause):
  - the inflation pressure, within the transducer's tolerance (sealed tests only);
  - a scale on both friction coefficients (eqs. 3.1.19-3.1.24 are the least certain part);
  - a scale on the bladder stress law (eqs. 3.1.12-13 were fitted to one rubber sample);
  - the build fields `[uncertain]` declares, each within its tolerance (by default the braid's wind
    within what counting it by hand allows), unless `[calibrate]` declares them unknown: no build is
    exactly as its file declares it, and a cause is judged against the build as it may be.
An effect adds its own physical parameters; every coordinate's bounds, start and plausible range
come from diagnosis/coordinates.py, shared with the static tables.
"""

from __future__ import annotations

import threading
from dataclasses import dataclass, field

import numpy as np

from pamkit._core import (
    BladderLaw,
    Effect,
    EffectStage,
    ElongationTrajectory,
    GasMode,
    InitialState,
    Measurement,
    MuscleModel,
    MuscleParams,
    ShapeTable,
    Simulator,
    SimulatorConfig,
    simulate_measurement,
    simulate_supplied_measurement,
)
from pamkit.diagnosis.coordinates import (
    Coordinate,
    linear_coordinate,
    uncertain_coordinate,
    uncertain_fields,
    unknown_coordinate,
    with_unknowns,
)
from pamkit.diagnosis.series.motion import measured_motion, programmed_motion, with_knots_after_turns
from pamkit.io.columns import SERIES_COLUMNS
from pamkit.io.experiment import Experiment
from pamkit.simulation import initial_length, muscle_params, sealed_start, with_effects

# A fixture's play is taken up within the first PLAY_REFINED_M of travel after each turn (the
# largest plausible play, fixture_slack's): runs with it follow the crosshead there on knots
# PLAY_SUBDIVISIONS times finer than the samples, so that a play shorter than one sample's
# travel moves the muscle as it does, still and then at the crosshead's rate.
PLAY_REFINED_M = 5e-3
PLAY_SUBDIVISIONS = 8
PRESSURE_TOLERANCE = 0.05  # relative: a hand-calibrated transducer read at inflation


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
                linear_coordinate(
                    "inflation_gauge_pressure_Pa",
                    p0 * (1 - PRESSURE_TOLERANCE),
                    p0 * (1 + PRESSURE_TOLERANCE),
                    p0,
                    (p0 * (1 - PRESSURE_TOLERANCE), p0 * (1 + PRESSURE_TOLERANCE)),
                    "the declared inflation pressure within the hand-read transducer's 5 %",
                )
            )
        space.append(
            linear_coordinate(
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
                linear_coordinate(
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
        # A sealed run whose muscle moves off the crosshead (a fixture's play) follows it on finer
        # knots after each turn, read back on the motion's own (played_measurement); a supplied
        # test is evaluated at its samples alone.
        self.played_motion, self._motion_rows = (
            with_knots_after_turns(self.motion, PLAY_REFINED_M, PLAY_SUBDIVISIONS)
            if self.mode == GasMode.sealed
            else (self.motion, np.arange(self.motion.time_s.size))
        )
        self.played_trajectory = ElongationTrajectory(self.played_motion.time_s, self.played_motion.elongation_m)
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
        it into a new measurement: the same numbers as a run with them, one simulation fewer."""
        if not effects or not all(self.reads_the_model(e) for e in effects):
            return self.simulate(x, effects)
        key = np.asarray(x, dtype=float).tobytes()
        last = getattr(self._last_run, "value", None)
        if last is None or last[0] != key:
            last = (key, self.simulate(x, []))
            self._last_run.value = last
        m = last[1]
        for effect in effects:
            m = effect.apply_to_measurement(m)  # a new measurement: the run kept stays as it was
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
        extended = with_effects(params, effects)
        initial = self.initial_state(extended, pressure_Pa)
        # A motion effect moves the muscle off the programmed lengths: no table applies.
        if self.moves_muscle(effects):
            run = simulate_measurement(params, initial, self.played_trajectory, effects, self.simulator)
            return self.played_measurement(run)
        shapes = self.shape_table(extended, initial)
        return simulate_measurement(params, initial, self.trajectory, effects, self.simulator, shapes=shapes)

    @staticmethod
    def moves_muscle(effects: list[Effect]) -> bool:
        """Whether an effect moves the muscle off the crosshead's motion (a fixture's play)."""
        return any(e.stage() == EffectStage.motion for e in effects)

    def played_measurement(self, m: Measurement) -> Measurement:
        """A run along played_trajectory read at the motion's own knots."""
        out = Measurement()
        for name in SERIES_COLUMNS:
            setattr(out, name, np.asarray(getattr(m, name))[self._motion_rows])
        return out

    def sealed_model(self, x: np.ndarray, effects: list[Effect]) -> MuscleModel:
        """The sealed test's model at baseline coordinates x, extended by `effects`' parameters."""
        params, pressure_Pa = self.baseline.model_params(x)
        extended = with_effects(params, effects)
        return MuscleModel(extended, self.initial_state(extended, pressure_Pa))

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
        """This test's sealed start (simulate.sealed_start) at inflation gauge pressure [Pa] of the
        muscle `params` (with its effects' fields: with_effects)."""
        return sealed_start(self.experiment, params, gauge_pressure_Pa)

    def select(self, m: Measurement) -> dict[str, np.ndarray]:
        """The measured channels of a simulated measurement, at the data's samples."""
        return {
            name: self.experiment.read(name, np.asarray(getattr(m, name))[self.motion.sample_rows])
            for name in self.channels
        }

    def run_rows(self, mask: np.ndarray, effects: list[Effect]) -> np.ndarray:
        """The samples of a run with `effects` that `select` reads for the data's rows `mask`: on
        the motion's knots, or on the played motion's where an effect moves the muscle."""
        rows = self.motion.sample_rows[mask]
        return self._motion_rows[rows] if self.moves_muscle(effects) else rows

    def predict(self, x: np.ndarray, effects: list[Effect]) -> dict[str, np.ndarray]:
        return self.select(self.measurement(x, effects))
