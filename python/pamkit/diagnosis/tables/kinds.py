"""The units of a static table (docs/experiments.md, its kinds): a campaign of one or more
tables of one muscle, the held-out group of each row (a map's held lengths, an isotonic test's
pressurise/vent sweeps, a free-inflation table's rows) and the noise, estimated without the
model. A campaign may join tables of different kinds (an isometric map and an isotonic test of
one muscle): each row then predicts its own kind's channels. A supplied time series of the same
muscle (a tensile machine cycling it at a regulated pressure) may join them: what a muscle's
friction with memory and its slack braid do depends on the path, not on its rate, so its samples
are rows in the order measured, its stretch cycles its groups."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from pamkit._core import PRESSURE_BRANCH_PLAY_PA, BraidGeometry, GasMode, pressure_branches
from pamkit.diagnosis.cycles import find_cycles
from pamkit.diagnosis.series.kinds import LOCKING_ANGLE_DEG
from pamkit.io.columns import value_from_si
from pamkit.io.experiment import Experiment, test_names
from pamkit.io.guards import ExperimentError
from pamkit.io.sections import BRAID_ANGLE_KEY
from pamkit.simulation import muscle_params
from pamkit.units import MILLIMETRE_PER_METRE

# [calibrate] fields that move the braid's reach: with one of them unknown, the reach is too.
REACH_FIELDS = ("length_m", "diameter_m", "fiber_revolutions", BRAID_ANGLE_KEY, "end_diameter_m", "cone_generator_m")
# A supplied time series in a campaign of tables: the crosshead cycles the muscle at a regulated pressure.
CYCLIC = "cyclic"
# The channels each kind predicts.
PREDICTED = {
    "isometric_map": ("force_N",),
    "free_inflation": ("length_m", "diameter_m"),
    "isotonic": ("length_m",),
    CYCLIC: ("force_N",),
}
# What each kind holds out.
GROUP_NAMES = {"isometric_map": "held length", "isotonic": "sweep", "free_inflation": "row", CYCLIC: "cycle"}
# What a map held at fewer than MIN_GROUPS lengths holds out instead: its pressure runs, and
# with too few of those, their halves.
RUN_NAMES = ("pressure run", "half pressure run")
# Fewer held-out groups than this cannot say whether a model carries beyond its fitted rows.
MIN_GROUPS = 3
# A held-out run (a sweep's pressurising or venting part) ends where the pressure turns by more
# than this share of the record's span: a regulator's overshoot of a few kPa on a 600 kPa sweep
# turns back by under 1 %, a sweep's top or bottom by all of it.
RUN_TURN = 0.05


def kind_of(experiment: Experiment) -> str:
    """A test's kind in a campaign of tables: its table kind, or CYCLIC for a supplied time series.

    Raises:
        ExperimentError: for a sealed time series, whose gas the tables' settled rows do not follow.
    """
    if experiment.is_table:
        return experiment.kind
    if experiment.gas == GasMode.supplied:
        return CYCLIC
    raise ExperimentError(
        f"{experiment.path}: a sealed time series joins a campaign of time series; a campaign of tables takes "
        '[test] gas = "supplied" series (the pressure regulated, the crosshead cycling the muscle)'
    )


@dataclass
class Campaign:
    """One or more tables of one muscle (docs/experiments.md, "Campaigns"), as one table: each test keeps
    its own build and rows; the [calibrate] unknowns are shared."""

    experiments: list[Experiment]
    kind: str  # the tests' kind, or their kinds joined by " + "
    columns: dict[str, np.ndarray]  # every test's rows, concatenated (NaN where a test has no such column)
    test: np.ndarray  # the test of each row
    groups: np.ndarray  # the held-out group of each row (an index into group_labels)
    group_labels: list[str]
    group_name: str
    censored: np.ndarray  # rows whose supplied pressure reads at the transducer's range: never scored
    branch: np.ndarray  # +1 pressurising, -1 venting: per held length of a map, per test otherwise

    @property
    def name(self) -> str:
        return " + ".join(str(e.path) for e in self.experiments)

    @property
    def channels(self) -> tuple[str, ...]:
        """What the campaign predicts: its kinds' channels, in the order the tests give them."""
        out: list[str] = []
        for e in self.experiments:
            out += [c for c in PREDICTED[kind_of(e)] if c not in out]
        return tuple(out)

    @property
    def kinds(self) -> list[str]:
        """Each test's kind (kind_of)."""
        return [kind_of(e) for e in self.experiments]

    def predicts(self, channel: str) -> np.ndarray:
        """The rows whose test's kind predicts `channel`."""
        kinds = np.array(self.kinds)
        return np.isin(kinds[self.test], [k for k, channels in PREDICTED.items() if channel in channels])

    def of_kind(self, kind: str) -> Campaign:
        """The campaign's tests of one kind, as a campaign of their own."""
        return campaign_of([e for e in self.experiments if kind_of(e) == kind])


