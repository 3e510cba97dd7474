"""Experiment files: a TOML describing the muscle and the test, naming a CSV of what was
measured (or planned). This module holds the :class:`Experiment` they are read into and the
loading, by their schema (:mod:`pamkit.io.schema`: the sections, the [test] keys, the kinds of
experiment): the TOML through the guards (:mod:`pamkit.io.guards`), the muscle's sections into
structs (:mod:`pamkit.io.sections`), the data by kind (:mod:`pamkit.io.series`).

A file is written for people (the inflation pressure in kPa, the room in degC, columns in kPa
and degC); an :class:`Experiment` is SI throughout, converted once, here and in the CSV readers.

Every problem is reported as an :class:`~pamkit.io.guards.ExperimentError` (a ``ValueError``)
that names the file, and for CSV data the line and column.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from pamkit._core import BladderLaw, FrictionParams, GasMode, GasParams, MuscleBuild
from pamkit.io.columns import COLUMN_UNITS, OPTIONAL_COLUMNS, other_units_of, si_name, value_to_si
from pamkit.io.guards import check_keys, experiment_warnings_kept, fail, named_file, number, read_toml
from pamkit.io.schema import (
    CAMPAIGN_SECTIONS,
    EXPERIMENT_SECTIONS,
    KINDS,
    RANGE_KEYS,
    SERIES_KIND,
    TABLE_COLUMNS,
    TABLE_DEFAULTS,
    TEST_CONDITIONS,
    TEST_KEYS,
)
from pamkit.io.sections import read_bladder, read_build, read_calibrate, read_friction, read_gas, read_uncertain
from pamkit.io.series import check_force_sign, check_units, read_isotonic, read_series, read_table
from pamkit.io.writers import write_experiment
from pamkit.io.zero_run import zero_offsets
from pamkit.units import NEWTON_PER_KILOGRAM_FORCE

# [test] gas: how the muscle's gas is held, by the name a file gives it.
GAS_MODES = dict(GasMode.__members__)
GLITCH_CHOICES = ("leave_out", "keep")  # [test] glitches: what a diagnosis does with them, the default first
SERIES_COMPLIANCE = "series_compliance_m_per_N"  # the build field only settled rows and samples model

if TYPE_CHECKING:
    import pandas as pd


@dataclass
class Experiment:
    """One experiment: the muscle, the test conditions and the measured series, in SI. The
    room's temperature is the gas's (``gas_params.ambient_temperature_K``): one fact, kept there."""

    path: Path
    build: MuscleBuild
    inflation_gauge_pressure_Pa: float  # gas pressure above the atmosphere after inflation [Pa]
    data_path: Path
    gas: GasMode = GasMode.sealed
    initial_length_m: float | None = None
    description: str = ""
    friction: FrictionParams = field(default_factory=FrictionParams)
    gas_params: GasParams = field(default_factory=GasParams)
    bladder: BladderLaw = field(default_factory=BladderLaw.thesis)
    kind: str = SERIES_KIND
    calibrate: dict[str, tuple[float, float]] = field(default_factory=dict)
    # [uncertain]: each build field the muscle may be off by, ± in its unit (default: the wind's 5 %)
    uncertain: dict[str, float] = field(default_factory=dict)
    uncertain_declared: bool = False  # the file gave [uncertain] (a static table frees only what a file declares)
    load_N: float | None = None
    load_mass_kg: float | None = None
    zeroed: dict[str, float] = field(default_factory=dict)  # offsets the zero run took off each channel
    preload_N: float | None = None
    ranges: dict[str, tuple[float, float]] = field(default_factory=dict)  # what each instrument reads
    columns: dict[str, np.ndarray] = field(default_factory=dict)  # SI: time_s, elongation_m, gauge_pressure_Pa, ...
    data_warnings: list[str] = field(default_factory=list)  # what reading the data repaired or doubted, as said
    keep_glitches: bool = False  # [test] glitches = "keep": a time series' diagnosis keeps every sample

    @property
    def is_table(self) -> bool:
        """A static table of settled rows, not a time series."""
        return self.kind in TABLE_COLUMNS

    @property
    def time_s(self) -> np.ndarray:
        return self.columns["time_s"]

    @property
    def elongation_m(self) -> np.ndarray:
        return self.columns["elongation_m"]

    def measured(self) -> list[str]:
        """The optional channels present in the data."""
        return [name for name in OPTIONAL_COLUMNS if name in self.columns]

    def reading_range(self, channel: str) -> tuple[float, float]:
        """The declared range of the channel's instrument, in the data's units: shifted by what the
        zero run took off (the instrument clips its raw reading)."""
        lowest, highest = self.ranges.get(channel, (-math.inf, math.inf))
        offset = self.zeroed.get(channel, 0.0)
        return lowest - offset, highest - offset

    def read(self, channel: str, values: np.ndarray) -> np.ndarray:
        """What the channel's instrument reads of true `values`: clipped into its range."""
        return np.clip(values, *self.reading_range(channel)) if channel in self.ranges else values

    @property
    def censored(self) -> np.ndarray:
        """Rows whose supplied pressure reads at an end of the transducer's range: the pressure
        that drove the muscle there is unknown (a reading of 0 kPa may be any pressure below the
        transducer's offset), so they are predicted but never fitted or scored."""
        rows = len(next(iter(self.columns.values())))
        if self.gas != GasMode.supplied or "gauge_pressure_Pa" not in self.ranges:
            return np.zeros(rows, dtype=bool)
        lowest, highest = self.reading_range("gauge_pressure_Pa")
        return (self.columns["gauge_pressure_Pa"] <= lowest) | (self.columns["gauge_pressure_Pa"] >= highest)

    def to_frame(self) -> pd.DataFrame:
        """The measured columns as a pandas DataFrame, one row per sample (or table row).

        Returns
        -------
        pandas.DataFrame
            The columns as read, SI (units in their names: time_s [s], elongation_m [m], force_N
            [N], gauge_pressure_Pa [Pa], temperature_K [K], length_m [m], ...), with ``df.attrs``
            "experiment" and "data" (the files' paths), "kind", "gas" (its name) and "units"
            (column -> unit), as :func:`pamkit.simulate` gives its prediction.
        """
        import pandas as pd  # imported where a table is built: it adds a sixth of a second to every start

        frame = pd.DataFrame({name: np.asarray(column) for name, column in self.columns.items()})
        frame.attrs.update(
            experiment=str(self.path),
            data=str(self.data_path),
            kind=self.kind,
            gas=self.gas.name,
            units={name: COLUMN_UNITS[name] for name in frame.columns},
        )
        return frame

    @classmethod
    def from_frame(
        cls, frame: pd.DataFrame, path: str | Path, sections: Mapping[str, Mapping[str, object]]
    ) -> Experiment:
        """An experiment from a pandas DataFrame of what was measured and the TOML sections that
        describe the muscle and the test: written as files (the TOML at `path`, its CSV beside it)
        and read back, so that it is checked exactly as a file is, and reports and calibrated
        parameters name a file that can be read again.

        Parameters
        ----------
        frame : pandas.DataFrame
            The measured columns, SI, units in their names (the columns of the experiment's kind:
            time_s and elongation_m, and any of force_N, gauge_pressure_Pa, temperature_K for a
            time series; a table's own), as :meth:`to_frame` gives them. Written to the CSV in
            the file's units (pressure_kPa, temperature_C) with 10 significant digits.
        path : str or Path
            The experiment TOML to write; the CSV gets its stem and the suffix ``.csv``.
        sections : mapping
            Section name -> {key: value}: ``"muscle"``, ``"test"`` and any of ``"bladder"``,
            ``"friction"``, ``"gas"``, ``"calibrate"``, as in a file (``pamkit template KIND``
            writes one with every key explained). ``[test] data`` is set to the CSV.

        Returns
        -------
        Experiment
            The experiment as :func:`pamkit.load_experiment` reads the files.

        Raises
        ------
        ExperimentError
            (a ValueError) naming the file, section, key, row or column of the first problem.
        ValueError
            Naming a column given under its file's name (``pressure_kPa``, not
            ``gauge_pressure_Pa``), or a section or key no experiment file has.
        """
        columns = {str(name): frame[name].to_numpy(dtype=float) for name in frame.columns}
        write_experiment(path, sections, columns)
        return load_experiment(path)


