"""Design sweeps: one experiment simulated over a grid or a Latin hypercube of its build and test
parameters, one row of summary metrics per run (`pamkit sweep SPEC.toml -o RESULTS.parquet`).

A spec is a TOML file::

    [sweep]
    experiment = "my_test.toml"  # relative to the spec; default: the thesis's PAM 2 at 207 kPa, 80 %
    cycles = 2                   # keep the test's first cycles only (default: all of them)
    design = "grid"              # every combination of the values; or "latin_hypercube"
    samples = 100                # latin_hypercube: how many runs
    seed = 1                     # latin_hypercube: the draw's seed (the same seed, the same runs)

    [parameters]
    inflation_pressure_kPa = { values = [138, 207, 276] }  # grid: listed values
    braid_angle_deg = { linspace = [18, 26, 5] }            # grid: lo, hi, count
    bladder.shear_modulus_Pa = { range = [0.5e6, 2e6] }     # latin_hypercube: lo, hi

A parameter is any name `[calibrate]` accepts (MuscleBuild's fields, braid_angle_deg,
bladder.shear_modulus_Pa: a neo-Hookean bladder of that modulus), a `[test]` condition
(inflation_pressure_kPa, ambient_temperature_C, initial_length_m) or a `friction.` or `gas.`
field, each within the range and in the unit experiment files give it (a spec is written by a
person, as an experiment file is, and read as one: pamkit.io.experiment.test_condition converts
the test's conditions to SI). Every other setting is the base experiment's, as written.

Each run gives the parameters and the metrics of METRICS; a run the model cannot follow (or a
combination the muscle's own checks reject) gives its message in `error` and NaN metrics.

With ``device = "exoskeleton"`` in [sweep] (no experiment, no cycles) the runs are the ankle
device of appendix G.3 on Winter's gait (pamkit.exo.exo_study, without the walking-cadence ODE
run), its parameters the `exo.` names of EXO_PARAMETERS, and its metrics EXO_METRICS: the
device's torque share and the clutch's timing.
"""

from __future__ import annotations

import dataclasses
import functools
import math
from pathlib import Path

import numpy as np
from scipy.integrate import trapezoid

from pamkit._core import (
    BladderLaw,
    ElongationTrajectory,
    Error,
    GasMode,
    InitialState,
    MuscleBuild,
    ParameterSets,
    RunFailure,
    Simulator,
    SimulatorConfig,
    SolverError,
    fiber_revolutions_for_braid_angle,
)
from pamkit.cluster import MAX_CHUNK, check_output, run_all
from pamkit.diagnosis.cycles import cycle_starts
from pamkit.exo import exo_study
from pamkit.io.columns import value_to_si
from pamkit.io.experiment import Experiment, test_condition
from pamkit.io.schema import TEST_CONDITIONS
from pamkit.io.sections import BRAID_ANGLE_KEY
from pamkit.simulation import muscle_params, simulate_experiment
from pamkit.sweep_spec import (
    EXO_METRICS,
    METRICS,
    TEST_PARAMETERS,
    SweepSpec,
    base_experiment,
    load_spec,
    prepare_base,
)

# With the spec's reader and metrics, which the command line, the gallery and the tests read here.
__all__ = [
    "METRICS",
    "SweepSpec",
    "base_experiment",
    "batch_rows",
    "load_spec",
    "parameter_sets",
    "prepare_base",
    "run_chunk",
    "run_in_process",
    "run_one",
    "summarize",
    "sweep",
    "with_parameters",
]

#: Most runs of one batch, in this process or in a Dask task: each keeps its force over the first
#: stretch. A batched run costs a tenth of a millisecond, so a task of MAX_CHUNK runs would be
#: little more than Dask's own cost per task.
LARGEST_BATCH = 4096


def _copy_struct(struct):
    """A bound parameter struct copied field by field (the bindings do not pickle or copy)."""
    copy = type(struct)()
    for name in type(struct).fields():
        setattr(copy, name, getattr(struct, name))
    return copy


