"""The coordinates a fit searches: each one's bounds and start, how it maps to a parameter's
value, and the parameter's physically plausible range with its source. An effect's come from what
it declares (its fields' search scale, interval and start); a build field's from the experiment
file (`[calibrate]`: an unknown within its bounds; `[uncertain]`: the declared value within its
tolerance). Both kinds of test fit on them: a time series (series/) and a static table (tables/),
and both report a fitted coordinate that ended at a bound or outside its plausible range (a
Finding).

Effect parameters move smoothly in their coordinate: log for time constants, rates for "infinite
means off" constants.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass
from typing import Protocol

import numpy as np

from pamkit._core import BladderLaw, Effect, EffectParameter, FitScale, MuscleParams, fiber_revolutions_for_braid_angle
from pamkit.io.experiment import Experiment
from pamkit.io.sections import BRAID_ANGLE_KEY, declared_value

# [calibrate] unknowns whose declared range spans more than this ratio are searched on a log scale.
LOG_SPAN = 20.0


def _identity(x: float) -> float:
    return x


def _reciprocal(x: float) -> float:
    return 1.0 / x if x > 0 else math.inf if x == 0 else -math.inf


# A fitted coordinate within this share of its interval's width from an end is "at a bound",
# unless its 95 % interval excludes that end (findings); within PRESSED, the bounded solver's own
# tolerance, it is at the bound whatever its interval, which the Jacobian of a constrained optimum
# does not give (a friction scale at 9e-10 of its bound 0).
AT_BOUND = 1e-3
PRESSED = 1e-6


@dataclass(frozen=True)
class Coordinate:
    """One fitted coordinate: its bounds and start, how it maps to a parameter's value, and the
    parameter's physically plausible range (in value units) with its source."""

    name: str
    lower: float
    upper: float
    start: float
    to_value: callable = _identity
    from_value: callable = _identity
    plausible: tuple[float, float] = (-math.inf, math.inf)
    source: str = ""

    def value(self, x: float) -> float:
        return self.to_value(x)

    def of(self, value: float) -> float:
        return self.from_value(value)

    def at_bound(self, x: float, share: float = AT_BOUND) -> str | None:
        """ "lower" or "upper" when x ended within `share` of the search interval's width of an end
        of it, else None."""
        margin = share * (self.upper - self.lower)
        if x <= self.lower + margin:
            return "lower"
        if x >= self.upper - margin:
            return "upper"
        return None

    def bound_value(self, side: str) -> float:
        return float(self.value(self.lower if side == "lower" else self.upper))

    def implausible(self, value: float) -> bool:
        return not (self.plausible[0] <= value <= self.plausible[1])


def log_coordinate(name, lower, upper, start, plausible=(-math.inf, math.inf), source=""):
    return Coordinate(name, math.log(lower), math.log(upper), math.log(start), math.exp, math.log, plausible, source)


def linear_coordinate(name, lower, upper, start, plausible=(-math.inf, math.inf), source=""):
    return Coordinate(name, lower, upper, start, plausible=plausible, source=source)


def rate_coordinate(name, largest_rate, start_value, plausible=(-math.inf, math.inf), source=""):
    """Fits 1/value in [0, largest_rate]: 0 is 'infinite', the effect switched off."""
    return Coordinate(name, 0.0, largest_rate, 1.0 / start_value, _reciprocal, _reciprocal, plausible, source)


def parameter_coordinate(p: EffectParameter) -> Coordinate:
    """The fit coordinate of an effect parameter, from what the effect declares (its search
    scale, interval and start, its plausible range: catalog.hpp, or a Python effect's
    EffectParameter)."""
    plausible = (p.plausible_min, p.plausible_max)
    if p.fit_scale == FitScale.log:
        return log_coordinate(p.name, p.fit_min, p.fit_max, p.fit_start, plausible, p.plausible_source)
    if p.fit_scale == FitScale.reciprocal:
        return rate_coordinate(p.name, 1.0 / p.fit_min, p.fit_start, plausible, p.plausible_source)
    return linear_coordinate(p.name, p.fit_min, p.fit_max, p.fit_start, plausible, p.plausible_source)


def effect_space(effect: Effect) -> list[Coordinate]:
    """The fit coordinates of an effect, one per numeric parameter it lets a diagnosis search
    (a parameter whose search interval is one point is held at it)."""
    return [parameter_coordinate(p) for p in effect.parameters() if p.fit_min != p.fit_max]