def test_condition(path: Path, key: str, value) -> float:
    """A [test] condition of TEST_CONDITIONS, checked against the range a file may give it in and
    converted to SI: the inflation pressure to Pa (gauge), the room's temperature to K.

    Raises:
        ExperimentError: naming the file, the key and the range it leaves.
    """
    given = number(path, f"[test] {key}", value)
    lowest, highest, unit, column = TEST_CONDITIONS[key]
    if not lowest <= given <= highest:
        raise fail(path, f"[test] {key} = {given} is outside [{lowest:g}, {highest:g}] {unit}")
    return value_to_si(column, given)


def _range(path: Path, key: str, value) -> tuple[float, float]:
    """An instrument's [lowest, highest] reading."""
    if not isinstance(value, list) or len(value) != 2:
        raise fail(path, f"[test] {key} = {value!r} must be [lowest, highest]")
    lowest, highest = (number(path, f"[test] {key}", v) for v in value)
    if not lowest < highest:
        raise fail(path, f"[test] {key} = [{lowest}, {highest}] needs lowest < highest")
    return lowest, highest


def load_tests(path: str | Path) -> list[Experiment]:
    """The experiments a TOML names: itself, or a campaign's tests (`[campaign] tests = [...]`,
    paths relative to it), each with the campaign's `[muscle]`, `[bladder]`, `[friction]`,
    `[gas]` and `[calibrate]` sections; a test may not give a section the campaign gives.

    Raises:
        ExperimentError: naming the campaign file, or the test's file, of the first problem.
    """
    path = Path(path)
    document = read_toml(path, "experiment")
    if "campaign" not in document:
        return [load_experiment(path)]
    for section in document:
        if section not in CAMPAIGN_SECTIONS:
            raise fail(path, f"unknown section [{section}] in a campaign (known: {', '.join(CAMPAIGN_SECTIONS)})")
    campaign = document.pop("campaign")
    check_keys(path, "campaign", campaign, ("tests",))
    tests = campaign.get("tests")
    if not isinstance(tests, list) or not tests or not all(isinstance(t, str) for t in tests):
        raise fail(path, f"[campaign] tests = {tests!r} must be a list of experiment files")
    return [load_experiment(path.parent / test, shared=document) for test in tests]


