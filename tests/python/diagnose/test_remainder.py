"""Where a time series' remainder lies (diagnosis/series/remainder.py), on residuals made by hand:
four stretch cycles fitted and four held out, each of 20 samples, the first half of each cycle
its stretch and the second its return, the noise 1."""

from types import SimpleNamespace

import numpy as np
import pytest

from pamkit.diagnosis.series.remainder import describe, where_left

CYCLES, SAMPLES = 8, 20


def problem_with(residual_of_cycle):
    """A problem whose held-out cycles (1, 3, 5, 7 counted from 0) carry `residual_of_cycle(k, half)`
    on each sample (half 0: stretch, 1: return); the fitted cycles none."""
    cycle = np.repeat(np.arange(CYCLES), SAMPLES)
    half = 2 * cycle + (np.tile(np.arange(SAMPLES), CYCLES) >= SAMPLES // 2)
    held = cycle % 2 == 1
    residual = np.array([residual_of_cycle(c, h % 2) if m else 0.0 for c, h, m in zip(cycle, half, held)])
    alternating = np.tile([1.0, -1.0], CYCLES * SAMPLES // 2)  # zero mean within every half
    problem = SimpleNamespace(
        measured={"force_N": np.zeros(cycle.size)},
        sigma={"force_N": 1.0},
        held_mask=held,
        cycle=cycle,
        half_cycle=half,
        unit_name="stretch cycle",
    )
    return problem, SimpleNamespace(predicted={"force_N": residual}), alternating


def test_one_cycle_holding_most_of_the_error_is_named():
    problem, fit, wiggle = problem_with(lambda c, h: 4.0 if c == 5 else 1.0)
    fit.predicted["force_N"] = fit.predicted["force_N"] * wiggle  # no mean in any half: neither loop nor offset
    w = where_left(problem, fit, "force_N")
    assert w["held_out"] == [2, 4, 6, 8] and w["ratios"] == pytest.approx([1.0, 1.0, 4.0, 1.0])
    assert w["pattern"] == "one unit" and w["worst"] == 6 and w["share"] == pytest.approx(16 / 19)
    assert w["others_ratio"] == pytest.approx(1.0) and w["halves"] == "neither"
    assert describe(w).startswith("most of it in stretch cycle 6: 84 %")


def test_a_drift_whose_last_cycle_holds_most_of_the_error_is_a_drift_not_one_cycle():
    # A load cell's zero creeping at a constant rate: 2.9x, 4.5x, 9.0x the noise over three held-out
    # cycles (a diagnosis's figures), the last holding 74 % of the squared error.
    size = {1: 2.9, 3: 4.5, 5: 9.0}
    problem, fit, wiggle = problem_with(lambda c, h: size.get(c, 0.0))
    problem.held_mask = problem.held_mask & (problem.cycle < 7)
    fit.predicted["force_N"] = fit.predicted["force_N"] * wiggle
    w = where_left(problem, fit, "force_N")
    assert w["share"] > 0.5 and w["pattern"] == "growing"


@pytest.mark.parametrize("direction", ["growing", "fading"])
def test_an_error_that_changes_steadily_over_the_test_is_a_drift(direction):
    size = {1: 1.0, 3: 1.4, 5: 1.8, 7: 2.2} if direction == "growing" else {1: 2.2, 3: 1.8, 5: 1.4, 7: 1.0}
    problem, fit, wiggle = problem_with(lambda c, h: size[c])
    fit.predicted["force_N"] = fit.predicted["force_N"] * wiggle
    w = where_left(problem, fit, "force_N")
    assert w["pattern"] == direction, w
    # Rising by less than DRIFT_FACTOR from the first held-out cycle to the last is no drift.
    problem, fit, wiggle = problem_with(lambda c, h: {1: 1.0, 3: 1.1, 5: 1.2, 7: 1.3}[c])
    fit.predicted["force_N"] = fit.predicted["force_N"] * wiggle
    w = where_left(problem, fit, "force_N")
    assert w["pattern"] == "spread" and describe(w) == "spread over the held-out stretch cycles, 1.0x to 1.3x"
    problem, fit, wiggle = problem_with(lambda c, h: 2.0)
    fit.predicted["force_N"] = fit.predicted["force_N"] * wiggle
    assert describe(where_left(problem, fit, "force_N")) == "spread over the held-out stretch cycles, 2.0x in each"


def test_opposite_signs_on_the_stretch_and_the_return_are_a_loop_and_one_sign_an_offset():
    problem, fit, _ = problem_with(lambda c, h: 2.0 if h == 0 else -2.0)
    w = where_left(problem, fit, "force_N")
    assert w["halves"] == "loop" and w["halves_mean"] == pytest.approx([2.0, -2.0]) and w["pattern"] == "spread"
    assert "a loop the model lacks" in describe(w)
    problem, fit, _ = problem_with(lambda c, h: 2.0)
    assert where_left(problem, fit, "force_N")["halves"] == "offset"
    # A mean below half the RMSE on either half says neither.
    problem, fit, wiggle = problem_with(lambda c, h: 2.0 if h == 0 else 0.5)
    fit.predicted["force_N"] = fit.predicted["force_N"] + 1.5 * wiggle * (fit.predicted["force_N"] != 0)
    assert where_left(problem, fit, "force_N")["halves"] == "neither"


def test_fewer_than_two_held_out_cycles_say_nothing():
    problem, fit, _ = problem_with(lambda c, h: 1.0)
    problem.held_mask = problem.held_mask & (problem.cycle == 1)
    assert where_left(problem, fit, "force_N") == {}