def with_parameters(base: Experiment, parameters: dict[str, float]) -> Experiment:
    """The base experiment with `parameters` set; the base is left as it was.

    Raises:
        ValueError: for a combination the muscle's own checks reject (a bladder wider than its
            braid, a braid angle the build cannot reach).
    """
    build: MuscleBuild = _copy_struct(base.build)
    build.construction = base.build.construction  # an enum, not a field of numbers
    friction = _copy_struct(base.friction)
    gas = _copy_struct(base.gas_params)
    gas.process = base.gas_params.process
    bladder, test = base.bladder, {}
    pressure = base.inflation_gauge_pressure_Pa
    for name, value in parameters.items():
        if name in MuscleBuild.fields():
            setattr(build, name, value)
        elif name.startswith("friction."):
            setattr(friction, name.removeprefix("friction."), value)
        elif name.startswith("gas."):
            setattr(gas, name.removeprefix("gas."), value)
        elif name == "bladder.shear_modulus_Pa":
            bladder = BladderLaw.neo_hookean(value)
        elif name == "inflation_pressure_kPa":
            pressure = test_condition(base.path, name, value)
        elif name == "ambient_temperature_C":
            gas.ambient_temperature_K = test_condition(base.path, name, value)
        elif name in TEST_PARAMETERS:
            test[name] = value
    if BRAID_ANGLE_KEY in parameters:  # converts through the other dimensions, set above
        build.fiber_revolutions = fiber_revolutions_for_braid_angle(build, parameters[BRAID_ANGLE_KEY])
    for struct in (build, friction, gas):
        struct.validate()
    return dataclasses.replace(
        base,
        build=build,
        friction=friction,
        gas_params=gas,
        bladder=bladder,
        inflation_gauge_pressure_Pa=pressure,
        **test,
    )


def first_stretch_end(elongation_m: np.ndarray) -> int:
    """Index of the sample where the first stretch ends: the largest elongation within the first
    cycle (from the last zero before the crosshead moves to its return to zero), or over the whole
    run when the crosshead never returns to zero."""
    try:
        starts = cycle_starts(elongation_m)
    except ValueError:
        return int(np.argmax(elongation_m))
    return int(starts[0] + np.argmax(elongation_m[starts[0] : starts[1] + 1]))


def summarize(experiment: Experiment, predicted: dict[str, np.ndarray]) -> dict[str, float]:
    """METRICS of one simulated run."""
    force, elongation = predicted["force_N"], predicted["elongation_m"]
    end = first_stretch_end(elongation) + 1
    sealed = experiment.gas == GasMode.sealed
    return {
        "peak_force_N": float(np.max(force)),
        "force_range_N": float(np.ptp(force)),
        "stored_energy_J": float(trapezoid(force[:end], elongation[:end])),
        "pressure_range_Pa": float(np.ptp(predicted["gauge_pressure_Pa"])) if sealed else math.nan,
        "temperature_swing_K": float(np.ptp(predicted["temperature_K"])) if sealed else math.nan,
    }


def exo_metrics(parameters: dict[str, float]) -> dict[str, float]:
    """EXO_METRICS of the device with `parameters` (exo_study's, without the walking-cadence run)."""
    arguments = {name.removeprefix("exo."): value for name, value in parameters.items()}
    if "pressure_kPa" in arguments:
        arguments["gauge_pressure_Pa"] = value_to_si("pressure_kPa", arguments.pop("pressure_kPa"))
    report = exo_study(**arguments, cadence_steps_per_min=None).report
    clutch = report["clutch"]
    return {
        "torque_share": report["torque_share_of_biological"],
        "peak_torque_Nm": report["peak_torque_Nm"],
        "elongation_max_m": report["elongation_max_m"],
        "engage_pct": math.nan if clutch["engage_pct"] is None else clutch["engage_pct"],
        "release_pct": math.nan if clutch["release_pct"] is None else clutch["release_pct"],
        "engaged_share_of_stride": clutch["engaged_share_of_stride"],
    }


def run_one(spec: SweepSpec, run: int) -> dict:
    """One run's row: its index, parameters, metrics (METRICS, or EXO_METRICS) and error (None
    when it ran). The runs of a sealed test's sweep go through `batch_rows` instead, with the
    same numbers; this is the exoskeleton's and a supplied test's path, one run at a time."""
    parameters = spec.parameters(run)
    row = {"run": run, **parameters}
    try:
        if spec.device == "exoskeleton":
            row.update(exo_metrics(parameters))
        else:
            experiment = with_parameters(base_experiment(spec.experiment, spec.cycles), parameters)
            row.update(summarize(experiment, simulate_experiment(experiment)))
        row["error"] = None
    except (ValueError, SolverError, Error) as error:  # the model or the muscle's checks: kept in the row
        row.update(dict.fromkeys(EXO_METRICS if spec.device == "exoskeleton" else METRICS, math.nan))
        row["error"] = str(error)
    return row


def batch_field(name: str) -> tuple[str, str | None]:
    """The ParameterSets field a spec's parameter sets, and the file column whose unit the spec
    gives it in (None: it is given in SI already)."""
    if name in MuscleBuild.fields() or name == BRAID_ANGLE_KEY:
        return f"build.{name}", None
    if name == "inflation_pressure_kPa":
        return "initial.gauge_pressure_Pa", TEST_CONDITIONS[name][3]
    if name == "ambient_temperature_C":
        return "gas.ambient_temperature_K", TEST_CONDITIONS[name][3]
    if name == "initial_length_m":
        return "initial.length_m", None
    return name, None  # friction.*, gas.*, bladder.shear_modulus_Pa: ParameterSets' own names


