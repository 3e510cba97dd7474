"""Simulate an experiment: drive the model with the experiment's time and elongation and
predict force, pressure and temperature.

:func:`simulate` (``pamkit.simulate``) returns a pandas DataFrame, one row per sample (or per
table row), SI, units in the column names:

    time_s [s], elongation_m [m], force_N [N], gauge_pressure_Pa [Pa], temperature_K [K]
    (a static table: its own columns, e.g. length_m, gauge_pressure_Pa, force_N)

with ``df.attrs``: "experiment" (the TOML's path), "data" (its CSV's path), "kind", "gas",
"effects" (each effect's repr), "solver_statistics" (CVODES counters of a sealed time series and
the method that ran, as a dict; None where no ODE is integrated) and "units" (column -> unit).

    import pamkit
    df = pamkit.simulate("experiment.toml", effects=["heat_transfer:time_constant_s=2"])
    df.plot(x="time_s", y="force_N")

The functions below it (:func:`simulate_experiment`: numpy columns in a dict; the streamed and
table variants) are what it is built on.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from pamkit._core import (
    BladderLaw,
    BraidGeometry,
    Effect,
    EffectStage,
    ElongationTrajectory,
    GasMode,
    InitialState,
    Measurement,
    MuscleParams,
    Simulator,
    SimulatorConfig,
    SolverStatistics,
    free_inflation,
    inflated_and_sealed,
    isotonic_lengths,
    isotonic_motion,
    simulate_measurement,
    simulate_measurement_blocks,
    simulate_supplied_measurement,
    static_forces,
)
from pamkit.effects import parse_effects
from pamkit.io.columns import COLUMN_UNITS, SERIES_COLUMNS
from pamkit.io.experiment import Experiment, load_experiment
from pamkit.io.guards import ExperimentError

if TYPE_CHECKING:
    import pandas as pd


def muscle_params(experiment: Experiment, bladder: BladderLaw | None = None) -> MuscleParams:
    """The model parameters an experiment file describes (its [bladder] law unless given)."""
    return MuscleParams(
        build=experiment.build,
        bladder=bladder if bladder is not None else experiment.bladder,
        friction=experiment.friction,
        gas=experiment.gas_params,
    )


def initial_length(experiment: Experiment, params: MuscleParams) -> float:
    """Length at zero elongation: as given ([test] initial_length_m), else the free inflated length
    (sealed test) or the deflated length (supplied test); a supplied test mounted with a preload
    starts where the deflated muscle carries it.

    Raises:
        ExperimentError: when the build cannot carry the preload deflated (no membrane stiffness).
    """
    if experiment.initial_length_m is not None:
        return experiment.initial_length_m
    if experiment.preload_N is not None:
        mounted = isotonic_lengths(params, np.zeros(1), experiment.preload_N, params.build.length_m)
        if mounted.at_limit[0]:
            raise ExperimentError(
                f"{experiment.path}: [test] preload_N = {experiment.preload_N:g} N: the deflated muscle does not "
                "carry it within the braid's range (a membrane law with stiffness, or initial_length_m, sets it)"
            )
        return mounted.length_m[0]
    if experiment.gas == GasMode.supplied:
        return experiment.build.length_m
    return sealed_start(experiment, params).length_m


def sealed_start(
    experiment: Experiment,
    params: MuscleParams,
    gauge_pressure_Pa: float | None = None,
    effects: Sequence[Effect] = (),
) -> InitialState:
    """A sealed test's state at zero elongation: its gas at `gauge_pressure_Pa` (the file's
    inflation pressure unless given, as a calibration moves it), at the file's initial length if
    it gives one, else inflated freely to that pressure and sealed at the length it takes
    (inflated_and_sealed, as the thesis's protocol does). What inflates is the muscle with its
    `effects`: compliant fibres stretch under the inflation and seal it longer. The one place a
    sealed test's start is made: a simulation, a diagnosis, a synthetic dataset and a sweep all
    start here."""
    if gauge_pressure_Pa is None:
        gauge_pressure_Pa = experiment.inflation_gauge_pressure_Pa
    if experiment.initial_length_m is not None:
        return InitialState(length_m=experiment.initial_length_m, gauge_pressure_Pa=gauge_pressure_Pa)
    return inflated_and_sealed(with_effects(params, effects), gauge_pressure_Pa)


def with_effects(params: MuscleParams, effects: Sequence[Effect]) -> MuscleParams:
    """`params` with each effect's own fields set (Effect.apply_to_params): the muscle the effects
    make, as a run builds it."""
    for effect in effects:
        params = effect.apply_to_params(params)
    return params


def simulate_experiment(
    experiment: Experiment,
    params: MuscleParams | None = None,
    config: SimulatorConfig | None = None,
    effects: Sequence[Effect] = (),
    initial: InitialState | None = None,
) -> dict[str, np.ndarray]:
    """Predicts the experiment's channels at its sample times, with `effects` applied.

    Returns the columns time_s, elongation_m, force_N, gauge_pressure_Pa, temperature_K. In
    a sealed test the gas is a closed mass integrated by CVODES, from `initial` if given (a
    calibrated state: read_muscle_params_file's [initial]), else from the file's inflation; in a
    supplied test the measured pressure drives the model and the gas stays at ambient temperature.

    Raises:
        ExperimentError: for an effect that cannot act in this kind of test, or data the model
            cannot follow (naming the file and sample).
    """
    params = params if params is not None else muscle_params(experiment)
    if experiment.is_table:
        return simulate_table(experiment, params, effects)
    return _channels(experiment, _measurement(experiment, params, config, effects, initial))


def _channels(experiment: Experiment, measurement: Measurement) -> dict[str, np.ndarray]:
    """The channels as the experiment's instruments read them (clipped to their ranges)."""
    return {name: experiment.read(name, np.asarray(getattr(measurement, name))) for name in SERIES_COLUMNS}


def _measurement(
    experiment: Experiment,
    params: MuscleParams,
    config: SimulatorConfig | None,
    effects: Sequence[Effect],
    initial: InitialState | None = None,
) -> Measurement:
    """The simulated time series of an experiment (with the solver's statistics); a sealed test
    starts from `initial` when given."""
    mode = _checked_mode(experiment, effects)
    if mode == GasMode.supplied:
        length0 = initial_length(experiment, params)
    elif initial is None:
        initial = sealed_start(experiment, params, effects=effects)
    crosshead = ElongationTrajectory(experiment.time_s, experiment.elongation_m)
    try:
        if mode == GasMode.supplied:
            measurement = simulate_supplied_measurement(
                params, length0, crosshead, experiment.columns["gauge_pressure_Pa"], list(effects)
            )
        else:
            simulator = Simulator(config if config is not None else SimulatorConfig())
            measurement = simulate_measurement(params, initial, crosshead, list(effects), simulator)
    except ValueError as error:
        raise ExperimentError(f"{experiment.data_path}: {error}") from None
    return measurement


def _checked_mode(experiment: Experiment, effects: Sequence[Effect]) -> GasMode:
    """The test's gas mode, once every effect can act in it."""
    for effect in effects:
        acts, why_not = effect.acts_in(experiment.gas)
        if not acts:
            raise ExperimentError(f"{experiment.path}: effect {effect.name()} cannot act here: {why_not}")
    return experiment.gas


#: Samples simulated (and handed on) at a time when a simulation streams its output.
STREAM_BLOCK_ROWS = 1 << 16


def why_not_streamed(experiment: Experiment, effects: Sequence[Effect] = ()) -> str | None:
    """Why :func:`simulate_streamed` cannot predict the experiment (None: it can). It streams a
    sealed time series: a static table is one solve a row, and a supplied test's pressure
    branches and transducer effects read the whole record. An effect on the measured channels
    (a sensor's lag, a clock's skew) reads the whole series too, a filter's past or a later
    sample."""
    if experiment.is_table:
        return f"a {experiment.kind} table is predicted row by row, not integrated in time"
    if experiment.gas != GasMode.sealed:
        return "a supplied test's pressure branches and transducer read the whole record"
    whole = [effect.name() for effect in effects if effect.stage() == EffectStage.measurement]
    if whole:
        return f"{', '.join(whole)} act(s) on the whole measured series"
    return None


def simulate_streamed(
    experiment: Experiment,
    sink: Callable[[dict[str, np.ndarray]], None],
    params: MuscleParams | None = None,
    config: SimulatorConfig | None = None,
    effects: Sequence[Effect] = (),
    initial: InitialState | None = None,
    block_rows: int = STREAM_BLOCK_ROWS,
) -> SolverStatistics:
    """Predicts a sealed time series as :func:`simulate_experiment` does, handing its channels to
    `sink` as they are integrated, `block_rows` samples at a time: the prediction never stands in
    memory whole (the C++ simulator hands each block over as it fills, as SUNDIALS's and
    Drake's hand output to a monitor), so a test of 10^7 samples needs memory for its input
    only. Each block is a dict of 1-D arrays, SERIES_COLUMNS in order (time_s [s],
    elongation_m [m], force_N [N], gauge_pressure_Pa [Pa], temperature_K [K]), as the
    instruments read them; the blocks joined equal simulate_experiment's columns bit for bit.

    Returns:
        The CVODES counters of the run.

    Raises:
        ExperimentError: for what simulate_experiment refuses, and for an experiment
            :func:`why_not_streamed` names a reason for (simulate it whole).
    """
    params = params if params is not None else muscle_params(experiment)
    why_not = why_not_streamed(experiment, effects)
    if why_not is not None:
        raise ExperimentError(f"{experiment.path}: cannot stream the simulation: {why_not}; simulate it whole")
    _checked_mode(experiment, effects)
    initial = initial if initial is not None else sealed_start(experiment, params, effects=effects)
    crosshead = ElongationTrajectory(experiment.time_s, experiment.elongation_m)
    simulator = Simulator(config if config is not None else SimulatorConfig())

    def read(first: int, channels: dict[str, np.ndarray]) -> None:
        sink({name: experiment.read(name, channels[name]) for name in SERIES_COLUMNS})

    try:
        return simulate_measurement_blocks(params, initial, crosshead, list(effects), simulator, block_rows, read)
    except ExperimentError:
        raise
    except ValueError as error:
        raise ExperimentError(f"{experiment.data_path}: {error}") from None


def simulate_table(
    experiment: Experiment,
    params: MuscleParams | None = None,
    effects: Sequence[Effect] = (),
    rows: np.ndarray | None = None,
    load_N: float | None = None,
) -> dict[str, np.ndarray]:
    """Predicts a static table row by row (all rows, or `rows`): an isometric map's force at its
    held length and supplied pressure, a free-inflation table's free length and diameter at its
    pressure, an isotonic test's length under its load (`load_N`, by default the file's) along
    the quasi-static path of every row from the deflated length, or, with `[test] load_mass_kg`,
    along the load's motion integrated in time (isotonic_motion). Returns the table's columns
    with the measured ones replaced by the prediction.

    Raises:
        ExperimentError: for an effect that cannot act on a static table, or a row the model
            cannot reach (naming the file and row).
    """
    params = params if params is not None else muscle_params(experiment)
    rows = np.arange(len(experiment.columns["gauge_pressure_Pa"])) if rows is None else rows
    pressure = experiment.columns["gauge_pressure_Pa"][rows]
    try:
        if experiment.kind == "isometric_map":
            # Each held length is its own record: all its rows, in the order measured, give the
            # pressurise/vent branch and the friction's memory (a map laid out length by length
            # starts each one low), whichever of them are asked for.
            every = np.round(experiment.columns["length_m"], 9)
            length = experiment.columns["length_m"][rows]
            force = np.empty(len(rows))
            for held in np.unique(every[rows]):
                record = np.flatnonzero(every == held)
                on_record = np.full(len(every), -1)
                on_record[record] = np.arange(len(record))
                at = np.flatnonzero(every[rows] == held)
                path = static_forces(
                    params,
                    experiment.columns["length_m"][record],
                    experiment.columns["gauge_pressure_Pa"][record],
                    list(effects),
                )
                force[at] = np.asarray(path)[on_record[rows[at]]]
            return {"length_m": length, "gauge_pressure_Pa": pressure, "force_N": experiment.read("force_N", force)}
        if experiment.kind == "isotonic":
            load = experiment.load_N if load_N is None else load_N
            if load is None:
                raise ExperimentError(
                    f"{experiment.path}: [test] load_N is unknown (in [calibrate]); a prediction needs a load: "
                    "give [test] load_N, or run `pamkit diagnose` to calibrate it"
                )
            if experiment.load_mass_kg is not None:  # the load's motion, integrated in time
                path = isotonic_motion(
                    params,
                    experiment.columns["time_s"],
                    experiment.columns["gauge_pressure_Pa"],
                    load,
                    experiment.load_mass_kg,
                    None,
                    list(effects),
                )
            else:
                path = isotonic_lengths(
                    params, experiment.columns["gauge_pressure_Pa"], load, params.build.length_m, list(effects)
                )
            return {"gauge_pressure_Pa": pressure, "length_m": np.asarray(path.length_m)[rows]}
        if effects:
            raise ExperimentError(f"{experiment.path}: a free-inflation table is predicted without effects")
        geometry = BraidGeometry(params.build)
        atmosphere = params.gas.atmospheric_pressure_Pa
        states = [free_inflation(geometry, params.bladder, atmosphere, p) for p in pressure]
    except ExperimentError:
        raise
    except ValueError as error:
        raise ExperimentError(f"{experiment.data_path}: {error}") from None
    return {
        "gauge_pressure_Pa": pressure,
        "length_m": np.array([s.length_m for s in states]),
        "diameter_m": np.array([s.diameter_m for s in states]),
    }


STATISTICS_FIELDS = (
    "steps",
    "rhs_evaluations",
    "output_evaluations",
    "jacobian_evaluations",
    "linear_solver_setups",
    "error_test_failures",
    "nonlinear_iterations",
    "nonlinear_convergence_failures",
    "restarts",
)


def simulate(
    experiment_or_path: Experiment | str | Path,
    effects: Sequence[Effect | str] = (),
    params: MuscleParams | None = None,
    config: SimulatorConfig | None = None,
) -> pd.DataFrame:
    """Predict an experiment as a pandas DataFrame.

    Parameters
    ----------
    experiment_or_path : Experiment or str or Path
        The experiment (:func:`pamkit.load_experiment`, :meth:`pamkit.Experiment.from_frame`), or
        the path of its TOML file.
    effects : sequence of Effect or str, optional
        Catalog effects to extend the model with, as :class:`pamkit.Effect` objects or specs like
        ``"heat_transfer:time_constant_s=2"`` (``pamkit effects`` lists them).
    params : MuscleParams, optional
        The model's parameters (default: the experiment file's; a calibrated muscle from
        :func:`pamkit.read_muscle_params`).
    config : SimulatorConfig, optional
        Integrator settings for a sealed time series (default: ``SimulatorConfig()``).

    Returns
    -------
    pandas.DataFrame
        N rows: the N samples of the experiment's data, or its N table rows, SI. A time series has
        the columns time_s [s], elongation_m [m], force_N [N], gauge_pressure_Pa [Pa] and
        temperature_K [K]; a static table its own (length_m [m], gauge_pressure_Pa, force_N,
        diameter_m). ``df.attrs`` holds "experiment", "data" (paths, str), "kind", "gas" (its
        name), "effects" (list of str), "units" (column -> unit) and "solver_statistics" (a dict of
        the integrator's counters and the method that ran, "bdf", "adams", "dopri5" or
        "rosenbrock4", for a sealed time series; None where no ODE is integrated).

    Raises
    ------
    ExperimentError
        (a ValueError) for a file that cannot be read, an effect that cannot act in this test,
        or data the model cannot follow, naming the file.

    Examples
    --------
    >>> df = pamkit.simulate("data/experiments/thesis/pam2_207kPa_90pct.toml")  # doctest: +SKIP
    >>> df.plot(x="time_s", y="force_N")  # doctest: +SKIP
    """
    import pandas as pd  # imported when used: it takes a second, and `import pamkit` should not

    experiment = (
        experiment_or_path if isinstance(experiment_or_path, Experiment) else load_experiment(experiment_or_path)
    )
    if isinstance(effects, (str, Effect)):
        effects = [effects]
    specs = [effect for effect in effects if isinstance(effect, str)]
    if specs:
        try:
            parsed = iter(parse_effects(specs))
        except ValueError as error:
            raise ExperimentError(f"{experiment.path}: {error}") from None
        effects = [next(parsed) if isinstance(effect, str) else effect for effect in effects]
    params = params if params is not None else muscle_params(experiment)
    statistics = None
    if experiment.is_table:
        columns = simulate_table(experiment, params, effects)
    else:
        measurement = _measurement(experiment, params, config, effects)
        columns = _channels(experiment, measurement)
        if experiment.gas == GasMode.sealed:
            statistics = {name: int(getattr(measurement.statistics, name)) for name in STATISTICS_FIELDS}
            statistics["method"] = measurement.statistics.method.name  # the method that ran: "bdf", "dopri5", ...
    frame = pd.DataFrame(columns)
    frame.attrs.update(
        experiment=str(experiment.path),
        data=str(experiment.data_path),
        kind=experiment.kind,
        gas=experiment.gas.name,
        effects=[repr(effect) for effect in effects],
        units={name: COLUMN_UNITS[name] for name in frame.columns},
        solver_statistics=statistics,
    )
    return frame
