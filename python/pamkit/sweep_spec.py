"""A sweep's spec: the base experiment, the design and each run's parameter values, read from
the TOML file :mod:`pamkit.sweep` describes, and the base experiment each process reads once."""

from __future__ import annotations

import dataclasses
import functools
import itertools
import os
from pathlib import Path

import numpy as np
from scipy.stats import qmc

from pamkit._core import FrictionParams, GasParams
from pamkit.cluster import work_key
from pamkit.diagnosis.cycles import cycle_starts
from pamkit.io.experiment import Experiment, load_experiment
from pamkit.io.guards import check_keys, fail, named_file, number, read_toml
from pamkit.io.schema import TEST_CONDITIONS
from pamkit.io.sections import BRAID_ANGLE_KEY, calibratable_fields

#: The base experiment when a spec names none: PAM 2 of the thesis at 207 kPa, stretched to 80 %.
DEFAULT_EXPERIMENT = "pam2_207kPa_80pct.toml"


def thesis_directory(directory: str | Path | None = None) -> Path:
    """data/experiments/thesis: `directory` if given, else under $PAMKIT_SOURCE_DIR, else the
    nearest parent of this file that holds it (the source tree, or a build tree inside it).

    Raises:
        FileNotFoundError: if none is found.
    """
    if directory is not None:
        return Path(directory)
    candidates = []
    if os.environ.get("PAMKIT_SOURCE_DIR"):
        candidates.append(Path(os.environ["PAMKIT_SOURCE_DIR"]))
    candidates.extend(Path(__file__).resolve().parents)
    for root in candidates:
        found = root / "data" / "experiments" / "thesis"
        if found.is_dir():
            return found
    raise FileNotFoundError("data/experiments/thesis not found: set PAMKIT_SOURCE_DIR or pass the directory")


DESIGNS = ("grid", "latin_hypercube")
#: The summary of one run, with its meaning.
METRICS = {
    "peak_force_N": "largest force over the run [N]",
    "force_range_N": "largest minus smallest force [N]",
    "stored_energy_J": "work done on the muscle over the first stretch, the integral of F dx [J]",
    "pressure_range_Pa": "highest minus lowest gauge pressure, sealed tests (NaN when supplied) [Pa]",
    "temperature_swing_K": "highest minus lowest gas temperature, sealed tests (NaN when supplied) [K]",
}
# [test] conditions a sweep may set, with the range an experiment file allows them in.
TEST_PARAMETERS = {
    **{key: (lowest, highest, unit) for key, (lowest, highest, unit, _) in TEST_CONDITIONS.items()},
    "initial_length_m": (1e-9, 5.0, "m"),
}
DEVICES = ("muscle", "exoskeleton")
#: The exoskeleton's parameters (exo_study's arguments), with the range a sweep allows; the
#: device's own checks (LinkageParams, the gait) may reject more, as a failed run.
EXO_PARAMETERS = {
    "exo.mass_kg": (1.0, 300.0, "kg"),
    "exo.pressure_kPa": (0.0, 2000.0, "kPa"),  # gauge, as `pamkit exo --pressure` takes it
    "exo.play_deg": (0.0, 90.0, "deg"),
    "exo.compliance_deg_per_Nm": (0.0, 10.0, "deg/(N m)"),
    "exo.ankle_range_deg": (0.1, 90.0, "deg"),
    "exo.block_angle_deg": (1.0, 179.0, "deg"),
}
EXO_METRICS = {
    "torque_share": "peak device torque over peak biological ankle torque",
    "peak_torque_Nm": "peak device torque at the ankle [N m]",
    "elongation_max_m": "largest stretch of the muscle over the gait [m]",
    "engage_pct": "where in the stride the clutch engages [% of the cycle] (NaN: it never does)",
    "release_pct": "where in the stride the clutch releases [% of the cycle] (NaN: it never does)",
    "engaged_share_of_stride": "share of the stride the clutch holds the spring",
}
# Set through ambient_temperature_C, as an experiment file sets it: the room is one fact.
GAS_FIELDS_SET_ELSEWHERE = ("ambient_temperature_K",)
DISTRIBUTIONS = ("values", "linspace", "range")


