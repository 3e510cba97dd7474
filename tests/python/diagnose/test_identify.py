"""Intervals never claim what the data cannot tell (python/pamkit/diagnosis/identify.py): a
parameter the data do not determine is reported as such, with what it trades against, and its
interval is its whole search interval, never a zero width."""

import json
import shutil

import numpy as np
import pytest
from conftest import SOURCE_DIR

from pamkit.diagnosis import diagnose, to_json
from pamkit.diagnosis.coordinates import linear_coordinate
from pamkit.diagnosis.identify import Z95, identify
from pamkit.diagnosis.series.calibrate import cluster_intervals
from pamkit.io.experiment import load_experiment

rng = np.random.default_rng(3)
FESTO = SOURCE_DIR / "data" / "experiments" / "festo"  # not the working folder: ctest runs in the build


def test_a_coordinate_the_prediction_does_not_depend_on_is_not_determined():
    jacobian = np.column_stack([rng.normal(size=50) * 30, np.zeros(50), rng.normal(size=50) * 30])
    found = identify(jacobian)
    assert found.undetermined == {1: []}
    assert found.covariance[1, 1] == 0.0 and found.covariance[0, 0] > 0.0


def test_two_coordinates_that_move_the_prediction_alike_trade_against_each_other():
    column = rng.normal(size=50) * 30
    jacobian = np.column_stack([column, 2.0 * column, rng.normal(size=50) * 30])
    found = identify(jacobian)
    assert found.undetermined == {0: [1], 1: [0]}


def test_a_determined_fit_has_the_least_squares_covariance():
    # One algorithm against another: (JᵀJ)⁻¹ by numpy's inverse, and the SVD's.
    jacobian = rng.normal(size=(60, 3)) * 40
    found = identify(jacobian)
    assert found.undetermined == {}
    np.testing.assert_allclose(found.covariance, np.linalg.inv(jacobian.T @ jacobian), rtol=1e-10)


@pytest.mark.parametrize("across_the_box, determined", [(1.5, False), (2.5, True)])
def test_a_direction_wider_than_the_search_is_not_determined(across_the_box, determined):
    # Moving across the whole box changes the fit by `across_the_box` noise sigmas: its 95 %
    # interval is Z95 / across_the_box of the box, wider than the box below Z95 = 1.96.
    found = identify(np.array([[across_the_box, 0.0], [0.0, 40.0]]))
    assert (0 not in found.undetermined) == determined == (Z95 / across_the_box < 1.0)
    assert 1 not in found.undetermined


def test_an_undetermined_interval_is_its_search_interval():
    space = [
        linear_coordinate("braid_angle_deg", 10.0, 45.0, 20.0),
        linear_coordinate("fiber_count", 20.0, 200.0, 100.0),
    ]
    jacobian = np.column_stack([rng.normal(size=40) * 50, np.zeros(40)])
    residual = rng.normal(size=40)
    bands, undetermined = cluster_intervals(space, np.array([0.3, 0.4]), jacobian, residual, np.arange(40) // 4)
    assert undetermined == {"fiber_count": []}
    assert bands[1] == (20.0, 200.0)
    assert 0.0 < bands[0][1] - bands[0][0] < 35.0


def test_a_festo_map_does_not_determine_a_fibre_count_it_does_not_depend_on(tmp_path):
    # The DMSP's fibres are embedded (fiber_thickness_m = 0): a settled force does not depend on
    # how many there are. Declared unknown, the count must come back not determined, with its
    # search interval, not as its start with a zero-width interval.
    for name in ("DMSP-10-250.toml", "DMSP-10-250.csv"):
        shutil.copy(FESTO / name, tmp_path / name)
    toml = tmp_path / "DMSP-10-250.toml"
    toml.write_text(toml.read_text().replace("[calibrate]\n", "[calibrate]\nfiber_count = [20, 200]\n"))
    report = json.loads(json.dumps(to_json(diagnose(load_experiment(toml))), default=float))
    for fit in ("baseline", "extended"):
        assert report[fit]["undetermined"]["fiber_count"]["trades_against"] == [], report[fit]["undetermined"]
        assert report[fit]["intervals"]["fiber_count"] == pytest.approx([20.0, 200.0])
        widths = {k: hi - lo for k, (lo, hi) in report[fit]["intervals"].items()}
        assert all(w > 0 for w in widths.values()), widths


def test_an_interval_prints_with_the_digits_that_tell_its_ends_apart():
    from pamkit.diagnosis.identify import interval_numbers

    # Four significant digits where they tell the ends apart; more where a narrow interval's ends
    # would print alike (a braid angle pinned to 0.002 degrees read "22 [22, 22]"), up to 9.
    assert interval_numbers(21.57, 20.86, 22.29) == ("21.57", "20.86", "22.29")
    assert interval_numbers(22.0023, 22.0011, 22.0041) == ("22.002", "22.001", "22.004")
    assert interval_numbers(1.0, 1.0 - 1e-12, 1.0 + 1e-12)[1:] == ("1", "1")  # beyond 9 digits: alike
    assert interval_numbers(3.0, 3.0, 3.0) == ("3", "3", "3")