def unknown_coordinate(name: str, bounds: tuple[float, float], experiment: Experiment) -> Coordinate:
    """The fit coordinate of a `[calibrate]` field (an unknown of the build): its declared
    bounds are both its search interval and its plausible range; it starts at the declared value
    when that lies inside, else mid-interval. `name` may carry a test's suffix (`load_N[a]`)."""
    lower, upper = bounds
    declared = declared_value(name.split("[", 1)[0], experiment.build, experiment.bladder, experiment.load_N)
    start = declared if lower < declared < upper else 0.5 * (lower + upper)
    source = "the [calibrate] bounds the experiment file declares"
    if lower > 0 and upper / lower > LOG_SPAN:
        return log_coordinate(name, lower, upper, start, (lower, upper), source)
    return linear_coordinate(name, lower, upper, start, (lower, upper), source)


@functools.cache
def _build_fields(build_type: type) -> frozenset[str]:
    return frozenset(build_type.fields())


def with_unknowns(params: MuscleParams, values: dict[str, float]) -> MuscleParams:
    """`params` with the `[calibrate]` build and bladder fields in `values` set (other names,
    such as the baseline's scales, are left to the caller)."""
    build = params.build
    fields = _build_fields(type(build))
    for name, value in values.items():
        if name in fields:
            setattr(build, name, value)
    if BRAID_ANGLE_KEY in values:
        build.fiber_revolutions = fiber_revolutions_for_braid_angle(build, values[BRAID_ANGLE_KEY])
    params.build = build
    if "bladder.shear_modulus_Pa" in values:
        params.bladder = BladderLaw.neo_hookean(values["bladder.shear_modulus_Pa"])
    return params


def configure(effect: Effect, space: list[Coordinate], x: np.ndarray) -> Effect:
    for coordinate, value in zip(space, x):
        effect.set(coordinate.name, float(coordinate.value(value)))
    return effect


def uncertain_fields(experiment: Experiment) -> list[str]:
    """The build fields `[uncertain]` declares that `[calibrate]` does not already fit (the wind
    and the braid angle are one number)."""
    known = set(experiment.calibrate)
    if {"fiber_revolutions", BRAID_ANGLE_KEY} & known:
        known |= {"fiber_revolutions", BRAID_ANGLE_KEY}
    return [name for name in experiment.uncertain if name not in known]


def uncertain_coordinate(name: str, experiment: Experiment) -> Coordinate:
    """A build field free within its `[uncertain]` tolerance of its declared value: its search
    interval is its plausible range, so that ending at an end is the base model straining."""
    declared = declared_value(name, experiment.build, experiment.bladder)
    tolerance = experiment.uncertain[name]
    bounds = (declared - tolerance, declared + tolerance)
    return linear_coordinate(
        name, *bounds, declared, bounds, f"[uncertain] {name} = {tolerance:g}: the build as it may be"
    )


class Fitted(Protocol):
    """Anything fitted on coordinates (a time series' fit, a table's, a campaign's): each
    coordinate with the point the fit ended at, by name."""

    coordinates: dict[str, tuple[Coordinate, float]]


# A bound whose lifting would lower the fitted RMSE by less than this share holds nothing back: the
# fit rests there on a flat floor (a wind traded against the inflation pressure), it does not strain.
NO_COST_AT_BOUND = 1e-3


@dataclass
class Finding:
    """One fitted parameter that ended at a bound or outside its plausible range."""

    parameter: str
    value: float
    bound: float | None
    plausible: list[float]
    source: str
    # at a bound: where the fit would take the parameter without it, and how much lower the
    # fitted RMSE would be there (series/calibrate.strain_at_bounds), when known
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

    @property
    def costs_nothing(self) -> bool:
        """At a bound that, lifted, would lower the fitted RMSE by less than NO_COST_AT_BOUND."""
        return self.bound is not None and self.rmse_drop is not None and self.rmse_drop < NO_COST_AT_BOUND

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


def _placed_off(interval, bound: float) -> bool:
    """Whether a value's 95 % interval excludes the bound it lies near: the data place it off the
    bound, however near in the search's own scale (a leak of 7500 s, 6.7e-4 of the width of its
    rate's search up to 1/(5 s) from "no leak", its interval inside thousands of seconds)."""
    if interval is None:
        return False
    low, high = interval
    return not low <= bound <= high


def findings(fit: Fitted) -> list[Finding]:
    """Every parameter of `fit` (anything with `coordinates`: a Fit, a table's or a campaign's)
    at a bound of its search or outside its plausible range, with how far beyond the bound the
    fit strains where it knows (`strain`)."""
    out = []
    strain = getattr(fit, "strain", {})
    intervals = getattr(fit, "intervals", {})
    for key, (coordinate, x) in fit.coordinates.items():
        value = float(coordinate.value(x))
        side = coordinate.at_bound(x)
        if (
            side is not None
            and _placed_off(intervals.get(key), coordinate.bound_value(side))
            and coordinate.at_bound(x, PRESSED) is None
        ):
            side = None
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
