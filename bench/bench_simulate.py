#!/usr/bin/env python3
"""Times and cross-checks one 10-cycle thesis test: pamkit (C++/CVODES, through the Python
bindings and directly in C++) against an independent SciPy implementation (scipy_reference.py).

The test: InitialState(length_m=0.167, gauge_pressure_Pa=236.63e3) and thesis_protocol(0.0523)
(table C.2, 207 kPa / 90 %), run three times: GasProcess.heat_transfer with tau = 5 s (a
temperature ODE that does something, non-stiff), with tau = 0.02 s (stiff) and
GasProcess.polytropic with n = 1 (isothermal: dT/dt = 0, only the energy integrals are
integrated).

It prints ratios only (absolute times go to --json):
  speed ratio         SciPy time / pamkit time, each the best of several runs, run alternately,
                      at matched tolerances (both rtol 1e-8, pamkit's default; both 1e-11)
  max rel. difference max |pamkit - SciPy| / max |SciPy| over each trace (force, pressure,
                      temperature), pamkit at rtol 1e-11 (and at its default 1e-8) against SciPy
                      at 1e-11
  binding overhead    Python Simulator.run time / the same run timed inside C++ - 1
                      (bench/bench_simulate.cpp, target pamkit_bench_simulate)
  RHS bound           C++ wall time / (CVODE RHS evaluations x the cost of one
                      MuscleModel::evaluate); also against every model evaluation the run makes
                      (RHS + quadrature RHS ~ one per step + one per output sample), with the
                      evaluation timed cold and as the simulator makes it (warm-started braid
                      solve, no angles: MuscleModel::evaluate_with), the run's evaluation floor

Usage:
  PYTHONPATH=build/python .venv/bin/python bench/bench_simulate.py [--exe build/bench/pamkit_bench_simulate]
      [--rounds 3] [--repeats 3] [--json OUT] [--methods LSODA,Radau,BDF] [--cycles 10]
"""

from __future__ import annotations

import argparse
import gc
import glob
import json
import os
import subprocess
import sys
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, HERE)

try:
    import pamkit
except ImportError:  # convenience: the usual build directory
    sys.path.insert(0, os.path.join(ROOT, "build", "python"))
    import pamkit

from scipy_reference import ReferenceMuscle  # noqa: E402

TARGETS = {
    "speed_ratio": 300.0,
    "max_rel_diff": 1e-6,
    "binding_overhead": 0.05,
    "rhs_bound": 2.0,
    "evaluation_floor": 1.3,
}
TIGHT = 1e-11
DEFAULT = pamkit.SimulatorConfig().relative_tolerance  # 1e-8
TRACES = ("force_N", "pressure_gauge_Pa", "temperature_K")
INITIAL = {"length_m": 0.167, "gauge_pressure_Pa": 236.63e3}
MAX_ELONGATION_M = 0.0523


def find_exe(given):
    if given:
        return given
    if os.environ.get("PAMKIT_BENCH_EXE"):
        return os.environ["PAMKIT_BENCH_EXE"]
    found = glob.glob(os.path.join(ROOT, "build*", "bench", "pamkit_bench_simulate"))
    return max(found, key=os.path.getmtime) if found else None


def best_time(fn, repeats):
    """Best wall time of `repeats` calls of fn(), garbage collector off (as timeit does)."""
    best = float("inf")
    enabled = gc.isenabled()
    gc.disable()
    try:
        for _ in range(repeats):
            start = time.perf_counter()
            fn()
            best = min(best, time.perf_counter() - start)
    finally:
        if enabled:
            gc.enable()
    return best


def rel_diff(a, b):
    a, b = np.asarray(a), np.asarray(b)
    return float(np.max(np.abs(a - b)) / np.max(np.abs(b)))


