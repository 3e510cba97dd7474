"""Every Python benchmark in bench/ runs to its end on this build, at its smallest size: a bench is
run by hand, seldom, and a change elsewhere (a file format, an API) can break it unseen, as the
thesis's files listing end_zone_m once broke bench_campaign.py. Each run must exit 0 and print
the line its README section reads its result from. Timings are not checked (benchmarks, not timed
tests). Left out: bench_logger.py, whose firmware variants are a target of their own
(bench_logger_firmware, built on demand), and `bench_sweep.py --jax`, which needs JAX installed
apart from the project (bench/requirements-jax.txt). `decision_diff.py`, which compares two
benches' files, is run on files made here."""

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest
from conftest import SOURCE_DIR

BENCH = SOURCE_DIR / "bench"
BUILD = Path(os.environ.get("PAMKIT_BUILD_DIR", SOURCE_DIR / "build")).resolve()

# (script, its smallest arguments, a line its output must hold)
SMALLEST = [
    ("bench_diagnose.py", ["--datasets", "2", "--threads", "1"], "nulls' baseline"),
    ("bench_families.py", ["--per-family", "1", "--families", "independent_leak"], "independent_leak"),
    ("bench_near_model.py", ["--seeds", "1", "--nulls", "1", "--families", "leak", "--strengths", "strong"], "wrong"),
    ("bench_campaign.py", ["--campaigns", "PAM 1", "--repeats", "1"], "PAM 1: heat_transfer"),
    # a tie between compliant fibres and a dead volume whose report asks for another inflation
    (
        "bench_follow_up.py",
        [
            "--seeds",
            "1",
            "--first-seed",
            "2",
            "--nulls",
            "0",
            "--families",
            "fiber_compliance",
            "--strengths",
            "strong",
        ],
        "1 of those run",
    ),
    ("bench_import.py", ["--rounds", "1"], "import pamkit.diagnosis / import scipy.optimize"),
    ("bench_isotonic.py", ["--rounds", "1", "--points", "5"], "largest difference between the two"),
    ("bench_jacobians.py", ["--datasets", "1"], "the same verdict"),
    ("bench_long_test.py", ["--rows", "12000", "--rate-hz", "100"], "total (load, diagnosis, report)"),
    ("bench_shape_table.py", ["--rounds", "1"], "channels with and without the table"),
    ("bench_sweep.py", ["--runs", "20", "--rounds", "1"], "loop / dask 2 workers"),
    ("bench_logger_kill.py", ["--kills", "2"], "whole-line check"),
]


def run_bench(script: str, arguments: list[str], tmp_path: Path) -> subprocess.CompletedProcess:
    environment = dict(os.environ, MPLBACKEND="Agg")
    return subprocess.run(
        [sys.executable, str(BENCH / script), *arguments],
        cwd=tmp_path,
        env=environment,
        capture_output=True,
        text=True,
        timeout=600,
    )


@pytest.mark.parametrize("script, arguments, expected", SMALLEST, ids=[s[0] for s in SMALLEST])
def test_a_bench_runs_to_its_end_at_its_smallest_size(script, arguments, expected, tmp_path):
    result = run_bench(script, arguments, tmp_path)
    assert result.returncode == 0, result.stderr[-3000:]
    assert expected in result.stdout, result.stdout[-3000:]


def test_the_decision_diff_lists_each_changed_decision_of_either_bench_format(tmp_path):
    # bench_near_model's and bench_families' files hold {"rows": [...]} keyed by family, strength
    # and seed; bench_diagnose's a list keyed by the hidden effect and seed. One decision changed,
    # one dataset only in the second run: two changes of three datasets; the same file: none.
    near = [
        {
            "family": "dead_volume+load_cell",
            "strength": "medium",
            "seed": 5,
            "outcome": "wrong",
            "named": ["fiber_compliance"],
        },
        {"family": "null", "strength": None, "seed": 1, "outcome": "honest", "named": []},
    ]
    after = [dict(near[0], outcome="right", named=["load_cell", "dead_volume"]), near[1]]
    after.append({"family": "leak", "strength": "strong", "seed": 1, "outcome": "right", "named": ["leak"]})
    (tmp_path / "before.json").write_text(json.dumps({"rows": near}))
    (tmp_path / "after.json").write_text(json.dumps({"rows": after}))
    own = [{"truth": "leak", "seed": 1000, "cause": "leak", "named": ["leak"]}]
    (tmp_path / "own.json").write_text(json.dumps(own))

    def diff(*arguments):
        return subprocess.run(
            [sys.executable, str(BENCH / "decision_diff.py"), *arguments], capture_output=True, text=True, cwd=tmp_path
        )

    changed = diff("before.json", "after.json", "--fail-on-change")
    assert changed.returncode == 1, changed.stderr
    assert "dead_volume+load_cell medium seed 5: wrong [fiber_compliance] -> right [dead_volume, load_cell]" in (
        changed.stdout
    )
    assert "leak strong seed 1: (not in this run) -> right [leak]" in changed.stdout
    assert "2 of 3 decisions changed" in changed.stdout
    same = diff("own.json", "own.json", "--fail-on-change")
    assert same.returncode == 0 and "0 of 1 decisions changed" in same.stdout, same.stdout + same.stderr


def test_every_python_bench_is_run_here_or_said_why_not():
    run_here = {script for script, _, _ in SMALLEST} | {"bench_simulate.py", "decision_diff.py"}
    left_out = {"bench_logger.py"}  # the module docstring says why
    references = {"jax_reference.py", "scipy_reference.py"}  # imported by the benches, not run
    assert {p.name for p in BENCH.glob("*.py")} == run_here | left_out | references


def test_the_simulation_bench_runs_beside_scipy(tmp_path):
    exe = BUILD / "bench" / "pamkit_bench_simulate"
    # The README's set-up builds the benchmark programs (PAMKIT_BUILD_BENCH is on in a full build),
    # so this runs there and in CI; a build configured without them skips, saying so (-rs).
    if not exe.exists():
        pytest.skip(f"{exe} is not built (configure with -DPAMKIT_BUILD_BENCH=ON)")
    arguments = ["--exe", str(exe), "--rounds", "1", "--repeats", "1", "--cycles", "1"]
    result = run_bench("bench_simulate.py", arguments, tmp_path)
    assert result.returncode == 0, result.stderr[-3000:]
    assert "SciPy LSODA" in result.stdout, result.stdout[-3000:]