def sweepable_parameters() -> dict[str, tuple[float, float, str]]:
    """Every name a spec's [parameters] may give, with its allowed range and unit."""
    allowed = {name: bounds for name, bounds in calibratable_fields().items() if name != "load_N"}
    allowed.update(TEST_PARAMETERS)
    for prefix, struct in (("friction", FrictionParams), ("gas", GasParams)):
        for name, info in struct.fields().items():
            if name not in GAS_FIELDS_SET_ELSEWHERE:
                allowed[f"{prefix}.{name}"] = (info["min"], info["max"], info["unit"])
    return allowed


@dataclasses.dataclass(frozen=True)
class SweepSpec:
    """What to run: the base experiment and each run's parameter values (plain data, so that
    Dask sends it to the workers as it is)."""

    path: Path  #: the spec file
    experiment: Path | None  #: the base experiment TOML (None for the exoskeleton)
    cycles: int | None  #: keep the base test's first cycles only
    design: str
    names: tuple[str, ...]  #: the parameters, in the spec's order
    runs: tuple[tuple[float, ...], ...]  #: each run's values, in `names` order
    seed: int | None = None
    device: str = "muscle"  #: or "exoskeleton": the runs are exo_study's

    def parameters(self, run: int) -> dict[str, float]:
        return dict(zip(self.names, self.runs[run]))

    def work_key(self) -> str:
        """A digest of the runs (the journal of a resumed sweep must have it)."""
        return work_key(
            {"experiment": str(self.experiment), "cycles": self.cycles, "names": self.names, "runs": self.runs}
        )


def _flatten(table: dict) -> dict[str, dict]:
    """[parameters] with its dotted names joined (a `[parameters.bladder]` table, or `bladder.x = {...}`)."""
    flat = {}
    for key, value in table.items():
        if isinstance(value, dict) and value and not set(value) & set(DISTRIBUTIONS):
            flat.update({f"{key}.{inner}": v for inner, v in _flatten(value).items()})
        else:
            flat[key] = value
    return flat


def _grid_values(path: Path, name: str, table: dict, low: float, high: float, unit: str) -> list[float]:
    where = f"[parameters] {name}"
    if set(table) == {"values"}:
        values = table["values"]
        if not isinstance(values, list) or not values:
            raise fail(path, f"{where}.values = {values!r} must be a list of numbers")
        values = [number(path, f"{where}.values", v) for v in values]
    elif set(table) == {"linspace"}:
        spec = table["linspace"]
        if not isinstance(spec, list) or len(spec) != 3 or isinstance(spec[2], bool) or not isinstance(spec[2], int):
            raise fail(path, f"{where}.linspace = {spec!r} must be [lo, hi, count]")
        if spec[2] < 1:
            raise fail(path, f"{where}.linspace count {spec[2]} must be at least 1")
        values = np.linspace(number(path, where, spec[0]), number(path, where, spec[1]), spec[2]).tolist()
    else:
        raise fail(path, f"{where} = {table!r}: a grid takes {{ values = [...] }} or {{ linspace = [lo, hi, n] }}")
    for value in values:
        if not low <= value <= high:
            raise fail(path, f"{where}: {value:g} {unit} leaves the allowed [{low:g}, {high:g}]")
    return values


def _bounds(path: Path, name: str, table: dict, low: float, high: float, unit: str) -> tuple[float, float]:
    where = f"[parameters] {name}"
    if set(table) != {"range"} or not isinstance(table["range"], list) or len(table["range"]) != 2:
        raise fail(path, f"{where} = {table!r}: a latin_hypercube takes {{ range = [lo, hi] }}")
    lower, upper = (number(path, f"{where}.range", v) for v in table["range"])
    if not lower < upper:
        raise fail(path, f"{where}.range = [{lower:g}, {upper:g}] needs lo < hi")
    if lower < low or upper > high:
        raise fail(path, f"{where}.range = [{lower:g}, {upper:g}] {unit} leaves the allowed [{low:g}, {high:g}]")
    return lower, upper


def _positive_int(path: Path, key: str, value) -> int:
    if isinstance(value, bool) or not isinstance(value, int) or value < 1:
        raise fail(path, f"[sweep] {key} = {value!r} must be a whole number >= 1")
    return value


