"""What a fit's parameters say of it: values at a bound of their search or outside their plausible
range (a Finding, with how far beyond a bound the fit strains), and values below what one sample
resolves (a lag shorter than the sample interval, a slack shorter than the crosshead's travel
between samples)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from pamkit._core import Resolution
from pamkit.diagnosis.series.calibrate import Fit
from pamkit.diagnosis.series.kinds import Problem


def sample_interval(problem: Problem) -> float:
    return float(np.median(np.diff(problem.experiment.time_s)))


def travel_per_sample(problem: Problem) -> float:
    steps = np.abs(np.diff(problem.experiment.elongation_m))
    moving = steps[steps > 0.1 * steps.max()] if steps.max() > 0 else steps
    return float(np.median(moving)) if moving.size else 0.0


def _resolution_limit(problem: Problem, resolution: Resolution) -> tuple[float, str]:
    # An effect smaller than one sample resolves mimics a sub-sample shift of the channels: a
    # clock drifting by 50 ppm over a 400 s test is 20 ms.
    if resolution == Resolution.sample_interval:
        return sample_interval(problem), "the sample interval"
    if resolution == Resolution.travel_per_sample:
        return travel_per_sample(problem), "the crosshead's travel between samples"
    return 0.0, ""


@dataclass
class Finding:
    """One fitted parameter that ended at a bound or outside its plausible range."""

    parameter: str
    value: float
    bound: float | None
    plausible: list[float]
    source: str
    # at a bound: where the fit would take the parameter without it, and how much lower the
    # fitted RMSE would be there (calibrate.strain_at_bounds), when known
    beyond: float | None = None
    rmse_drop: float | None = None

    def to_json(self) -> dict:
        return {
            "parameter": self.parameter,
            "value": self.value,
            "bound": self.bound,
            "plausible": self.plausible,
            "source": self.source,
            "beyond_bound": self.beyond,
            "rmse_drop_beyond_bound": self.rmse_drop,
        }

    def sentence(self) -> str:
        if self.bound is not None:
            strain = (
                f" (unbounded, the fit would take it to {self.beyond:.4g}, its fitted RMSE "
                f"{100 * self.rmse_drop:.2g} % lower)"
                if self.beyond is not None
                else ""
            )
            return f"{self.parameter} = {self.value:.4g} ended at its search bound {self.bound:.4g}{strain}"
        return (
            f"{self.parameter} = {self.value:.4g} is outside its plausible range "
            f"[{self.plausible[0]:.4g}, {self.plausible[1]:.4g}]"
        )


def baseline_findings(baseline: Fit) -> list[Finding]:
    """The calibrated baseline's parameters at a bound or implausible, less those the data do not
    determine (a friction scale in a test that never moves: where it ends says nothing of the
    model; it is reported among the undetermined values instead)."""
    return [f for f in findings(baseline) if f.parameter not in getattr(baseline, "undetermined", {})]


def findings(fit: Fit) -> list[Finding]:
    """Every parameter of `fit` (anything with `coordinates`: a Fit, a table's or a campaign's)
    at a bound of its search or outside its plausible range, with how far beyond the bound the
    fit strains where it knows (`strain`)."""
    out = []
    strain = getattr(fit, "strain", {})
    for key, (coordinate, x) in fit.coordinates.items():
        value = float(coordinate.value(x))
        side = coordinate.at_bound(x)
        if side is None and not coordinate.implausible(value):
            continue
        beyond, drop = strain.get(key, (None, None)) if side else (None, None)
        out.append(
            Finding(
                key,
                value,
                coordinate.bound_value(side) if side else None,
                [float(coordinate.plausible[0]), float(coordinate.plausible[1])],
                coordinate.source,
                beyond,
                drop,
            )
        )
    return out


def unresolved(problem: Problem, fit: Fit) -> list[str]:
    """Parameters whose fitted size is below what one sample resolves, as sentences."""
    out = []
    for effect in fit.effects:
        prefix = f"{effect.name()}." if len(fit.effects) > 1 else ""
        for p in effect.parameters():
            limit, what = _resolution_limit(problem, p.resolution)
            value = fit.params.get(prefix + p.name)
            if limit > 0 and value is not None and abs(value) < limit:
                out.append(f"{prefix + p.name} = {value:.3g} is below {what} ({limit:.3g})")
    return out