def test_names(experiments: list[Experiment]) -> list[str]:
    """A short name for each test of a campaign: its file's stem, with its folder where stems repeat."""
    stems = [Path(e.path).stem for e in experiments]
    if len(set(stems)) == len(stems):
        return stems
    return [f"{Path(e.path).parent.name}/{stem}" for e, stem in zip(experiments, stems)]


def load_experiment(path: str | Path, shared: dict | None = None) -> Experiment:
    """Reads an experiment TOML and its CSV (pamkit's own, a spreadsheet's with ";" and decimal
    commas, or a tensile machine's export: Instron Bluehill, ZwickRoell testXpert); `shared`
    sections (a campaign's) are added to it.

    Returns:
        An :class:`Experiment`, SI throughout: the muscle (``build``), the test conditions
        (``inflation_gauge_pressure_Pa``, the room in ``gas_params.ambient_temperature_K``,
        ``gas`` a GasMode) and ``columns``, a dict of 1-D float arrays of one length N (rows of
        the CSV), units in their names: time_s [s], elongation_m [m], and as measured
        force_N [N], gauge_pressure_Pa [Pa] (the file's pressure_kPa), temperature_K [K] (its
        temperature_C); a static table has its own (length_m [m], diameter_m [m], ...).

    Raises:
        ExperimentError: naming the file (and line and column for CSV data) of the first problem.
    """
    path = Path(path)
    document = read_toml(path, "experiment")
    if "campaign" in document:
        raise fail(path, "a campaign file, not one experiment: diagnose it, or load its tests with load_tests")
    for section, table in (shared or {}).items():
        if section in document:
            raise fail(path, f"gives [{section}], which its campaign shares: give it in one place")
        document[section] = table
    experiment = _experiment_of(path, _checked_sections(path, document))
    with experiment_warnings_kept(experiment.data_warnings):
        _read_data(experiment, document["test"])
    return experiment