class Case:
    """One test, built both ways."""

    def __init__(self, name, process, tau_s, polytropic_index, sharpness, cycles):
        self.name, self.process, self.tau_s, self.n = name, process, tau_s, polytropic_index
        self.sharpness, self.cycles = sharpness, cycles
        gas = pamkit.GasParams(
            process=getattr(pamkit.GasProcess, process),
            heat_transfer_time_constant_s=tau_s,
            polytropic_index=polytropic_index,
        )
        params = pamkit.MuscleParams(
            pamkit.MuscleBuild(), pamkit.BladderLaw.thesis(), pamkit.FrictionParams(sharpness_s_per_m=sharpness), gas
        )
        self.model = pamkit.MuscleModel(params, pamkit.InitialState(**INITIAL))
        self.trajectory = pamkit.thesis_protocol(MAX_ELONGATION_M, cycles=cycles)
        self.time_s = np.array(self.trajectory.time_s)
        self.elongation_m = np.array(self.trajectory.elongation_m)
        self.reference = ReferenceMuscle(
            build=pamkit.MuscleBuild().to_dict(),
            initial_length_m=INITIAL["length_m"],
            initial_gauge_pressure_Pa=INITIAL["gauge_pressure_Pa"],
            friction=pamkit.FrictionParams(sharpness_s_per_m=sharpness).to_dict(),
            gas={**gas.to_dict(), "process": process},
        )
        self.simulators = {
            tol: pamkit.Simulator(
                pamkit.SimulatorConfig(relative_tolerance=tol, absolute_tolerance_K=tol, absolute_tolerance_J=tol)
            )
            for tol in (DEFAULT, TIGHT)
        }

    def pamkit_run(self, tol):
        return self.simulators[tol].run(self.model, self.trajectory)

    def scipy_run(self, tol, method="LSODA"):
        return self.reference.simulate(self.time_s, self.elongation_m, rtol=tol, atol_K=tol, atol_J=tol, method=method)

    def exe_args(self, tol):
        return [
            "--process",
            self.process,
            "--tau",
            repr(self.tau_s),
            "--polytropic-index",
            repr(self.n),
            "--sharpness",
            repr(self.sharpness),
            "--cycles",
            str(self.cycles),
            "--length",
            repr(INITIAL["length_m"]),
            "--gauge",
            repr(INITIAL["gauge_pressure_Pa"]),
            "--max-elongation",
            repr(MAX_ELONGATION_M),
            "--rtol",
            repr(tol),
            "--atol-K",
            repr(tol),
            "--atol-J",
            repr(tol),
        ]


def run_exe(exe, case, tol, repeats):
    out = subprocess.run(
        [exe, *case.exe_args(tol), "--repeats", str(repeats)], check=True, capture_output=True, text=True
    )
    return json.loads(out.stdout)


def measure(case, exe, rounds, repeats, methods):
    res = {"case": case.name, "samples": int(case.time_s.size)}
    # Accuracy.
    ref_tight = case.scipy_run(TIGHT)
    res["max_rel_diff"] = {}
    for tol in (TIGHT, DEFAULT):
        r = case.pamkit_run(tol)
        res["max_rel_diff"][f"pamkit@{tol:g}"] = {
            k: rel_diff(getattr(r, k), ref_tight[k])
            for k in (*TRACES, "work_J", "heat_lost_J", "friction_dissipated_J")
        }
        st = r.statistics
        res.setdefault("statistics", {})[f"{tol:g}"] = {
            "steps": st.steps,
            "rhs_evaluations": st.rhs_evaluations,
            "jacobian_evaluations": st.jacobian_evaluations,
            "error_test_failures": st.error_test_failures,
            "restarts": st.restarts,
            "output_evaluations": st.output_evaluations,
        }
    for method in methods[1:]:  # the other SciPy methods agree too (informative)
        other = case.scipy_run(TIGHT, method)
        res["max_rel_diff"][f"SciPy {method} vs LSODA"] = {k: rel_diff(other[k], ref_tight[k]) for k in TRACES}

    # Timing, alternating pamkit (Python), pamkit (C++) and SciPy within every round.
    py = {tol: float("inf") for tol in (DEFAULT, TIGHT)}
    cxx = {tol: None for tol in (DEFAULT, TIGHT)}
    sp = {(m, tol): float("inf") for m in methods for tol in (DEFAULT, TIGHT)}
    nfev = {}
    pamkit_repeats = max(5 * repeats, 10)  # pamkit runs are short: more of them for a stable best
    for _ in range(rounds):
        for tol in (DEFAULT, TIGHT):
            py[tol] = min(py[tol], best_time(lambda tol=tol: case.pamkit_run(tol), pamkit_repeats))
            if exe:
                c = run_exe(exe, case, tol, pamkit_repeats)
                if cxx[tol] is not None:  # keep the best of each, over the rounds
                    c["simulate_s"] = min(c["simulate_s"], cxx[tol]["simulate_s"])
                    c["evaluate_s"] = min(c["evaluate_s"], cxx[tol]["evaluate_s"])
                    if "evaluate_warm_s" in c:
                        c["evaluate_warm_s"] = min(c["evaluate_warm_s"], cxx[tol]["evaluate_warm_s"])
                cxx[tol] = c
            for m in methods:
                repeats_m = repeats if m == "LSODA" else 1
                sp[(m, tol)] = min(sp[(m, tol)], best_time(lambda tol=tol, m=m: case.scipy_run(tol, m), repeats_m))
    for m in methods:
        for tol in (DEFAULT, TIGHT):
            nfev[f"{m}@{tol:g}"] = case.scipy_run(tol, m)["nfev"]

    # One evaluation of the SciPy reference's model, at the states of the run.
    lengths = INITIAL["length_m"] + case.elongation_m
    rates = np.concatenate([[0.0], np.diff(case.elongation_m) / np.diff(case.time_s)])
    rates[0] = rates[1]
    temps = np.array(ref_tight["temperature_K"])
    states = list(zip(lengths.tolist(), rates.tolist(), temps.tolist()))

    def scipy_evaluations():
        for L, v, T in states:
            case.reference.evaluate(L, v, T)

    scipy_eval_s = best_time(scipy_evaluations, max(repeats, 3)) / len(states)

    res["times_s"] = {
        "pamkit_python": {f"{t:g}": py[t] for t in py},
        "pamkit_cxx": {f"{t:g}": (cxx[t]["simulate_s"] if cxx[t] else None) for t in cxx},
        "scipy": {f"{m}@{t:g}": sp[(m, t)] for (m, t) in sp},
        "evaluate_cxx": cxx[DEFAULT]["evaluate_s"] if cxx[DEFAULT] else None,
        # an older pamkit_bench_simulate (--exe) times no warm evaluation
        "evaluate_warm_cxx": cxx[DEFAULT].get("evaluate_warm_s") if cxx[DEFAULT] else None,
        "evaluate_scipy": scipy_eval_s,
    }
    res["scipy_nfev"] = nfev
    res["speed_ratio"] = {f"{m}@{t:g}": sp[(m, t)] / py[t] for (m, t) in sp}
    if exe:
        res["binding_overhead"] = {f"{t:g}": py[t] / cxx[t]["simulate_s"] - 1.0 for t in py}
        res["rhs_bound"] = {}
        res["model_eval_bound"] = {}
        res["evaluation_floor"] = {}
        warm_s = res["times_s"]["evaluate_warm_cxx"]
        for t in (DEFAULT, TIGHT):
            c = cxx[t]
            eval_s = res["times_s"]["evaluate_cxx"]
            # Every evaluate() of a run: CVODE's RHS (the counter), the quadrature RHS (one per
            # step, within ~1 %: checked once with callgrind) and one per output sample.
            all_evals = c["rhs_evaluations"] + c["steps"] + c["samples"]
            res["rhs_bound"][f"{t:g}"] = c["simulate_s"] / (c["rhs_evaluations"] * eval_s)
            res["model_eval_bound"][f"{t:g}"] = c["simulate_s"] / (all_evals * eval_s)
            res["evaluation_floor"][f"{t:g}"] = c["simulate_s"] / (all_evals * warm_s) if warm_s else None
        res["per_evaluation_ratio"] = scipy_eval_s / res["times_s"]["evaluate_cxx"]
    return res