def load_spec(path: str | Path) -> SweepSpec:
    """Reads a sweep spec and lays out its runs (the hypercube drawn with its seed).

    Raises:
        ExperimentError: naming the spec file, section and key of the first problem.
    """
    path = Path(path)
    document = read_toml(path, "sweep spec")
    for section in document:
        if section not in ("sweep", "parameters"):
            raise fail(path, f"unknown section [{section}] (known: parameters, sweep)")
    sweep = document.get("sweep", {})
    check_keys(path, "sweep", sweep, ("experiment", "cycles", "design", "samples", "seed", "device"))
    device = sweep.get("device", "muscle")
    if device not in DEVICES:
        raise fail(path, f"[sweep] device = {device!r} must be one of {', '.join(DEVICES)}")
    if device == "exoskeleton":
        for key in ("experiment", "cycles"):
            if key in sweep:
                raise fail(path, f"[sweep] {key}: the exoskeleton runs on Winter's gait, not on an experiment")
    if device == "exoskeleton":
        experiment = None
    elif "experiment" in sweep:
        experiment = named_file(path, "[sweep] experiment", sweep["experiment"])
    else:
        experiment = thesis_directory() / DEFAULT_EXPERIMENT
    cycles = _positive_int(path, "cycles", sweep["cycles"]) if "cycles" in sweep else None
    design = sweep.get("design", "grid")
    if design not in DESIGNS:
        raise fail(path, f"[sweep] design = {design!r} must be one of {', '.join(DESIGNS)}")
    for key in ("samples", "seed"):
        if (key in sweep) != (design == "latin_hypercube"):
            raise fail(path, f"[sweep] {key}: {'needed by' if key not in sweep else 'belongs to'} a latin_hypercube")
    table = _flatten(document.get("parameters", {}))
    if not table:
        raise fail(path, "[parameters] is empty: name at least one parameter to sweep")
    allowed = EXO_PARAMETERS if device == "exoskeleton" else sweepable_parameters()
    for name, value in table.items():
        if name not in allowed:
            raise fail(path, f"[parameters] {name}: not a parameter a sweep can set (known: {', '.join(allowed)})")
        if not isinstance(value, dict):
            raise fail(path, f"[parameters] {name} = {value!r} must be a table such as {{ values = [...] }}")
    if BRAID_ANGLE_KEY in table and "fiber_revolutions" in table:
        raise fail(path, f"[parameters] names both fiber_revolutions and {BRAID_ANGLE_KEY}: they say the same")
    names = tuple(table)
    if design == "grid":
        axes = [_grid_values(path, name, table[name], *allowed[name]) for name in names]
        runs = tuple(itertools.product(*axes))
        seed = None
    else:
        samples = _positive_int(path, "samples", sweep["samples"])
        seed = sweep["seed"]
        if isinstance(seed, bool) or not isinstance(seed, int) or seed < 0:
            raise fail(path, f"[sweep] seed = {seed!r} must be a whole number >= 0")
        bounds = np.array([_bounds(path, name, table[name], *allowed[name]) for name in names])
        unit = qmc.LatinHypercube(d=len(names), rng=seed).random(samples)
        runs = tuple(tuple(row) for row in qmc.scale(unit, bounds[:, 0], bounds[:, 1]).tolist())
    return SweepSpec(path, experiment, cycles, design, names, runs, seed, device)


@functools.lru_cache(maxsize=4)
def base_experiment(path: Path, cycles: int | None) -> Experiment:
    """The base experiment, read once per process (a Dask worker keeps it between chunks), cut
    to its first `cycles` cycles when given."""
    experiment = load_experiment(path)
    if experiment.is_table:
        raise fail(path, f"a {experiment.kind} table: a sweep simulates a time series")
    if cycles is not None:
        try:
            starts = cycle_starts(experiment.elongation_m)
        except ValueError as error:
            raise fail(experiment.data_path, f"[sweep] cycles: {error}") from None
        if len(starts) - 1 < cycles:
            raise fail(experiment.data_path, f"[sweep] cycles = {cycles}: the test has {len(starts) - 1} cycles")
        end = starts[cycles] + 1
        experiment.columns = {name: values[:end] for name, values in experiment.columns.items()}
    return experiment


def prepare_base(spec: SweepSpec) -> int:
    """Reads the spec's base experiment into this process's cache; returns its sample count.
    Run on every worker before the runs, so that a base file a worker cannot read is one error."""
    if spec.device == "exoskeleton":
        return 0
    return len(base_experiment(spec.experiment, spec.cycles).time_s)
