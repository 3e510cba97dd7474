"""Where a time series' remainder lies: over the held-out cycles (one cycle, a drift that grows or
fades over the test, or spread evenly) and between their halves (opposite on the stretch and
the return: a loop the model lacks; the same on both: an offset or a scale). The report says it
beside the channel's held-out RMSE, so that what is left is described, not only measured."""

from __future__ import annotations

import numpy as np

from pamkit.diagnosis.series.calibrate import Fit
from pamkit.diagnosis.series.kinds import Problem

# One held-out unit holding at least this share of the squared error, the others level, is where
# the remainder lies.
ONE_UNIT_SHARE = 0.5
# A drift: the units' RMSE in the order measured rank-correlates with time at least this well and
# changes by at least this factor from the first held-out unit to the last.
DRIFT_RANK_CORRELATION = 0.8
DRIFT_FACTOR = 1.5
# The two halves' mean residuals, in units of the channel's held-out RMSE, beyond which a loop or
# an offset is what the remainder looks like (a mean of half the RMSE carries a quarter of its square).
HALVES_MEAN = 0.5


def _rank(values: np.ndarray) -> np.ndarray:
    return np.argsort(np.argsort(values)).astype(float)


def where_left(problem: Problem, fit: Fit, channel: str) -> dict:
    """The held-out error of `channel` per held-out unit (cycle) in units of its noise, the unit
    with the largest share of the squared error, the pattern over the units (`one unit`,
    `growing`, `fading` or `spread`), and the mean residual over the stretch halves and over the
    return halves in units of the noise with what they look like (`loop`, `offset` or `neither`).
    Empty with fewer than two held-out units."""
    residual = (fit.predicted[channel] - problem.measured[channel]) / problem.sigma[channel]
    held = problem.held_mask & (problem.cycle >= 0)
    units = np.unique(problem.cycle[held])
    if units.size < 2:
        return {}
    squared = np.array([np.sum(residual[held & (problem.cycle == u)] ** 2) for u in units])
    counts = np.array([np.count_nonzero(held & (problem.cycle == u)) for u in units])
    ratios = np.sqrt(squared / counts)
    worst = int(np.argmax(squared))
    share = float(squared[worst] / squared.sum())
    others = np.delete(np.arange(units.size), worst)
    out = {
        "unit": problem.unit_name,
        "held_out": [int(u) + 1 for u in units],  # numbered from 1, as a person counts cycles
        "ratios": [float(r) for r in ratios],
        "worst": int(units[worst]) + 1,
        "share": share,
        "others_ratio": float(np.sqrt(squared[others].sum() / counts[others].sum())),
    }
    rho = float(np.corrcoef(_rank(units), _rank(ratios))[0, 1]) if np.ptp(ratios) > 0 else 0.0
    # One unit stands out from the others only where they are level among themselves: a drift's
    # last unit holds most of the error too.
    level = ratios[others].max() < DRIFT_FACTOR * ratios[others].min()
    if units.size >= 3 and share >= ONE_UNIT_SHARE and level:
        out["pattern"] = "one unit"
    elif units.size >= 3 and rho >= DRIFT_RANK_CORRELATION and ratios[-1] >= DRIFT_FACTOR * ratios[0]:
        out["pattern"] = "growing"
    elif units.size >= 3 and rho <= -DRIFT_RANK_CORRELATION and ratios[0] >= DRIFT_FACTOR * ratios[-1]:
        out["pattern"] = "fading"
    else:
        out["pattern"] = "spread"
    stretch = held & (problem.half_cycle >= 0) & (problem.half_cycle % 2 == 0)
    back = held & (problem.half_cycle >= 0) & (problem.half_cycle % 2 == 1)
    if stretch.any() and back.any():
        up, down = float(np.mean(residual[stretch])), float(np.mean(residual[back]))
        rmse = float(np.sqrt(np.mean(residual[held] ** 2)))
        large = min(abs(up), abs(down)) >= HALVES_MEAN * rmse
        out["halves_mean"] = [up, down]
        out["halves"] = ("loop" if up * down < 0 else "offset") if large else "neither"
    return out


def describe(where: dict) -> str:
    """`where_left`'s finding as a phrase, to follow "<channel> at <ratio>x its noise"."""
    unit = where["unit"]
    if where["pattern"] == "one unit":
        text = (
            f"most of it in {unit} {where['worst']}: {100 * where['share']:.0f} % of the squared error, "
            f"{where['others_ratio']:.1f}x over the other held-out {unit}s"
        )
    elif where["pattern"] in ("growing", "fading"):
        first, last = where["ratios"][0], where["ratios"][-1]
        text = (
            f"{where['pattern']} over the test: {first:.1f}x in {unit} {where['held_out'][0]}, "
            f"{last:.1f}x in {unit} {where['held_out'][-1]}"
        )
    else:
        low, high = f"{min(where['ratios']):.1f}x", f"{max(where['ratios']):.1f}x"
        text = f"spread over the held-out {unit}s, " + (f"{low} in each" if low == high else f"{low} to {high}")
    halves = where.get("halves")
    if halves == "loop":
        text += "; of opposite sign on the way out and back: a loop the model lacks"
    elif halves == "offset":
        text += "; of one sign on the way out and back: an offset or a scale"
    return text