def experiment_of(path: str | Path, sections: Mapping[str, Mapping[str, object]]) -> Experiment:
    """The experiment that a file at `path` holding `sections` (section name -> {key: value}, as
    write_experiment takes them) describes, without its data: what load_experiment makes of the
    file before it reads the data. A writer that simulates what it writes (pamkit synth) reads
    its sections here, so that it runs the model a reader of the file will run.

    Raises:
        ExperimentError: naming `path` and the section and key of the first problem.
    """
    path = Path(path)
    document = _checked_sections(path, {name: dict(table) for name, table in sections.items()})
    return _experiment_of(path, document)


def _checked_sections(path: Path, document: dict) -> dict:
    """`document`, once each of its sections is a table of a known name, [muscle] and [test] there."""
    for section in document:
        if section not in EXPERIMENT_SECTIONS:
            raise fail(path, f"unknown section [{section}] (known: {', '.join(sorted(EXPERIMENT_SECTIONS))})")
    for section in ("muscle", "test"):
        if section not in document:
            raise fail(path, f"missing section [{section}]")
    for section, table in document.items():
        if not isinstance(table, dict):
            raise fail(path, f"{section} = {table!r}: [{section}] is a section (a [{section}] line, then its keys)")
    return document


def _experiment_of(path: Path, document: dict) -> Experiment:
    """The experiment a file's sections describe, without its data."""
    build = read_build(path, document["muscle"])
    bladder = read_bladder(path, document.get("bladder", {}))
    friction = read_friction(path, document.get("friction", {}))
    gas_params = read_gas(path, document.get("gas", {}))
    test = _test_table(path, document["test"])
    kind = test.get("kind", SERIES_KIND)
    pressure = test_condition(path, "inflation_pressure_kPa", test["inflation_pressure_kPa"])
    gas_params.ambient_temperature_K = test_condition(path, "ambient_temperature_C", test["ambient_temperature_C"])
    gas_name = test.get("gas", "sealed")
    if not isinstance(gas_name, str) or gas_name not in GAS_MODES:
        raise fail(path, f"[test] gas = {gas_name!r} must be one of {', '.join(GAS_MODES)}")
    gas = GAS_MODES[gas_name]
    initial_length = _given(path, test, "initial_length_m")
    if initial_length is not None and not 0 < initial_length <= 5:
        raise fail(path, f"[test] initial_length_m = {initial_length} is outside (0, 5] m")
    calibrate = read_calibrate(path, document.get("calibrate", {}), bladder)
    uncertain = read_uncertain(path, document.get("uncertain"), build)
    load = _given(path, test, "load_N", kind)
    if load is not None and not 0 <= load <= 1e5:
        raise fail(path, f"[test] load_N = {load} is outside [0, 1e5] N")
    mass = _given(path, test, "load_mass_kg", kind)
    if mass is not None and not 0 < mass <= 1e4:
        raise fail(path, f"[test] load_mass_kg = {mass} is outside (0, 1e4] kg")
    if load is None and kind == "isotonic" and "load_N" not in calibrate:
        hung = (
            f" (a mass hung on the muscle weighs its mass times g: load_N = {mass * NEWTON_PER_KILOGRAM_FORCE:.6g} for "
            f"load_mass_kg = {mass:g}; load_mass_kg adds its inertia, for a record in time)"
            if mass is not None
            else ""
        )
        raise fail(path, f"[test] load_N is missing: an isotonic test needs its load, or load_N in [calibrate]{hung}")
    if "load_N" in calibrate and kind != "isotonic":
        raise fail(path, f'[calibrate] load_N belongs to kind = "isotonic", not {kind!r}')
    # A sealed test's ODE, and a load's motion, would carry the braid's length L - c F as an
    # algebraic unknown of every state: the compliance is modelled where rows and samples settle.
    integrated = "a sealed test's simulation" if kind == SERIES_KIND and gas != GasMode.supplied else None
    integrated = "a load's motion (load_mass_kg)" if mass is not None else integrated
    if integrated and (build.series_compliance_m_per_N > 0 or SERIES_COMPLIANCE in calibrate):
        raise fail(
            path,
            f"[muscle] {SERIES_COMPLIANCE} is modelled where the muscle settles at each row or sample (a static "
            f"table, a supplied test), not in {integrated}: give 0 and leave it out of [calibrate]",
        )
    preload = _given(path, test, "preload_N")
    if preload is not None:
        if gas != GasMode.supplied or kind != SERIES_KIND:
            raise fail(path, "[test] preload_N belongs to a supplied time series: a rig that holds the mounted length")
        if initial_length is not None:
            raise fail(path, "[test] gives both preload_N and initial_length_m: the preload sets the length")
        if not 0 < preload <= 1e5:
            raise fail(path, f"[test] preload_N = {preload} is outside (0, 1e5] N")
    ranges = {
        si_name(column): tuple(value_to_si(column, end) for end in _range(path, key, test[key]))
        for column, key in RANGE_KEYS.items()
        if key in test
    }
    return Experiment(
        path=path,
        build=build,
        inflation_gauge_pressure_Pa=pressure,
        data_path=named_file(path, "[test] data", test["data"]),
        gas=gas,
        initial_length_m=initial_length,
        description=str(test.get("description", "")),
        friction=friction,
        gas_params=gas_params,
        bladder=bladder,
        kind=kind,
        calibrate=calibrate,
        uncertain=uncertain,
        uncertain_declared="uncertain" in document,
        load_N=load,
        preload_N=preload,
        ranges=ranges,
        load_mass_kg=mass,
        keep_glitches=test.get("glitches") == "keep",
    )


