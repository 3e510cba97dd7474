#!/usr/bin/env python3
"""Times one sweep three ways (and a control), side by side in one run: a plain loop in this process
(pamkit.sweep.run_in_process), and `pamkit.sweep.sweep` on a Dask LocalCluster of 1 and of 2
worker processes (one thread each, journal and Parquet written as the command does).

The sweep: a Latin hypercube (seed 1) of --runs runs over inflation pressure (100-300 kPa) and
braid angle (27-35 deg, around PAM 2's own 31.2) of the thesis's PAM 2 test at 207 kPa, 80 %
(table C.2), cut to its first --cycles cycles (1 by default: 372 samples, 1-2 ms a run).

It prints ratios (no absolute pass/fail; the times are in --json):
  dask 1 worker / loop     the cost of going through Dask with no parallelism
  overhead per run         (dask 1 worker - loop) / runs: what Dask, the journal and the table add to a run
  speed-up 1 -> 2 workers  dask 1 worker / dask 2 workers
  loop / dask 2 workers    what a 2-core machine gains over the plain loop
  control                  loop / the same chunks on 2 plain processes (concurrent.futures): what
                           the second core gives at the moment, without Dask; and dask 2 workers /
                           those 2 processes, Dask's own cost at 2 workers
Cluster start-up (workers spawned, pamkit imported, the base experiment read on each worker) is
timed apart and left out of the ratios: a command pays it once. Each time is the best of --rounds,
the three ways taking turns. The rows of the three ways are checked equal (Dask changes no number).

Usage:
  PYTHONPATH=build/python .venv/bin/python bench/bench_sweep.py [--runs 1000] [--cycles 1] [--rounds 3] [--json OUT]
"""

from __future__ import annotations

import argparse
import contextlib
import json
import os
import sys
import tempfile
import time
from concurrent.futures import ProcessPoolExecutor
from functools import partial
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
try:
    import pamkit  # noqa: F401
except ImportError:  # convenience: the usual build directory
    sys.path.insert(0, str(ROOT / "build" / "python"))

from pamkit.cluster import chunked, client  # noqa: E402
from pamkit.sweep import load_spec, prepare_base, run_chunk, run_in_process, sweep  # noqa: E402

SPEC = """[sweep]
experiment = "{base}"
cycles = {cycles}
design = "latin_hypercube"
samples = {runs}
seed = 1

[parameters]
inflation_pressure_kPa = {{ range = [100, 300] }}
braid_angle_deg = {{ range = [27, 35] }}
"""


def best(times: dict, key: str, seconds: float) -> None:
    times[key] = min(times.get(key, seconds), seconds)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--runs", type=int, default=1000)
    parser.add_argument("--cycles", type=int, default=1)
    parser.add_argument("--rounds", type=int, default=3, help="each way's time is the best of this many")
    parser.add_argument("--json", help="write every time here")
    arguments = parser.parse_args(argv)

    with tempfile.TemporaryDirectory() as scratch:
        scratch = Path(scratch)
        base = ROOT / "data" / "experiments" / "thesis" / "pam2_207kPa_80pct.toml"
        spec_path = scratch / "spec.toml"
        spec_path.write_text(SPEC.format(base=base.as_posix(), cycles=arguments.cycles, runs=arguments.runs))
        spec = load_spec(spec_path)

        times, clusters = {}, {}
        with contextlib.ExitStack() as stack:
            for workers in (1, 2):
                started = time.perf_counter()
                clusters[workers] = stack.enter_context(client(workers=workers))
                clusters[workers].wait_for_workers(workers)
                clusters[workers].run(prepare_base, spec)  # pamkit imported, the base read
                times[f"startup_{workers}_s"] = time.perf_counter() - started
            # The control: the same chunks on 2 plain processes, what the machine's second core
            # gives at this moment without Dask (other work on a shared machine takes from it).
            pool = stack.enter_context(ProcessPoolExecutor(2, initializer=prepare_base, initargs=(spec,)))
            list(pool.map(prepare_base, [spec] * 2))  # the processes started
            chunks = chunked(range(len(spec.runs)), 2)
            # The four ways take turns, best of --rounds each: load from other processes on
            # the machine hits all of them alike.
            reference = None
            for round_ in range(arguments.rounds):
                started = time.perf_counter()
                reference = run_in_process(spec)
                best(times, "loop_s", time.perf_counter() - started)
                started = time.perf_counter()
                pooled = [row for rows in pool.map(partial(run_chunk, spec), chunks) for row in rows]
                best(times, "pool_2_s", time.perf_counter() - started)
                if json.dumps(pooled) != json.dumps(reference):
                    raise SystemExit("the rows of the process pool differ from the loop's")
                for workers, connected in clusters.items():
                    started = time.perf_counter()
                    rows = sweep(spec, scratch / f"dask{workers}_{round_}.parquet", connected)
                    best(times, f"dask_{workers}_s", time.perf_counter() - started)
                    if json.dumps(rows) != json.dumps(reference):  # NaN-safe: a failed run's metrics
                        raise SystemExit(f"the rows of {workers} Dask worker(s) differ from the loop's")

    runs = arguments.runs
    failed = sum(1 for row in reference if row["error"])
    ratio = {
        "dask 1 worker / loop": times["dask_1_s"] / times["loop_s"],
        "overhead per run (1 worker), ms": 1e3 * (times["dask_1_s"] - times["loop_s"]) / runs,
        "speed-up 1 -> 2 workers": times["dask_1_s"] / times["dask_2_s"],
        "loop / dask 2 workers": times["loop_s"] / times["dask_2_s"],
        "control: loop / 2 plain processes": times["loop_s"] / times["pool_2_s"],
        "dask 2 workers / 2 plain processes": times["dask_2_s"] / times["pool_2_s"],
    }
    what = f"{arguments.cycles} cycle(s) of PAM 2 at 207 kPa; {failed} failed"
    print(f"sweep of {runs} runs ({what}); {os.cpu_count()} cores")
    print(f"  {'loop, per run, ms':34} {1e3 * times['loop_s'] / runs:8.2f}")
    for name, value in ratio.items():
        print(f"  {name:34} {value:8.2f}")
    startup = f"{times['startup_1_s']:.2f} s, {times['startup_2_s']:.2f} s"
    print(f"  {'cluster start-up (1, 2 workers)':34} {startup} (not in the ratios)")
    if arguments.json:
        Path(arguments.json).write_text(json.dumps({"runs": runs, "cycles": arguments.cycles, **times}, indent=2))
    return 0


if __name__ == "__main__":
    sys.exit(main())