def held_out_branches(gauge_pressure_Pa: np.ndarray) -> np.ndarray:
    """Each row's pressurising (+1) or venting (-1) run as a held-out unit sees it: a turn of the
    pressure by less than RUN_TURN of the record's span (a regulator overshooting a step, a
    settled step's noise) does not end a run, where the friction's branch may turn
    (PRESSURE_BRANCH_PLAY_PA). A run ends at its last row within that play of its extreme (the
    top or bottom step, settled or overshooting), not where the turn is first told."""
    pressure = np.asarray(gauge_pressure_Pa, dtype=float)
    span = float(np.ptp(pressure)) if len(pressure) else 0.0
    play = max(0.5 * RUN_TURN * span, PRESSURE_BRANCH_PLAY_PA)
    told = np.asarray(pressure_branches(pressure, play))
    branch = told.copy()
    start = 0
    for turn in np.flatnonzero(np.diff(told)) + 1:
        run = pressure[start:turn]
        near = run >= run.max() - play if told[turn - 1] > 0 else run <= run.min() + play
        end = start + int(np.flatnonzero(near)[-1]) + 1
        branch[end:turn] = told[turn]
        start = end
    return branch


def pressure_runs(gauge_pressure_Pa: np.ndarray) -> list[tuple[np.ndarray, bool, int]]:
    """The record's pressurising and venting runs (held_out_branches): each run's rows, whether
    the pressure rises along it, and its number among the runs of its direction."""
    branch = held_out_branches(gauge_pressure_Pa)
    run = np.concatenate([[0], np.cumsum(branch[1:] != branch[:-1])])
    out, count = [], {True: 0, False: 0}
    for number in np.unique(run):
        rising = bool(branch[run == number][0] > 0)
        count[rising] += 1
        out.append((np.flatnonzero(run == number), rising, count[rising]))
    return out