def _test_table(path: Path, table: dict) -> dict:
    """[test] with its keys known, its kind known, and a static table's defaults filled in."""
    test = dict(table)
    check_keys(path, "test", test, TEST_KEYS)
    kind = test.get("kind", SERIES_KIND)
    if kind not in KINDS:
        raise fail(path, f"[test] kind = {kind!r} must be one of {', '.join(KINDS)}")
    if kind in TABLE_COLUMNS:
        if "zero" in test:
            raise fail(
                path, f"[test] zero: a {kind} table is zeroed before it is tabulated; zero runs apply to time series"
            )
        if "glitches" in test:
            raise fail(
                path, f"[test] glitches: a table's rows ({kind}) are settled states; glitches are a time series'"
            )
        # A table of settled rows at supplied pressures: no inflation to seal, no gas to warm.
        for key, default in TABLE_DEFAULTS.items():
            test.setdefault(key, default)
        if test.get("gas", "supplied") != "supplied":
            raise fail(path, f"[test] gas = {test['gas']!r}: a {kind} table is measured at supplied pressures")
        test["gas"] = "supplied"
    if test.get("glitches", GLITCH_CHOICES[0]) not in GLITCH_CHOICES:
        raise fail(path, f"[test] glitches = {test['glitches']!r} must be one of {', '.join(GLITCH_CHOICES)}")
    for key, (required, meaning) in TEST_KEYS.items():
        if required and key not in test:
            raise fail(path, f"missing key [test] {key} ({meaning})")
    return test


def _given(path: Path, test: dict, key: str, kind: str | None = None) -> float | None:
    """[test] `key` as a number if given, else None; with `kind`, a key that only an isotonic
    test takes."""
    if key not in test:
        return None
    value = number(path, f"[test] {key}", test[key])
    if kind is not None and kind != "isotonic":
        raise fail(path, f'[test] {key} belongs to kind = "isotonic", not {kind!r}')
    return value