def parameter_sets(spec: SweepSpec, runs: list[int]) -> ParameterSets:
    """The muscles of `runs` as ParameterSets on the base experiment, each parameter converted to
    SI once for all of them (what with_parameters does run by run)."""
    base = base_experiment(spec.experiment, spec.cycles)
    fields, columns = zip(*(batch_field(name) for name in spec.names))
    values = np.array([spec.runs[run] for run in runs], dtype=float).reshape(len(runs), len(spec.names))
    for j, column in enumerate(columns):
        if column is not None:
            values[:, j] = value_to_si(column, values[:, j])
    start = InitialState(gauge_pressure_Pa=base.inflation_gauge_pressure_Pa)
    if base.initial_length_m is not None:
        start.length_m = base.initial_length_m
    return ParameterSets(muscle_params(base), start, list(fields), values, inflated_start=base.initial_length_m is None)


def batch_rows(spec: SweepSpec, runs: list[int], threads: int = 1) -> list[dict]:
    """The rows of `runs` of a sealed test's sweep from one batch of C++ runs on `threads` threads
    (Simulator.run_batch over parameter_sets): METRICS from each run's extremes and its force over
    the first stretch, read through the base's instruments as summarize reads them, the same
    numbers bit for bit. A failed run keeps its message, after the data file's name where the model
    could not follow the test (RunFailure.input), as simulate_experiment says it."""
    base = base_experiment(spec.experiment, spec.cycles)
    elongation = base.read("elongation_m", base.elongation_m)
    end = first_stretch_end(elongation) + 1
    result = Simulator(SimulatorConfig()).run_batch(
        parameter_sets(spec, runs),
        ElongationTrajectory(base.time_s, base.elongation_m),
        channels=["force_N", "gauge_pressure_Pa", "temperature_K"],
        rows=np.arange(end),
        threads=threads,
    )
    highest = {name: base.read(name, values) for name, values in result.maximum.items()}
    lowest = {name: base.read(name, values) for name, values in result.minimum.items()}
    stored = trapezoid(base.read("force_N", result.values["force_N"]), elongation[:end], axis=-1)
    not_followed = result.failures == int(RunFailure.input)
    rows = []
    for i, run in enumerate(runs):
        row = {"run": run, **spec.parameters(run)}
        if result.failed[i]:
            row.update(dict.fromkeys(METRICS, math.nan))
            row["error"] = f"{base.data_path}: {result.errors[i]}" if not_followed[i] else result.errors[i]
        else:
            row["peak_force_N"] = float(highest["force_N"][i])
            row["force_range_N"] = float(highest["force_N"][i] - lowest["force_N"][i])
            row["stored_energy_J"] = float(stored[i])
            for metric, name in (("pressure_range_Pa", "gauge_pressure_Pa"), ("temperature_swing_K", "temperature_K")):
                row[metric] = float(highest[name][i] - lowest[name][i])
            row["error"] = None
        rows.append(row)
    return rows


def batched(spec: SweepSpec) -> bool:
    """Whether the spec's runs go through batch_rows: a sealed test's time series (the
    exoskeleton and a supplied test's static solves run one at a time)."""
    if spec.device == "exoskeleton":
        return False
    return base_experiment(spec.experiment, spec.cycles).gas == GasMode.sealed


def run_chunk(spec: SweepSpec, runs: list[int], threads: int = 1) -> list[dict]:
    """The rows of several runs (one Dask task): one batch of C++ runs on `threads` threads where
    the spec is `batched`, else run by run."""
    if batched(spec):
        return batch_rows(spec, list(runs), threads)
    return [run_one(spec, run) for run in runs]


def run_in_process(spec: SweepSpec, threads: int = 1) -> list[dict]:
    """Every run in this process, in order, in batches of at most LARGEST_BATCH runs (the
    kept force over the first stretch bounds the memory): what a sweep on Dask must reproduce."""
    runs = range(len(spec.runs))
    return [
        row
        for start in range(0, len(runs), LARGEST_BATCH)
        for row in run_chunk(spec, list(runs[start : start + LARGEST_BATCH]), threads)
    ]


def sweep(spec: SweepSpec, output: str | Path, client, progress=None) -> list[dict]:
    """Runs the spec on the Dask `client` (see pamkit.cluster), writes the table to `output`
    (.parquet or .csv) and returns its rows in run order. Rows are journaled as they complete:
    after a crash the same call resumes."""
    output = check_output(output)
    prepare_base(spec)  # a bad base file is one error here, not one per run
    client.run(prepare_base, spec)  # on a cluster of many machines, each must see the file
    return run_all(
        functools.partial(run_chunk, spec),
        range(len(spec.runs)),
        row_key="run",
        item_key=lambda run: run,
        output=output,
        work=spec.work_key(),
        connected=client,
        label="sweep",
        progress=progress,
        largest_chunk=LARGEST_BATCH if batched(spec) else MAX_CHUNK,
    )
