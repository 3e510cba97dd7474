"""The same input gives the same report: `pamkit diagnose` run on one dataset with 1
thread and with 2 (fits in parallel and the BLAS's own threads) writes identical JSON, timing
aside. Identical means byte for byte: every fit, interval and decision, so no tolerance. On
another CPU the numbers may move in their last digits, and the decision may not."""

import json
import os
import subprocess
import sys

import numpy as np
import pytest

from pamkit.diagnosis.engine import data_seed
from pamkit.diagnosis.series.kinds import build_problem
from pamkit.io.experiment import load_experiment
from pamkit.synth.dataset import synthesize

# The bundled example (three channels, a cause named, pairs tried) and a synthetic dataset with no
# effect (the hidden-effect tests' first null seed: nothing named). The thesis tests in
# data/experiments/thesis hold protocols only, nothing measured to diagnose.
DATASETS = ["example", "synth-none-21"]
TIMING_KEYS = {"timing_s"}


def diagnose_with_threads(experiment, threads, report_path, machine=None):
    """The report of `pamkit diagnose` in a fresh process, timing left out; `machine` adds to its
    environment."""
    environment = os.environ.copy()
    for variable in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
        environment[variable] = str(threads)
    environment.update(machine or {})
    done = subprocess.run(
        [
            sys.executable,
            "-m",
            "pamkit",
            "diagnose",
            str(experiment),
            "--threads",
            str(threads),
            "--json",
            str(report_path),
            "--quiet",
        ],
        capture_output=True,
        text=True,
        env=environment,
        timeout=300,
    )
    assert done.returncode == 0, done.stderr
    report = json.loads(report_path.read_text())
    assert TIMING_KEYS <= set(report)  # the keys left out below exist: a rename would not hide a difference
    return {key: value for key, value in report.items() if key not in TIMING_KEYS}


def experiment_path(dataset, thesis_dir, directory):
    if dataset == "example":
        return thesis_dir.parent / "example" / "experiment.toml"
    _, effect, seed = dataset.split("-")
    return synthesize(effect, int(seed), directory).experiment


@pytest.mark.parametrize("dataset", DATASETS)
def test_one_and_two_threads_give_the_same_report(dataset, thesis_dir, tmp_path):
    experiment = experiment_path(dataset, thesis_dir, tmp_path / "data")
    one = diagnose_with_threads(experiment, 1, tmp_path / "one.json")
    two = diagnose_with_threads(experiment, 2, tmp_path / "two.json")
    assert one["verdict"]  # the verdict is compared with the rest
    # Compared as canonical JSON text: exact, and NaN (if a report holds one) equals itself.
    assert json.dumps(one, sort_keys=True) == json.dumps(two, sort_keys=True)


def oldest_cpu() -> dict[str, str]:
    """The environment of a machine with none of this one's vector units beyond x86-64's
    baseline, as far as a process can pretend: OpenBLAS's oldest kernels (Prescott: SSE3), none of
    numpy's SIMD loops above the baseline it was built for, and glibc's maths functions without
    AVX2 and FMA (its fused variants of exp, log and atan2 serve the model's C++). Each orders
    and rounds sums differently, as another CPU does."""
    try:
        from numpy._core import _multiarray_umath as umath
    except ImportError:  # numpy 1
        from numpy.core import _multiarray_umath as umath

    above_baseline = [feature for feature in umath.__cpu_dispatch__ if umath.__cpu_features__.get(feature)]
    return {
        "OPENBLAS_CORETYPE": "Prescott",
        "NPY_DISABLE_CPU_FEATURES": " ".join(above_baseline),
        "GLIBC_TUNABLES": "glibc.cpu.hwcaps=-AVX2,-FMA,-AVX512F",
    }


def to_six_digits(value):
    """`value` with every number in it to six significant digits: a fit stops far above a CPU's
    last digits (candidates.JOINT_FTOL), so what it decides holds to six."""
    if isinstance(value, float):
        return float(f"{value:.5e}")
    if isinstance(value, dict):
        return {key: to_six_digits(item) for key, item in value.items()}
    if isinstance(value, (list, tuple)):
        return [to_six_digits(item) for item in value]
    return value


def decision_of(report: dict) -> dict:
    """What a diagnosis decides, and the sentence that says it: the causes with their fitted
    values, what is left, what was rejected or told apart."""
    decision = report["decision"]
    return to_six_digits(
        {
            "cause": report["cause"],
            "causes": [(c["effect"], c["params"]) for c in report["causes"]],
            "remainder": report["remainder"] and sorted(report["remainder"]["channels"]),
            "left_above_noise": decision["left_above_noise"],
            "rejected": decision["rejected"],
            "untied_from": decision["untied_from"],
            "verdict": report["verdict"],
        }
    )


@pytest.mark.parametrize("dataset", DATASETS)
def test_the_oldest_cpu_takes_the_same_decision(dataset, thesis_dir, tmp_path):
    # On the bundled example these settings move fitted values by up to 2e-10 of themselves (a
    # screened candidate's time constant, on a flat cost, by 2e-4) and change no decision; the
    # decision benches give the same decisions on a machine held to AVX2 (docs/validation.md).
    experiment = experiment_path(dataset, thesis_dir, tmp_path / "data")
    here = diagnose_with_threads(experiment, 2, tmp_path / "here.json")
    oldest = diagnose_with_threads(experiment, 2, tmp_path / "oldest.json", oldest_cpu())
    assert decision_of(here) == decision_of(oldest)


def test_the_default_seed_comes_from_the_measured_data(thesis_dir):
    experiment = thesis_dir.parent / "example" / "experiment.toml"
    problem = build_problem(load_experiment(experiment))
    assert data_seed(problem) == data_seed(build_problem(load_experiment(experiment)))  # loaded again
    channel = problem.channels[0]
    changed = problem.measured[channel].copy()
    changed[len(changed) // 2] = np.nextafter(changed[len(changed) // 2], np.inf)  # one sample, one ulp
    seed = data_seed(problem)
    problem.measured[channel] = changed
    assert data_seed(problem) != seed