# The span of lengths a muscle can be measured at, as shares of its deflated length: the span an
# isotonic test's equilibrium is searched over (pipeline.hpp, isotonic_lengths). A muscle contracts
# by at most about 40 % and stretches little; a length beyond is in another unit (millimetres under
# a column in metres) or of another muscle than [muscle] declares.
MEASURED_LENGTH_SHARES = (0.5, 1.2)


def _check_muscle_lengths(experiment: Experiment) -> None:
    """Raises an ExperimentError when a table's muscle lengths leave MEASURED_LENGTH_SHARES of the
    declared deflated length."""
    lengths, deflated = experiment.columns["length_m"], experiment.build.length_m
    low, high = (share * deflated for share in MEASURED_LENGTH_SHARES)
    if float(np.min(lengths)) < low or float(np.max(lengths)) > high:
        others = ", ".join(other_units_of(("length_m", "contraction_m")))
        raise fail(
            experiment.data_path,
            f"the muscle's length spans {float(np.min(lengths)):.4g} to {float(np.max(lengths)):.4g} m, outside "
            f"{low:.4g}-{high:.4g} m, {MEASURED_LENGTH_SHARES[0]:g}-{MEASURED_LENGTH_SHARES[1]:g} times the deflated "
            f"length [muscle] length_m = {deflated:g} m declares: is the column in another unit (length_m and "
            f"contraction_m are in metres; a file may give {others}), or the muscle another?",
        )


def _read_data(experiment: Experiment, test: dict) -> None:
    """The experiment's columns, read from its data file by kind; a time series zeroed by its
    zero run, if it names one."""
    path, data_path, kind = experiment.path, experiment.data_path, experiment.kind
    ignore = test.get("ignore_columns", [])
    if not isinstance(ignore, list) or not all(isinstance(name, str) for name in ignore):
        raise fail(
            path, f"[test] ignore_columns = {ignore!r} must be a list of column names, as the data file names them"
        )
    ignore = tuple(name.strip() for name in ignore)
    atmosphere = experiment.gas_params.atmospheric_pressure_Pa  # an absolute pressure's column is read above it
    if kind != SERIES_KIND and "specimen" in test:
        raise fail(path, f"[test] specimen chooses among a tensile machine's specimens: a {kind} table has none")
    if kind == "isotonic":
        dynamic = experiment.load_mass_kg is not None
        experiment.columns = read_isotonic(data_path, experiment.build.length_m, dynamic, ignore, atmosphere)
        check_units(data_path, experiment.columns)
        _check_muscle_lengths(experiment)
        return
    if kind in TABLE_COLUMNS:
        deflated = experiment.build.length_m if kind == "isometric_map" else None
        experiment.columns = read_table(data_path, TABLE_COLUMNS[kind], kind, False, ignore, deflated, atmosphere)
        check_units(data_path, experiment.columns)
        check_force_sign(data_path, experiment.columns)
        if kind == "isometric_map":
            _check_muscle_lengths(experiment)
        return
    specimen = test.get("specimen")
    if specimen is not None and (isinstance(specimen, bool) or not isinstance(specimen, (str, int))):
        raise fail(path, f"[test] specimen = {specimen!r} must be a specimen's label (its Specimen Number)")
    experiment.columns = read_series(data_path, None if specimen is None else str(specimen), ignore, atmosphere)
    check_units(data_path, experiment.columns)
    if "zero" in test:
        offsets = zero_offsets(path, test["zero"], list(experiment.columns), experiment.preload_N, ignore, atmosphere)
        for channel, offset in offsets.items():  # taken off, and recorded
            experiment.columns[channel] = experiment.columns[channel] - offset
        experiment.zeroed.update(offsets)
    check_force_sign(data_path, experiment.columns)
    if experiment.gas == GasMode.supplied and "gauge_pressure_Pa" not in experiment.columns:
        raise fail(data_path, 'a "supplied" test drives the model with pressure_kPa: the column is missing')
