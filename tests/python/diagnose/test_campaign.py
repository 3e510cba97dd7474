"""Campaigns of time series (issue "Diagnosis that holds outside its own world", item 2): several
bench tests of one muscle from the independent model (tests/independent, never importing
pamkit), each held out in turn; and the campaign TOML that names them."""

import json
import os
import sys
from pathlib import Path

import pytest

SOURCE_DIR = Path(os.environ.get("PAMKIT_SOURCE_DIR", Path(__file__).resolve().parents[3]))
sys.path.insert(0, str(SOURCE_DIR / "tests"))  # tests/independent: a folder, not an installed package

from independent.families import independent_leak, sealed_test  # noqa: E402 (needs the path above)
from independent.physics import Physics  # noqa: E402

from pamkit.diagnose import diagnose, verdict  # noqa: E402
from pamkit.diagnose.campaign import campaign_of_series  # noqa: E402
from pamkit.diagnose.report import write  # noqa: E402
from pamkit.effects import catalog  # noqa: E402
from pamkit.io.experiment import ExperimentError, load_tests  # noqa: E402

HEAT_TIME_CONSTANT_S = 3.0  # one muscle, one wall: the same heat exchange in every test


@pytest.fixture(scope="module")
def diagnosed(tmp_path_factory):
    """Three sealed tests of one muscle with heat exchange (different inflation pressures, speeds
    and cycle counts: seeds 1-3 of the families' protocol), and one test with a leak instead."""
    root = tmp_path_factory.mktemp("campaign")
    physics = Physics(heat_time_constant_s=HEAT_TIME_CONSTANT_S)
    heat = [sealed_test(seed, root / f"heat_{seed}", physics=physics).experiment for seed in (1, 2, 3)]
    leak = independent_leak(4, root / "leak_4").experiment
    return {path: diagnose(path, threads=2) for path in [*heat, leak]}, heat, leak


def test_an_effect_every_test_shares_carries_from_the_others_to_each(diagnosed, tmp_path):
    single, heat, _ = diagnosed
    c = campaign_of_series([single[path] for path in heat], catalog())
    write(c, tmp_path / "campaign.json", tmp_path / "campaign.png")
    report = json.loads((tmp_path / "campaign.json").read_text())
    assert report["held_out"] == "test" and len(report["per_test"]) == 3
    assert (tmp_path / "campaign.png").stat().st_size > 0
    assert c.cause == "heat_transfer", verdict(c)
    carried = report["carried"]["heat_transfer"]
    assert [x["test"] for x in carried] == c.tests and all(x["carries"] for x in carried)
    # Fitted on the other two tests, the time constant is the hidden one within a factor of two
    # (the fits of one test alone span 0.5-10 s in the families' benchmark).
    for x in carried:
        assert 0.5 * HEAT_TIME_CONSTANT_S < x["params"]["time_constant_s"] < 2.0 * HEAT_TIME_CONSTANT_S, verdict(c)
        assert x["gain"] >= 0.03 and x["gain_ci95"][0] > 0.0


def test_tests_that_disagree_leave_the_campaign_unexplained(diagnosed):
    single, heat, leak = diagnosed
    c = campaign_of_series([single[heat[0]], single[leak]], catalog())
    assert c.cause == "unexplained", verdict(c)
    assert "no cause holds across the campaign" in c.reason


def test_a_campaign_toml_shares_its_sections_with_its_tests(tmp_path):
    (tmp_path / "run.csv").write_text("time_s,elongation_m,force_N\n0,0,1\n1,0.001,2\n")
    test = '[test]\ninflation_pressure_kPa = 200.0\nambient_temperature_C = 22.0\ndata = "run.csv"\n'
    (tmp_path / "a.toml").write_text(test)
    (tmp_path / "b.toml").write_text(test.replace("200.0", "150.0"))
    campaign = tmp_path / "campaign.toml"
    campaign.write_text('[campaign]\ntests = ["a.toml", "b.toml"]\n\n[muscle]\nlength_m = 0.2\n')
    a, b = load_tests(campaign)
    assert a.build.length_m == b.build.length_m == 0.2
    assert (a.inflation_pressure_kPa, b.inflation_pressure_kPa) == (200.0, 150.0)
    (tmp_path / "b.toml").write_text("[muscle]\nlength_m = 0.3\n" + test)
    with pytest.raises(ExperimentError, match=r"b.toml: gives \[muscle\], which its campaign shares"):
        load_tests(campaign)
    campaign.write_text('[campaign]\ntests = "a.toml"\n')
    with pytest.raises(ExperimentError, match="must be a list of experiment files"):
        load_tests(campaign)
