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
# What a campaign of too few natural units (held_out_units) holds out instead in the kinds whose
# pressure runs: their pressure runs, and with too few of those, their halves.
RUN_KINDS = ("isometric_map", "isotonic")
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
    record: np.ndarray  # the record of each row, along which the pressure runs: a map's held length, another test
    branch: np.ndarray  # +1 pressurising, -1 venting, along each record

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


def isotonic_sweeps(gauge_pressure_Pa: np.ndarray) -> np.ndarray:
    """Each row's sweep (0, 1, ...): pressurised, then vented; the next starts where the pressure
    rises again (held_out_branches)."""
    branch = held_out_branches(gauge_pressure_Pa)
    return np.concatenate([[0], np.cumsum((branch[1:] > 0) & (branch[:-1] < 0))])


Parts = list[tuple[np.ndarray, str]]  # a test's held-out groups: each one's rows and label


def natural_units(experiment: Experiment) -> Parts:
    """What a test holds out when a campaign has enough of them: a map's held lengths, an
    isotonic test's sweeps, a cyclic test's stretch cycles, a free-inflation table's rows."""
    kind = kind_of(experiment)
    pressure = experiment.columns["gauge_pressure_Pa"]
    if kind == "isometric_map":
        lengths = np.round(experiment.columns["length_m"], 9)
        return [(np.flatnonzero(lengths == length), f"L={length:g}") for length in np.unique(lengths)]
    if kind == "isotonic":
        sweep = isotonic_sweeps(pressure)
        return [(np.flatnonzero(sweep == number), f"sweep {number + 1}") for number in np.unique(sweep)]
    if kind == CYCLIC:
        # A stretch cycle from one low turn of the crosshead to the next; what comes before the
        # first (the mounting, the pressurising) belongs to it, what follows the last to that.
        cycles = find_cycles(experiment.elongation_m)
        number = np.clip(cycles.index(len(pressure)), 0, None) if len(cycles) else np.zeros(len(pressure), dtype=int)
        if len(cycles):
            number[cycles.ends[-1] :] = len(cycles) - 1
        return [(np.flatnonzero(number == cycle), f"cycle {cycle + 1}") for cycle in np.unique(number)]
    kPa = value_from_si("gauge_pressure_Pa", pressure)  # labelled in the file's unit
    return [(np.array([row]), f"p={value:g}") for row, value in enumerate(kPa)]


def runs_of(experiment: Experiment) -> Parts:
    """A map's or an isotonic test's pressurising and venting runs (pressure_runs): at each held
    length of a map, along the whole record of an isotonic test. Other kinds keep their units."""
    if kind_of(experiment) not in RUN_KINDS:
        return natural_units(experiment)
    pressure = experiment.columns["gauge_pressure_Pa"]
    whole = [(np.arange(len(pressure)), "")]
    records = natural_units(experiment) if kind_of(experiment) == "isometric_map" else whole
    return [
        (at[run], " ".join(filter(None, (name, "pressurising" if rising else "venting", str(number)))))
        for at, name in records
        for run, rising, number in pressure_runs(pressure[at])
    ]