def fmt_ratio(x):
    return "n/a" if x is None else (f"{x:,.0f}x" if x >= 100 else f"{x:.1f}x")


def report(results, methods, exe):
    lines = []
    w = 46
    for res in results:
        d, t = f"{DEFAULT:g}", f"{TIGHT:g}"
        lines.append(f"\n== {res['case']}  ({res['samples']} samples)")
        lines.append(f"{'':{w}}{'rtol ' + d:>14}{'rtol ' + t:>14}   target")
        for m in methods:
            sr = res["speed_ratio"]
            tgt = f">= {TARGETS['speed_ratio']:.0f}x" if m == "LSODA" else "(info)"
            lines.append(
                f"{'speed ratio SciPy ' + m + ' / pamkit':{w}}{fmt_ratio(sr[m + '@' + d]):>14}"
                f"{fmt_ratio(sr[m + '@' + t]):>14}   {tgt}"
            )
        mixed = res["times_s"]["scipy"]["LSODA@" + t] / res["times_s"]["pamkit_python"][d]
        lines.append(f"{'speed ratio SciPy LSODA@' + t + ' / pamkit@' + d:{w}}{fmt_ratio(mixed):>14}{'':>14}   (info)")
        for k in TRACES:
            tight = res["max_rel_diff"][f"pamkit@{t}"][k]
            default = res["max_rel_diff"][f"pamkit@{d}"][k]
            lines.append(
                f"{'max rel diff vs SciPy@1e-11, ' + k:{w}}{default:>14.1e}{tight:>14.1e}   "
                f"<= {TARGETS['max_rel_diff']:.0e} (at {t})"
            )
        for m in methods[1:]:
            worst = max(res["max_rel_diff"][f"SciPy {m} vs LSODA"].values())
            lines.append(f"{'max rel diff SciPy ' + m + ' vs LSODA (F, p, T)':{w}}{'':>14}{worst:>14.1e}   (info)")
        if exe:
            bo = res["binding_overhead"]
            lines.append(
                f"{'binding overhead (Python / C++ - 1)':{w}}{100 * bo[d]:>13.2f}%{100 * bo[t]:>13.2f}%   "
                f"<= {100 * TARGETS['binding_overhead']:.0f} %"
            )
            rb, mb = res["rhs_bound"], res["model_eval_bound"]
            lines.append(
                f"{'wall / (CVODE RHS evals x one evaluate)':{w}}{rb[d]:>13.2f}x{rb[t]:>13.2f}x   "
                f"<= {TARGETS['rhs_bound']:.0f}x"
            )
            lines.append(f"{'wall / (all evaluate calls x one evaluate)':{w}}{mb[d]:>13.2f}x{mb[t]:>13.2f}x   (info)")
            fl = res["evaluation_floor"]
            if fl[d] is not None:
                lines.append(
                    f"{'wall / (all evaluate calls x one warm evaluate)':{w}}{fl[d]:>13.2f}x{fl[t]:>13.2f}x   "
                    f"<= {TARGETS['evaluation_floor']:.1f}x"
                )
            lines.append(
                f"{'one evaluate: SciPy reference / C++':{w}}{fmt_ratio(res['per_evaluation_ratio']):>14}"
                f"{'':>14}   (info)"
            )
        sd, stt = res["statistics"][d], res["statistics"][t]
        lines.append(
            f"{'CVODE steps / RHS evals':{w}}{str(sd['steps']) + ' / ' + str(sd['rhs_evaluations']):>14}"
            f"{str(stt['steps']) + ' / ' + str(stt['rhs_evaluations']):>14}"
        )
        lines.append(
            f"{'output evaluations (one per sample)':{w}}{sd['output_evaluations']:>14}{stt['output_evaluations']:>14}"
        )
        lines.append(
            f"{'SciPy LSODA RHS evals (4 states at once)':{w}}{res['scipy_nfev']['LSODA@' + d]:>14}"
            f"{res['scipy_nfev']['LSODA@' + t]:>14}"
        )
    return "\n".join(lines)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--exe", help="path of pamkit_bench_simulate (default: $PAMKIT_BENCH_EXE or build*/bench/)")
    ap.add_argument("--rounds", type=int, default=3, help="alternating timing rounds (default 3)")
    ap.add_argument("--repeats", type=int, default=3, help="SciPy runs per round; pamkit runs 5x as many (default 3)")
    ap.add_argument("--methods", default="LSODA", help="SciPy methods, comma-separated; the first is the reference")
    ap.add_argument("--cycles", type=int, default=10)
    ap.add_argument(
        "--sharpness",
        type=float,
        default=pamkit.FrictionParams().sharpness_s_per_m,
        help="friction Kf [s/m] (default: pamkit's, 1 s/m as in the thesis)",
    )
    ap.add_argument("--json", metavar="OUT", help="write every measurement (times in s) to OUT")
    args = ap.parse_args(argv)
    methods = [m.strip() for m in args.methods.split(",") if m.strip()]
    if methods[0] != "LSODA":
        methods.insert(0, "LSODA")
    exe = find_exe(args.exe)
    if exe and not os.access(exe, os.X_OK):
        ap.error(f"--exe {exe} is not an executable")
    if not exe:
        print(
            "pamkit_bench_simulate not found (build target pamkit_bench_simulate or pass --exe): "
            "no binding overhead or RHS bound",
            file=sys.stderr,
        )

    cases = [
        Case("heat_transfer, tau = 5 s", "heat_transfer", 5.0, 1.0, args.sharpness, args.cycles),
        Case("heat_transfer, tau = 0.02 s (stiff)", "heat_transfer", 0.02, 1.0, args.sharpness, args.cycles),
        Case("polytropic, n = 1", "polytropic", 5.0, 1.0, args.sharpness, args.cycles),
    ]
    results = [measure(c, exe, args.rounds, args.repeats, methods) for c in cases]
    print(
        f"pamkit {pamkit.__version__} vs SciPy reference ({', '.join(methods)}); {args.cycles} cycles, "
        f"Kf = {args.sharpness:g} s/m; best of {args.rounds} rounds; exe: {exe or 'not found'}"
    )
    print(report(results, methods, exe))
    if args.json:
        with open(args.json, "w") as f:
            json.dump(
                {
                    "targets": TARGETS,
                    "exe": exe,
                    "cycles": args.cycles,
                    "sharpness_s_per_m": args.sharpness,
                    "methods": methods,
                    "results": results,
                },
                f,
                indent=2,
            )
    return 0


if __name__ == "__main__":
    sys.exit(main())
