#!/usr/bin/env python3
"""Times one sweep three ways (and a control), side by side in one run: in this process
(pamkit.sweep.run_in_process: the runs as C++ batches on one thread), and `pamkit.sweep.sweep` on
a Dask LocalCluster of 1 and of 2 worker processes (one thread each, a batch per task, journal and
Parquet written as the command does).

The sweep: a Latin hypercube (seed 1) of --runs runs over inflation pressure (100-300 kPa) and
braid angle (27-35 deg, around PAM 2's own 31.2) of the thesis's PAM 2 test at 207 kPa, 80 %
(table C.2), cut to its first --cycles cycles (1 by default: 372 samples, 1-2 ms a run).

It prints ratios (no absolute pass/fail; the times are in --json):
  dask 1 worker / loop     the cost of going through Dask with no parallelism ("loop": run_in_process)
  overhead per run         (dask 1 worker - loop) / runs: what Dask, the journal and the table add to a run
  speed-up 1 -> 2 workers  dask 1 worker / dask 2 workers
  loop / dask 2 workers    what a 2-core machine gains over the plain loop
  control                  loop / the same chunks on 2 plain processes (concurrent.futures): what
                           the second core gives at the moment, without Dask; and dask 2 workers /
                           those 2 processes, Dask's own cost at 2 workers
Cluster start-up (workers spawned, pamkit imported, the base experiment read on each worker) is
timed apart and left out of the ratios: a command pays it once.

With --jax (needs bench/requirements-jax.txt, e.g. in .venv-bench), the same runs also go through
JAX + diffrax (Tsit5, jit, vmap over the runs: bench/jax_reference.py, the same equations written
apart from pamkit), side by side with pamkit on each run's model:
  CPU per run             process CPU time / runs (every thread counted): pamkit's loop of
                          Simulator.run (one run at a time from Python), pamkit's Simulator.run_batch
                          of the same models on one thread, the sweep's own rows
                          (run_in_process: the ParameterSets batch and the rows built from it;
                          without --jax-tau, when the sweep and the side-by-side run the same gas),
                          and JAX's one vectorised call (its compilation timed apart)
  JAX / pamkit            the ratio of those CPU times: below 1, JAX spends less CPU per run
  agreement               max |F_jax - F_pamkit| / max |F_pamkit| over every run (pamkit by bdf, its
                          default, and by auto, the stiffness test's pick), all at rtol 1e-8
                          (pamkit's default): at most 1e-6, the bound bench_simulate.py holds pamkit
                          to against SciPy Each time is the best of --rounds,
the three ways taking turns. The rows of the three ways are checked equal (Dask changes no number).

Usage:
  PYTHONPATH=build/python .venv/bin/python bench/bench_sweep.py [--runs 1000] [--cycles 1] [--rounds 3] [--json OUT]
  PYTHONPATH=build/python .venv-bench/bin/python bench/bench_sweep.py --jax   # JAX side by side
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

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
try:
    import pamkit
except ImportError:  # convenience: the usual build directory
    sys.path.insert(0, str(ROOT / "build" / "python"))

import pamkit  # noqa: E402
from pamkit.cluster import chunked, client  # noqa: E402
from pamkit.simulation import muscle_params  # noqa: E402
from pamkit.sweep import (  # noqa: E402
    base_experiment,
    load_spec,
    prepare_base,
    run_chunk,
    run_in_process,
    sweep,
    with_parameters,
)

AGREEMENT = 1e-6  # max |F_jax - F_pamkit| / max |F_pamkit|: bench_simulate.py's bound against SciPy

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


def jax_side_by_side(spec, rows: list[dict], repeats: int, tau_s: float | None) -> dict:
    """Times the sweep's runs that succeeded with pamkit's Simulator.run, one after the other, and
    with JAX + diffrax vectorised over all of them; checks they agree. CPU seconds per run. With
    `tau_s`, both sides give the gas a heat exchange with the wall in tau_s instead of the base's
    process (the thesis's tests are isothermal: their temperature ODE does nothing)."""
    sys.path.insert(0, str(Path(__file__).resolve().parent))
    import jax
    from jax_reference import JaxMuscle

    base = base_experiment(spec.experiment, spec.cycles)
    experiments = [with_parameters(base, spec.parameters(row["run"])) for row in rows if row["error"] is None]
    thesis = pamkit.BladderLaw.thesis()
    if base.bladder.form != thesis.form or (
        list(base.bladder.longitudinal_Pa) != list(thesis.longitudinal_Pa)
        or list(base.bladder.hoop_Pa) != list(thesis.hoop_Pa)
    ):
        raise SystemExit("--jax: jax_reference.py knows the thesis's bladder law only")
    gas = {**base.gas_params.to_dict(), "process": pamkit.GasProcess(base.gas_params.process).name}
    if tau_s is not None:
        gas.update(process="heat_transfer", heat_transfer_time_constant_s=tau_s)
    muscle = JaxMuscle(
        base.build.to_dict(), base.friction.to_dict(), gas, base.initial_length_m, base.time_s, base.elongation_m
    )
    pressures = np.array([e.inflation_gauge_pressure_Pa for e in experiments])
    revolutions = np.array([e.build.fiber_revolutions for e in experiments])

    # pamkit: each run's model along the same crosshead, the sweep's own configuration.
    trajectory = pamkit.ElongationTrajectory(base.time_s, base.elongation_m)
    rows = np.arange(len(base.time_s))
    simulators = {
        name: pamkit.Simulator(pamkit.SimulatorConfig(method=getattr(pamkit.IntegrationMethod, name)))
        for name in ("bdf", "auto")  # the default, and the stiffness test's pick
    }
    models = []
    for e, p in zip(experiments, pressures):
        params = muscle_params(e)
        if tau_s is not None:
            params.gas.process = pamkit.GasProcess.heat_transfer
            params.gas.heat_transfer_time_constant_s = tau_s
        initial = pamkit.InitialState(length_m=base.initial_length_m, gauge_pressure_Pa=p)
        models.append(pamkit.MuscleModel(params, initial))
    pamkit_cpu, forces = dict.fromkeys(simulators, float("inf")), {}
    batch_cpu = dict.fromkeys(simulators, float("inf"))
    sweep_cpu = float("inf")
    for _ in range(repeats):
        for name, simulator in simulators.items():
            started = time.process_time()
            forces[name] = [np.asarray(simulator.run(model, trajectory).force_N) for model in models]
            pamkit_cpu[name] = min(pamkit_cpu[name], time.process_time() - started)
            started = time.process_time()
            batched = simulator.run_batch(models, trajectory, channels=["force_N"], rows=rows, threads=1)
            batch_cpu[name] = min(batch_cpu[name], time.process_time() - started)
            if not np.array_equal(batched.values["force_N"], np.array(forces[name])):
                raise SystemExit(f"run_batch ({name}) differs from Simulator.run")
        if tau_s is None:
            started = time.process_time()
            run_in_process(spec)
            sweep_cpu = min(sweep_cpu, time.process_time() - started)
    auto_ran = simulators["auto"].run(models[0], trajectory).statistics.method.name

    batch = muscle.batch(rtol=pamkit.SimulatorConfig().relative_tolerance)
    started = time.perf_counter()
    jax_force, _ = jax.block_until_ready(batch(pressures, revolutions))  # compiles
    compile_s = time.perf_counter() - started
    jax_cpu, jax_wall = float("inf"), float("inf")
    for _ in range(repeats):
        started, wall = time.process_time(), time.perf_counter()
        jax_force, _ = jax.block_until_ready(batch(pressures, revolutions))
        jax_cpu, jax_wall = min(jax_cpu, time.process_time() - started), min(jax_wall, time.perf_counter() - wall)
    jax_force = np.asarray(jax_force)
    agreement = max(
        float(np.max(np.abs(jax_force[i] - pamkit_force[i])) / np.max(np.abs(pamkit_force[i])))
        for pamkit_force in forces.values()
        for i in range(len(pamkit_force))
    )
    runs = len(experiments)
    return {
        "jax_runs": runs,
        "jax_version": jax.__version__,
        "pamkit_cpu_per_run_s": pamkit_cpu["bdf"] / runs,
        "pamkit_auto_cpu_per_run_s": pamkit_cpu["auto"] / runs,
        "pamkit_batch_cpu_per_run_s": batch_cpu["bdf"] / runs,
        "pamkit_batch_auto_cpu_per_run_s": batch_cpu["auto"] / runs,
        "sweep_cpu_per_run_s": sweep_cpu / len(spec.runs),
        "pamkit_auto_ran": auto_ran,
        "jax_cpu_per_run_s": jax_cpu / runs,
        "jax_wall_per_run_s": jax_wall / runs,
        "jax_compile_s": compile_s,
        "jax_agreement": agreement,
    }


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--runs", type=int, default=1000)
    parser.add_argument("--cycles", type=int, default=1)
    parser.add_argument("--rounds", type=int, default=3, help="each way's time is the best of this many")
    parser.add_argument("--json", help="write every time here")
    parser.add_argument("--jax", action="store_true", help="time JAX + diffrax on the same runs, side by side")
    parser.add_argument(
        "--jax-tau", type=float, help="with --jax: the gas exchanges heat with the wall in this time [s] on both sides"
    )
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
    if arguments.jax:
        times.update(jax_side_by_side(spec, reference, arguments.rounds, arguments.jax_tau))
        gas = "the base's gas" if arguments.jax_tau is None else f"heat exchange in {arguments.jax_tau:g} s"
        print(
            f"side by side with JAX {times['jax_version']} + diffrax (Tsit5, jit, vmap over {times['jax_runs']} runs; "
            f"{gas}), CPU per run, ms, and JAX's over it:"
        )
        auto = times["pamkit_auto_ran"]
        ways = {
            "pamkit Simulator.run, one at a time": "pamkit_cpu_per_run_s",
            f"pamkit Simulator.run, method=auto ({auto})": "pamkit_auto_cpu_per_run_s",
            "pamkit Simulator.run_batch, 1 thread": "pamkit_batch_cpu_per_run_s",
            f"pamkit run_batch, method=auto ({auto})": "pamkit_batch_auto_cpu_per_run_s",
        }
        if arguments.jax_tau is None:  # the sweep above ran the base's gas
            ways["pamkit sweep's own rows (run_in_process)"] = "sweep_cpu_per_run_s"
        jax_cpu = times["jax_cpu_per_run_s"]
        for label, key in ways.items():
            print(f"  {label:48} {1e3 * times[key]:8.3f}   JAX / it {jax_cpu / times[key]:6.2f}")
        print(f"  {'JAX + diffrax vectorised':48} {1e3 * jax_cpu:8.3f}")
        print(f"  {'JAX + diffrax vectorised, wall per run, ms':48} {1e3 * times['jax_wall_per_run_s']:8.3f}")
        agreement = times["jax_agreement"]
        verdict = "ok" if agreement <= AGREEMENT else "DISAGREE"
        print(f"  {'max |F_jax - F_pamkit| / max |F|, worst run':48} {agreement:8.1e}  <= {AGREEMENT:.0e}: {verdict}")
        print(f"  {'JAX compilation, s':48} {times['jax_compile_s']:8.2f}  (not in the ratios)")
        if agreement > AGREEMENT:
            return 1
    if arguments.json:
        Path(arguments.json).write_text(json.dumps({"runs": runs, "cycles": arguments.cycles, **times}, indent=2))
    return 0


if __name__ == "__main__":
    sys.exit(main())