def halves_of(experiment: Experiment) -> Parts:
    """The first and second half of each of runs_of's runs, in the order measured."""
    runs = runs_of(experiment)
    if kind_of(experiment) not in RUN_KINDS:
        return runs
    halves = [(rows[: len(rows) // 2], f"{label}, first half") for rows, label in runs]
    halves += [(rows[len(rows) // 2 :], f"{label}, second half") for rows, label in runs]
    return sorted((part for part in halves if len(part[0])), key=lambda part: part[0][0])


def held_out_units(experiments: list[Experiment]) -> tuple[str, list[Parts]]:
    """What a campaign holds out (its unit's name, and each test's groups): its tests' natural
    units; with fewer than MIN_GROUPS of them in all, each map's and isotonic test's pressurising
    and venting runs; with fewer of those, the first and second half of each run. A lab's first
    test of a muscle (one held length, one or two sweeps under a load) is judged on parts of its
    own record rather than refused."""
    for split, unit in ((natural_units, None), (runs_of, RUN_NAMES[0])):
        parts = [split(e) for e in experiments]
        if sum(map(len, parts)) >= MIN_GROUPS:
            return _unit_name(experiments, unit), parts
    return _unit_name(experiments, RUN_NAMES[1]), [halves_of(e) for e in experiments]


def _unit_name(experiments: list[Experiment], split_unit: str | None) -> str:
    """The held-out unit's name: `split_unit` for the kinds whose runs were split, each other
    kind's own; several joined by " or "."""
    names = [split_unit if split_unit and kind_of(e) in RUN_KINDS else GROUP_NAMES[kind_of(e)] for e in experiments]
    return " or ".join(dict.fromkeys(names))


def campaign_of(experiments: list[Experiment]) -> Campaign:
    """Joins tables of one muscle, of one kind or several, each test's rows held out by the
    units held_out_units gives it."""
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
    name, parts_of_tests = held_out_units(experiments)
    for i, parts in enumerate(parts_of_tests):
        rows = np.flatnonzero(test == i)
        for part, label in parts:
            groups[rows[part]] = len(labels)
            labels.append(f"{prefix(i)}{label}")
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
    return Campaign(experiments, kind, columns, test, groups, labels, name, censored, records, branch)


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
    branch of several isotonic sweeps or of several sweeps at one held length of a map), the
    pooled spread of the repeats; otherwise the residual of a cubic in pressure fitted to each
    pressurising or venting run of a held length (its loaded rows, force > 0) or to each
    free-inflation table. Either leaves what the instruments add, not what the model misses. A
    slack muscle's force reads exactly zero, with no noise in it: such rows are left out. A first
    sweep starts from rest, and friction with memory makes it no repeat of the sweeps after it:
    the repeats are looked for among those. A loop between the branches is the muscle's: pooled
    across them, a held DMSP whose braid moved read 4-8 N of noise for the load cell's 1 N. A
    cyclic time series's noise is its samples' scatter about their neighbours (cyclic_noise).
    Where several kinds predict a channel, their noises pooled by rows."""
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
    # A loop between a record's pressurising and venting runs, and its first sweep from rest, are
    # the muscle's, not the instruments': a repeat is a row of the same run direction at the same
    # pressure in a later sweep, and a cubic follows one run.
    records = campaign.record
    branch = campaign.branch if campaign.kind in ("isotonic", "isometric_map") else np.ones(len(pressure))
    used = ~campaign.censored
    key = np.column_stack([campaign.test, branch, np.round(pressure, 3)])  # to a mPa: a file's 1e-6 kPa
    if campaign.kind == "isometric_map":
        key = np.column_stack([key, np.round(campaign.columns["length_m"], 9)])
    runs = np.zeros(len(pressure), dtype=int)
    if campaign.kind in ("isotonic", "isometric_map"):
        first = np.zeros(len(pressure), dtype=bool)
        for record in np.unique(records):
            rows = np.flatnonzero(records == record)
            first[rows] = isotonic_sweeps(pressure[rows]) == 0
            if campaign.kind == "isometric_map":
                for number, (run, _, _) in enumerate(pressure_runs(pressure[rows])):
                    runs[rows[run]] = number
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
        if campaign.kind == "isotonic":
            out[channel] = sweep_noise(campaign, channel)
            continue
        # A map's held lengths, run by run; a free-inflation table.
        if campaign.kind == "isometric_map":
            units = np.unique(np.column_stack([records, runs])[rows], axis=0, return_inverse=True)[1].ravel()
        else:
            units = campaign.test[rows]
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


# A standard normal's variance within three of its deviations of zero.
TRUNCATED_VARIANCE_3 = 0.9733
# Consecutive rows whose difference sweep_noise takes: four, so that a quadratic cancels.
DIFFERENCE_ROWS = 4


def difference_residuals(x: np.ndarray, y: np.ndarray) -> np.ndarray:
    """The noise in y as each DIFFERENCE_ROWS consecutive rows tell it: a combination of their
    values that cancels every quadratic in x (a third divided difference), scaled to unit norm,
    so that its spread is the noise's where the signal is locally quadratic (the difference-based
    variance estimators of Hall, Kay and Titterington, 1990, at unequal spacing). Rows read at
    one pressure (a settled step read several times) leave more than one such combination; any
    of them serves."""
    out = []
    for start in range(len(x) - DIFFERENCE_ROWS + 1):
        window = x[start : start + DIFFERENCE_ROWS]
        scaled = (window - window.mean()) / (np.ptp(window) or 1.0)  # one step read four times: any difference
        powers = np.vander(scaled, DIFFERENCE_ROWS - 1, increasing=True).T
        weights = np.linalg.svd(powers)[2][-1]  # spans what the powers leave
        out.append(float(weights @ y[start : start + DIFFERENCE_ROWS]))
    return np.array(out)


def sweep_noise(campaign: Campaign, channel: str) -> float:
    """The noise of isotonic tests whose steps do not repeat (fewer than three sweeps), model-free.
    Along a pressurising or venting run the length is smooth in the pressure except where the
    friction breaks away, a knee no low-order polynomial follows over a whole run: here each
    four consecutive rows of a run tell the noise (difference_residuals), except the few around a
    knee, left out beyond three spreads by the median absolute deviation; the rest's RMS,
    corrected for that cut, is the noise."""
    residuals = []
    for test in np.unique(campaign.test):
        rows = np.flatnonzero((campaign.test == test) & ~campaign.censored)
        pressure, values = campaign.columns["gauge_pressure_Pa"][rows], campaign.columns[channel][rows]
        for run, _, _ in pressure_runs(pressure):
            x, y = pressure[run], values[run]
            if len(run) >= DIFFERENCE_ROWS:
                residuals.append(difference_residuals(x, y))
    if not residuals:
        return float("nan")
    joined = np.concatenate(residuals)
    spread = 1.4826 * np.median(np.abs(joined))
    if spread == 0.0:  # more than half the windows exact: a quantised record
        return float(np.sqrt(np.mean(joined**2)))
    kept = joined[np.abs(joined) <= 3.0 * spread]
    return float(np.sqrt(np.mean(kept**2) / TRUNCATED_VARIANCE_3))


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
