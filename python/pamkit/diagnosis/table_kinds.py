"""The units of a static table (DESIGN.md, "Experiment kinds"): a campaign of one or more
tables of one muscle, the held-out group of each row (a map's held lengths, an isotonic test's
pressurise/vent sweeps, a free-inflation table's rows) and the noise, estimated without the
model."""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from pamkit._core import BraidGeometry, pressure_branches
from pamkit.diagnosis.kinds import LOCKING_ANGLE_DEG
from pamkit.io.columns import value_from_si
from pamkit.io.experiment import Experiment
from pamkit.io.guards import ExperimentError
from pamkit.io.sections import BRAID_ANGLE_KEY
from pamkit.simulation import muscle_params
from pamkit.units import MILLIMETRE_PER_METRE

# [calibrate] fields that move the braid's reach: with one of them unknown, the reach is too.
REACH_FIELDS = ("length_m", "diameter_m", "fiber_revolutions", BRAID_ANGLE_KEY, "end_diameter_m", "cone_generator_m")


@dataclass
class Campaign:
    """One or more tables of one muscle (DESIGN.md, "Campaigns"), as one table: each test keeps
    its own build and rows; the [calibrate] unknowns are shared."""

    experiments: list[Experiment]
    kind: str
    columns: dict[str, np.ndarray]  # every test's rows, concatenated
    test: np.ndarray  # the test of each row
    groups: np.ndarray  # the held-out group of each row (an index into group_labels)
    group_labels: list[str]
    group_name: str
    censored: np.ndarray  # rows whose supplied pressure reads at the transducer's range: never scored
    branch: np.ndarray  # +1 pressurising, -1 venting: per held length of a map, per test otherwise

    @property
    def name(self) -> str:
        return " + ".join(str(e.path) for e in self.experiments)


def test_names(experiments: list[Experiment]) -> list[str]:
    """A short name for each test of a campaign: its file's stem, with its folder where stems repeat."""
    stems = [Path(e.path).stem for e in experiments]
    if len(set(stems)) == len(stems):
        return stems
    return [f"{Path(e.path).parent.name}/{stem}" for e, stem in zip(experiments, stems)]


def campaign_of(experiments: list[Experiment]) -> Campaign:
    """Joins tables of one kind; a map's groups are its held lengths, a free-inflation table's its
    rows (DESIGN.md: the held-out unit follows the kind)."""
    kinds = {e.kind for e in experiments}
    if len(kinds) != 1:
        raise ExperimentError(f"a campaign's tables must be of one kind; found {', '.join(sorted(kinds))}")
    kind = kinds.pop()
    columns = {c: np.concatenate([e.columns[c] for e in experiments]) for c in experiments[0].columns}
    test = np.concatenate([np.full(len(e.columns["gauge_pressure_Pa"]), i) for i, e in enumerate(experiments)])
    labels: list[str] = []
    groups = np.empty(len(test), dtype=int)
    names = test_names(experiments)
    prefix = (lambda i: f"{names[i]} ") if len(experiments) > 1 else (lambda i: "")
    for i, e in enumerate(experiments):
        rows = np.flatnonzero(test == i)
        if kind == "isometric_map":
            for length in np.unique(np.round(e.columns["length_m"], 9)):
                groups[rows[np.round(e.columns["length_m"], 9) == length]] = len(labels)
                labels.append(f"{prefix(i)}L={length:g}")
        elif kind == "isotonic":
            # A sweep: pressurised, then vented; the next starts where the pressure rises again.
            branch = pressure_branches(e.columns["gauge_pressure_Pa"])
            sweep = np.concatenate([[0], np.cumsum((branch[1:] > 0) & (branch[:-1] < 0))])
            for number in np.unique(sweep):
                groups[rows[sweep == number]] = len(labels)
                labels.append(f"{prefix(i)}sweep {number + 1}")
        else:
            for row, pressure in zip(rows, value_from_si("gauge_pressure_Pa", e.columns["gauge_pressure_Pa"])):
                groups[row] = len(labels)
                labels.append(f"{prefix(i)}p={pressure:g}")  # in kPa, as the file gives it
    name = {"isometric_map": "held length", "isotonic": "sweep"}.get(kind, "row")
    censored = np.concatenate([e.censored for e in experiments])
    records = groups if kind == "isometric_map" else test
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
    if campaign.kind != "free_inflation":
        return []
    out = []
    for e in campaign.experiments:
        if any(field in e.calibrate for field in REACH_FIELDS):
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
    what the instruments add, not what the model misses."""
    pressure = campaign.columns["gauge_pressure_Pa"]
    branch = campaign.branch if campaign.kind == "isotonic" else np.ones(len(pressure))
    used = ~campaign.censored
    key = np.column_stack([campaign.test, branch, np.round(pressure, 3)])  # to a mPa: a file's 1e-6 kPa
    if campaign.kind == "isometric_map":
        key = np.column_stack([key, np.round(campaign.columns["length_m"], 9)])
    pressure, key = pressure[used], key[used]
    _, repeat, counts = np.unique(key, axis=0, return_inverse=True, return_counts=True)
    repeat = repeat.ravel()
    out = {}
    for channel in channels:
        values = campaign.columns[channel][used]
        if np.sum(counts - 1) >= 5:
            means = np.bincount(repeat, weights=values) / counts
            squares = float(np.sum((values - means[repeat]) ** 2))
            out[channel] = math.sqrt(squares / float(np.sum(counts - 1)))
            continue
        units = (campaign.groups if campaign.kind == "isometric_map" else campaign.test)[used]
        squares, dof = 0.0, 0
        for unit in np.unique(units):
            rows = units == unit
            if channel == "force_N":
                rows &= values > 0
            if rows.sum() < 6:
                continue
            coefficients = np.polyfit(pressure[rows], values[rows], 3)
            squares += float(np.sum((np.polyval(coefficients, pressure[rows]) - values[rows]) ** 2))
            dof += int(rows.sum()) - 4
        out[channel] = math.sqrt(squares / dof) if dof > 0 else float("nan")
    return out
