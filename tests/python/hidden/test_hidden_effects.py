"""Hidden effects, as rates over seeds: `pamkit synth` writes datasets with one catalog effect
switched on (random realistic strength, random protocol, instrument noise and quantisation), and
the diagnosis, given only the TOML and CSV, must name it — in two worlds:

- pamkit's own: the data come from the very model the file declares;
- near the model: the data come from a muscle that differs from its declared build the way a real
  one does (pamkit.synth.mismatch: a braid wound 2-5 % otherwise, another wall thickness or end
  cone, a sharper friction), leaving the calibrated baseline 1-5 noise sigmas off on a null.

Each world is the same contiguous block of seeds, the effects in turn (as bench/bench_diagnose.py
draws them: its seeds 1000-1035, 33 effects and 3 nulls), and is judged as a rate: so many named right, no wrong name,
nulls within their rule. A test that picks its seeds would pass a diagnosis that names nothing
elsewhere; a rate fails it. bench/bench_diagnose.py sweeps more seeds (`--mismatch` for the second
world); the near-model world of another team's implementation is tests/python/hidden/test_near_model.py.
"""

import json
from concurrent.futures import ThreadPoolExecutor

import numpy as np
import pytest

from pamkit.diagnosis import diagnose, to_json
from pamkit.io.experiment import load_experiment
from pamkit.synth.dataset import hideable_effects, synthesize
from pamkit.synth.mismatch import draw_mismatch

FIRST_SEED = 1000
NAMES = ["none", *hideable_effects()]
DATASETS = 3 * len(NAMES)  # three of each effect and three nulls


def named(report: dict) -> set[str]:
    return {c["effect"].split(":")[0] for c in report["causes"]}


def run_world(tmp_path_factory, mismatch: bool) -> list[dict]:
    """Every dataset of a world, diagnosed from its files: truth, names, the report's cause."""
    folder = tmp_path_factory.mktemp("near" if mismatch else "own")

    def one(i: int) -> dict:
        seed, effect = FIRST_SEED + i, NAMES[i % len(NAMES)]
        true_muscle = draw_mismatch(np.random.default_rng([seed, 7])) if mismatch else None
        files = synthesize(effect, seed, folder / str(i), true_muscle=true_muscle)
        truth = json.loads(files.manifest.read_text())["effect"]["name"]
        report = to_json(diagnose(load_experiment(files.experiment), threads=1))
        rmse, noise = report["baseline"]["rmse"], report["evidence"]["noise"]
        return {
            "seed": seed,
            "truth": truth,
            "named": named(report),
            "cause": report["cause"],
            "remainder": report["remainder"],
            "baseline_over_noise": max(rmse[c] / noise[c] for c in noise),
            "verdict": report["verdict"],
        }

    with ThreadPoolExecutor(max_workers=2) as pool:
        return list(pool.map(one, range(DATASETS)))


@pytest.fixture(scope="module")
def own_world(tmp_path_factory):
    return run_world(tmp_path_factory, mismatch=False)


@pytest.fixture(scope="module")
def near_world(tmp_path_factory):
    return run_world(tmp_path_factory, mismatch=True)


def summary(rows: list[dict]) -> str:
    return "\n".join(f"  {r['seed']} {r['truth']:<24} -> {sorted(r['named']) or r['cause']}" for r in rows)


def effects(rows):
    return [r for r in rows if r["truth"] != "none"]


def nulls(rows):
    return [r for r in rows if r["truth"] == "none"]


def test_own_world_names_the_hidden_effect(own_world):
    # Measured: 30 of these 33 (bench_diagnose's seeds 1000-1035; the misses are a fibre
    # compliance within the noise and two pressure offsets a wind within its 5 % explains as
    # well). The floor: that rate less two binomial standard deviations
    # (33 * 0.91 - 2 sqrt(33 * 0.91 * 0.09) = 26).
    rows = effects(own_world)
    right = sum(r["truth"] in r["named"] for r in rows)
    assert right >= 26, f"{right} of {len(rows)} named right:\n{summary(rows)}"


def test_own_world_never_names_a_wrong_cause(own_world):
    wrong = [r for r in own_world if r["named"] - {r["truth"]}]
    assert not wrong, f"wrong names:\n{summary(wrong)}"


def test_own_world_nulls_come_back_none(own_world):
    # The baseline is the truth there: `none`, the calibrated model within NONE_WITHIN_NOISE of
    # the noise on every channel (diagnosis/significance.py; tests/python/diagnose/test_decide.py pins the factor).
    rows = nulls(own_world)
    assert all(r["cause"] == "none" for r in rows), summary(rows)


def test_near_world_names_the_hidden_effect(near_world):
    # Measured: 30 of these 33 (bench_diagnose --mismatch's seeds 1000-1035; 28 before a play
    # shorter than a sample's travel was modelled as it acts, 25 when a cause had to survive the
    # braid's wind freed after it was named, 21 before). The floor: that rate less two binomial
    # standard deviations (33 * 0.91 - 2 sqrt(33 * 0.91 * 0.09) = 26).
    rows = effects(near_world)
    right = sum(r["truth"] in r["named"] for r in rows)
    assert right >= 26, f"{right} of {len(rows)} named right:\n{summary(rows)}"


def test_near_world_wrong_names_stay_rare(near_world):
    # The target: at most 5 % wrong names overall; of 36 datasets, at most 1.8: 2 would be a miss.
    wrong = [r for r in near_world if r["named"] - {r["truth"]}]
    assert len(wrong) <= 1, f"wrong names:\n{summary(wrong)}"


def test_near_world_nulls_name_nothing(near_world):
    # A null of a muscle that is not its declared build names no cause: `none` within the noise,
    # or `unexplained` with what is left as a remainder (its channels above the noise).
    for r in nulls(near_world):
        assert not r["named"], summary([r])
        if r["cause"] == "unexplained":
            assert r["remainder"] and r["remainder"]["channels"], r["verdict"]