def map_groups(experiment: Experiment) -> tuple[str, list[tuple[np.ndarray, str]]]:
    """What an isometric map holds out (its unit's name, and each group's rows and label): its
    held lengths; with fewer than MIN_GROUPS, each pressurising or venting run at each; with
    fewer of those, the first and second half of each run's rows."""
    lengths = np.round(experiment.columns["length_m"], 9)
    held = [np.flatnonzero(lengths == length) for length in np.unique(lengths)]
    names = [f"L={length:g}" for length in np.unique(lengths)]
    if len(held) >= MIN_GROUPS:
        return GROUP_NAMES["isometric_map"], list(zip(held, names))
    runs = [
        (at[run], f"{name} {'pressurising' if rising else 'venting'} {number}")
        for at, name in zip(held, names)
        for run, rising, number in pressure_runs(experiment.columns["gauge_pressure_Pa"][at])
    ]
    if len(runs) >= MIN_GROUPS:
        return RUN_NAMES[0], runs
    halves = [(rows[: len(rows) // 2], f"{label}, first half") for rows, label in runs]
    halves += [(rows[len(rows) // 2 :], f"{label}, second half") for rows, label in runs]
    return RUN_NAMES[1], sorted((part for part in halves if len(part[0])), key=lambda part: part[0][0])


def campaign_of(experiments: list[Experiment]) -> Campaign:
    """Joins tables of one muscle, of one kind or several; a map's groups are its held lengths, an
    isotonic test's its sweeps, a free-inflation table's its rows: the held-out unit follows the
    kind."""
    kinds = list(dict.fromkeys(kind_of(e) for e in experiments))
    kind = " + ".join(kinds)
    names_of_columns = list(dict.fromkeys(c for e in experiments for c in e.columns))
    columns = {
        c: np.concatenate([e.columns.get(c, np.full(len(e.columns["gauge_pressure_Pa"]), np.nan)) for e in experiments])
        for c in names_of_columns
    }
    test = np.concatenate([np.full(len(e.columns["gauge_pressure_Pa"]), i) for i, e in enumerate(experiments)])
    labels: list[str] = []
    groups = np.empty(len(test), dtype=int)
    names = test_names(experiments)
    prefix = (lambda i: f"{names[i]} ") if len(experiments) > 1 else (lambda i: "")
    units: list[str] = []  # what each test holds out, in the order met
    for i, e in enumerate(experiments):
        rows = np.flatnonzero(test == i)
        if e.kind == "isometric_map":
            unit, parts = map_groups(e)
            units.append(unit)
            for part, label in parts:
                groups[rows[part]] = len(labels)
                labels.append(f"{prefix(i)}{label}")
        elif e.kind == "isotonic":
            # A sweep: pressurised, then vented; the next starts where the pressure rises again.
            branch = held_out_branches(e.columns["gauge_pressure_Pa"])
            sweep = np.concatenate([[0], np.cumsum((branch[1:] > 0) & (branch[:-1] < 0))])
            for number in np.unique(sweep):
                groups[rows[sweep == number]] = len(labels)
                labels.append(f"{prefix(i)}sweep {number + 1}")
        elif kind_of(e) == CYCLIC:
            # A stretch cycle from one low turn of the crosshead to the next; what comes before
            # the first (the mounting, the pressurising) belongs to it, what follows the last to that.
            cycles = find_cycles(e.elongation_m)
            number = np.clip(cycles.index(len(rows)), 0, None) if len(cycles) else np.zeros(len(rows), dtype=int)
            if len(cycles):
                number[cycles.ends[-1] :] = len(cycles) - 1
            for cycle in np.unique(number):
                groups[rows[number == cycle]] = len(labels)
                labels.append(f"{prefix(i)}cycle {cycle + 1}")
        else:
            for row, pressure in zip(rows, value_from_si("gauge_pressure_Pa", e.columns["gauge_pressure_Pa"])):
                groups[row] = len(labels)
                labels.append(f"{prefix(i)}p={pressure:g}")  # in kPa, as the file gives it
    name = " or ".join(dict.fromkeys(units + [GROUP_NAMES[k] for k in kinds if k != "isometric_map"]))
    censored = np.concatenate([e.censored for e in experiments])
    # A branch runs along a record: a map's held length, another kind's whole test.
    records = np.empty(len(test))
    for i, e in enumerate(experiments):
        rows = np.flatnonzero(test == i)
        records[rows] = np.round(e.columns["length_m"], 9) if e.kind == "isometric_map" else -1.0
    records = np.unique(np.column_stack([test, records]), axis=0, return_inverse=True)[1].ravel()
    branch = np.empty(len(test))
    for record in np.unique(records):
        rows = np.flatnonzero(records == record)
        branch[rows] = pressure_branches(columns["gauge_pressure_Pa"][rows])
    return Campaign(experiments, kind, columns, test, groups, labels, name, censored, branch)


def beyond_reach(campaign: Campaign) -> list[dict]:
    """Free-inflation diameters no cylinder of the declared braid can reach: at its locking angle
    (inflated with no load, a braid approaches it and no further) the braid's diameter is
    b sin(54.7°) / (n π) for fibre length b and n revolutions, and calipers
    on the braid add at most its two crossing fibres. Each such test is a warning (a measurement
    over a bulge, or a build other than the one declared), not a cause to fit."""
    out = []
    for e in campaign.experiments:
        if kind_of(e) != "free_inflation" or any(field in e.calibrate for field in REACH_FIELDS):
            continue
        build = muscle_params(e).build
        reach = (
            BraidGeometry(build).fiber_length
            * math.sin(math.radians(LOCKING_ANGLE_DEG))
            / (build.fiber_revolutions * math.pi)
        )
        reach += 2.0 * build.fiber_thickness_m
        rows = np.flatnonzero(e.columns["diameter_m"] > reach)
        if rows.size == 0:
            continue
        pressures = ", ".join(
            f"{value_from_si('gauge_pressure_Pa', e.columns['gauge_pressure_Pa'][r]):g}" for r in rows
        )
        diameters = ", ".join(f"{MILLIMETRE_PER_METRE * e.columns['diameter_m'][r]:.4g}" for r in rows)
        out.append(
            {
                "data": "diameter_m",
                "test": str(e.path),
                "rows": [int(r) for r in rows],
                "reach_m": reach,
                "message": (
                    f"{e.path}: the diameter at {pressures} kPa ({diameters} mm) exceeds the most a cylinder of the "
                    f"declared braid reaches ({MILLIMETRE_PER_METRE * reach:.4g} mm: its locking angle, plus two "
                    "fibres for the "
                    "calipers); measured over a bulge, or the braid is not the one declared — no model parameter of "
                    "this build can fit it"
                ),
            }
        )
    return out


def noise_of(campaign: Campaign, channels: tuple[str, ...]) -> dict[str, float]:
    """The table's noise per channel, model-free. Where rows repeat (the same pressure on the same
    branch of several isotonic sweeps, the same length and pressure in several maps), the pooled
    spread of the repeats; otherwise the residual of a cubic in pressure fitted to each held
    length's loaded rows (force > 0) of a map or to each free-inflation table. Either leaves
    what the instruments add, not what the model misses. A slack muscle's force reads exactly
    zero, with no noise in it: such rows are left out. An isotonic test's first sweep starts from
    rest, and friction with memory makes it no repeat of the sweeps after it: the repeats are
    looked for among those. A cyclic time series's noise is its samples' scatter about their
    neighbours (cyclic_noise). Where several kinds predict a channel, their noises pooled by rows."""
    kinds = list(dict.fromkeys(campaign.kinds))
    if len(kinds) > 1:  # each channel from the tests that predict it
        out = {}
        for c in channels:
            parts = [campaign.of_kind(k) for k in kinds if c in PREDICTED[k]]
            variances = [(noise_of(part, (c,))[c] ** 2, len(part.test)) for part in parts]
            out[c] = math.sqrt(sum(v * n for v, n in variances) / sum(n for _, n in variances))
        return out
    if kinds == [CYCLIC]:
        return {c: cyclic_noise(campaign, c) for c in channels}
    pressure = campaign.columns["gauge_pressure_Pa"]
    branch = campaign.branch if campaign.kind == "isotonic" else np.ones(len(pressure))
    used = ~campaign.censored
    key = np.column_stack([campaign.test, branch, np.round(pressure, 3)])  # to a mPa: a file's 1e-6 kPa
    if campaign.kind == "isometric_map":
        key = np.column_stack([key, np.round(campaign.columns["length_m"], 9)])
    if campaign.kind == "isotonic":
        first_sweep = {test: campaign.groups[campaign.test == test].min() for test in np.unique(campaign.test)}
        first = campaign.groups == np.array([first_sweep[test] for test in campaign.test])
        # Each row of a first sweep a key of its own: no repeat of anything.
        key = np.column_stack([key, np.where(first, np.arange(len(pressure)), -1)])
    out = {}
    for channel in channels:
        rows = used & (campaign.columns[channel] > 0) if channel == "force_N" else used
        values = campaign.columns[channel][rows]
        _, repeat, counts = np.unique(key[rows], axis=0, return_inverse=True, return_counts=True)
        repeat = repeat.ravel()
        if np.sum(counts - 1) >= 5:
            means = np.bincount(repeat, weights=values) / counts
            squares = float(np.sum((values - means[repeat]) ** 2))
            out[channel] = math.sqrt(squares / float(np.sum(counts - 1)))
            continue
        # A map's held lengths; an isotonic test's pressurising and venting rows apart (a loop
        # between them is no noise); a free-inflation table.
        if campaign.kind == "isometric_map":
            units = campaign.groups[rows]
        else:
            units = (2 * campaign.test + (branch > 0))[rows]
        at = pressure[rows]
        squares, dof = 0.0, 0
        for unit in np.unique(units):
            mine = units == unit
            if mine.sum() < 6:
                continue
            coefficients = np.polyfit(at[mine], values[mine], 3)
            squares += float(np.sum((np.polyval(coefficients, at[mine]) - values[mine]) ** 2))
            dof += int(mine.sum()) - 4
        out[channel] = math.sqrt(squares / dof) if dof > 0 else float("nan")
    return out


def cyclic_noise(campaign: Campaign, channel: str) -> float:
    """The noise of a channel of cyclic time series, model-free: a smooth signal sampled densely
    changes by nearly the same step from one sample to the next, so its second difference is the
    noise's, whose spread is sqrt(6) times the noise's. The median of its magnitude (over samples
    whose force is not a slack zero), as the median absolute deviation estimates a spread, is not
    moved by the few samples where the crosshead turns or the muscle goes slack."""
    values = []
    for test in np.unique(campaign.test):
        rows = np.flatnonzero(campaign.test == test)
        signal = campaign.columns[channel][rows]
        loaded = (signal > 0) if channel == "force_N" else np.ones(len(rows), dtype=bool)
        second = signal[2:] - 2.0 * signal[1:-1] + signal[:-2]
        values.append(second[loaded[2:] & loaded[1:-1] & loaded[:-2]])
    joined = np.concatenate(values)
    if joined.size == 0:
        return float("nan")
    return float(1.4826 * np.median(np.abs(joined - np.median(joined))) / math.sqrt(6.0))
