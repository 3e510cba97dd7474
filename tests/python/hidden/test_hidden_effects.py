"""Hidden effects: `pamkit synth` writes a dataset with
one catalog effect switched on (random realistic strength, random protocol, instrument noise
and quantisation), and `pamkit diagnose`, given only the TOML and CSV, must name it; datasets
with no effect must come back "none". A fixed set of seeds; bench/bench_diagnose.py sweeps more."""

import json

import pytest

from pamkit.synth.dataset import hideable_effects

SEEDS = (11, 12)
NULL_SEEDS = (21, 22, 23)
CASES = [(name, seed) for name in hideable_effects() for seed in SEEDS] + [("none", seed) for seed in NULL_SEEDS]


@pytest.mark.parametrize("effect, seed", CASES, ids=[f"{name}-{seed}" for name, seed in CASES])
def test_diagnosis_names_the_hidden_effect(effect, seed, tmp_path, run_pamkit):
    dataset = tmp_path / "dataset"
    made = run_pamkit("synth", "--effect", effect, "--seed", seed, "-o", dataset)
    assert made.returncode == 0, made.stderr
    # Diagnosis sees a copy of the experiment only: the manifest stays behind.
    seen = tmp_path / "seen"
    seen.mkdir()
    for name in ("experiment.toml", "experiment.csv"):
        (seen / name).write_bytes((dataset / name).read_bytes())
    report_path = tmp_path / "report.json"
    done = run_pamkit("diagnose", seen / "experiment.toml", "--json", report_path, "--quiet")
    assert done.returncode == 0, done.stderr
    report = json.loads(report_path.read_text())
    truth = json.loads((dataset / "manifest.json").read_text())["effect"]
    assert report["cause"] == truth["name"], report["verdict"]
    if effect == "none":
        return
    # The cause comes with a significant held-out gain on some channel.
    assert any(lo > 0 for lo, _ in report["gain_ci95"].values()), report["gain_ci95"]
    if "channel" in truth["options"]:
        assert report["extended"]["params"]["channel"] == truth["options"]["channel"]
