"""What a fitted value's place in its search says (python/pamkit/diagnosis/coordinates.py): at a
bound, or placed off it by the data."""

import math
from types import SimpleNamespace

from pamkit.diagnosis.coordinates import AT_BOUND, PRESSED, findings, rate_coordinate

# A leak's time constant as the catalog searches it: a rate from 0 ("no leak") to 1/(5 s).
LEAK = rate_coordinate("time_constant_s", 1.0 / 5.0, 1000.0, plausible=(5.0, math.inf))


def fitted(rate: float, interval):
    return SimpleNamespace(coordinates={"time_constant_s": (LEAK, rate)}, intervals={"time_constant_s": interval})


def test_a_value_near_a_bound_is_at_it_unless_its_interval_excludes_it():
    # A 7500 s leak (bench_near_model, leak medium seed 4: the truth 9300 s) lies 6.7e-4 of the
    # rate's search from "no leak", within AT_BOUND: with its interval inside thousands of seconds
    # the data place it off the bound; with the interval reaching "no leak" they do not.
    rate = 1.0 / 7500.0
    assert PRESSED < rate / (LEAK.upper - LEAK.lower) < AT_BOUND
    assert findings(fitted(rate, (6900.0, 8200.0))) == []
    (at,) = findings(fitted(rate, (6900.0, math.inf)))
    assert at.bound == math.inf and at.value == 7500.0
    assert len(findings(SimpleNamespace(coordinates={"time_constant_s": (LEAK, rate)}))) == 1  # no interval


def test_a_value_pressed_against_its_bound_is_at_it_whatever_its_interval():
    # Within PRESSED of the bound, where a bounded solver stops against it, the interval (from the
    # Jacobian of a constrained optimum) does not place the value off.
    rate = 0.5 * PRESSED * (LEAK.upper - LEAK.lower)
    (at,) = findings(fitted(rate, (0.9 / rate, 1.1 / rate)))
    assert at.bound == math.inf
