#!/usr/bin/env python3
"""Times and cross-checks one 10-cycle thesis test: pamkit (C++/CVODES, through the Python
bindings and directly in C++) against an independent SciPy implementation (scipy_reference.py).

The test: InitialState(length_m=0.167, gauge_pressure_Pa=236.63e3) and thesis_protocol(0.0523)
(table C.2, 207 kPa / 90 %), run three times: GasProcess.heat_transfer with tau = 5 s (a
temperature ODE that does something, non-stiff), with tau = 0.02 s (stiff) and
GasProcess.polytropic with n = 1 (isothermal: dT/dt = 0, only the energy integrals are
integrated).

pamkit runs each case with each integration method (SimulatorConfig.method): bdf (the default),
adams, dopri5, rosenbrock4 and auto (the stiffness test's pick, named in the report), side by side.

It prints ratios only (absolute times go to --json):
  speed ratio         SciPy time / pamkit time, each the best of several runs, run alternately,
                      at matched tolerances (both rtol 1e-8, pamkit's default; both 1e-11), for
                      each pamkit method
  max rel. difference max |pamkit - SciPy| / max |SciPy| over each trace (force, pressure,
                      temperature), pamkit at rtol 1e-11 (and at its default 1e-8) against SciPy
                      at 1e-11, for each method
  binding overhead    Python Simulator.run time / the same run timed inside C++ - 1
                      (bench/bench_simulate.cpp, target pamkit_bench_simulate)
  RHS bound           C++ wall time / (RHS evaluations x the cost of one MuscleModel::evaluate);
                      also against every model evaluation the run makes (the RHS ones, Jacobian
                      columns included, and one per output sample: callgrind counts exactly these
                      calls), with the evaluation timed cold and as the simulator makes it
                      (warm-started braid solve, no angles: MuscleModel::evaluate_with), the run's
                      evaluation floor; these three for each method, with the solver's own counters
                      (steps, RHS evaluations, Jacobians, LU factorisations, Newton iterations)
  explicit RK         the same test by Dormand-Prince 5(4) with dense output (Boost.Odeint) on the
                      same right-hand side and output path, restarted at the same corners
                      (pamkit_bench_simulate --integrator dopri5): pamkit's C++ time over its time,
                      its accuracy against SciPy at 1e-11 and its own evaluation floor

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
    "speed_ratio": 60.0,  # SciPy LSODA / pamkit at rtol 1e-8, stiff and non-stiff (docs/benchmarks.md)
    "max_rel_diff": 1e-6,
    "binding_overhead": 0.05,
    "rhs_bound": 2.0,
    "evaluation_floor": 1.3,
}
TIGHT = 1e-11
DEFAULT = pamkit.SimulatorConfig().relative_tolerance  # 1e-8
METHODS = ("bdf", "adams", "dopri5", "rosenbrock4", "auto")  # pamkit.IntegrationMethod's names; bdf is the default
TRACES = ("force_N", "gauge_pressure_Pa", "temperature_K")
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
            (method, tol): pamkit.Simulator(
                pamkit.SimulatorConfig(
                    relative_tolerance=tol,
                    absolute_tolerance_K=tol,
                    absolute_tolerance_J=tol,
                    method=getattr(pamkit.IntegrationMethod, method),
                )
            )
            for method in METHODS
            for tol in (DEFAULT, TIGHT)
        }

    def pamkit_run(self, tol, method="bdf"):
        return self.simulators[(method, tol)].run(self.model, self.trajectory)

    def scipy_run(self, tol, method="LSODA"):
        return self.reference.simulate(self.time_s, self.elongation_m, rtol=tol, atol_K=tol, atol_J=tol, method=method)

    def exe_args(self, tol, method):
        return [
            "--method",
            method,
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


def run_exe(exe, case, tol, method, repeats, integrator="pamkit"):
    out = subprocess.run(
        [exe, *case.exe_args(tol, method), "--repeats", str(repeats), "--integrator", integrator],
        check=True,
        capture_output=True,
        text=True,
    )
    return json.loads(out.stdout)


def measure(case, exe, rounds, repeats, methods):
    res = {"case": case.name, "samples": int(case.time_s.size)}
    tols = (DEFAULT, TIGHT)
    runs = [(method, tol) for method in METHODS for tol in tols]
    # Accuracy.
    ref_tight = case.scipy_run(TIGHT)
    res["max_rel_diff"] = {}
    res["statistics"] = {}
    for method, tol in runs:
        r = case.pamkit_run(tol, method)
        res["max_rel_diff"][f"{method}@{tol:g}"] = {
            k: rel_diff(getattr(r, k), ref_tight[k])
            for k in (*TRACES, "work_J", "heat_lost_J", "friction_dissipated_J")
        }
        st = r.statistics
        res["statistics"][f"{method}@{tol:g}"] = {
            "method": st.method.name,
            "steps": st.steps,
            "rhs_evaluations": st.rhs_evaluations,
            "jacobian_evaluations": st.jacobian_evaluations,
            "linear_solver_setups": st.linear_solver_setups,
            "nonlinear_iterations": st.nonlinear_iterations,
            "error_test_failures": st.error_test_failures,
            "nonlinear_convergence_failures": st.nonlinear_convergence_failures,
            "restarts": st.restarts,
            "output_evaluations": st.output_evaluations,
        }
    res["stiffness"] = {
        f"{tol:g}": pamkit.estimate_stiffness(
            case.model, case.trajectory, pamkit.SimulatorConfig(relative_tolerance=tol)
        ).ratio
        for tol in tols
    }
    for method in methods[1:]:  # the other SciPy methods agree too (informative)
        other = case.scipy_run(TIGHT, method)
        res["max_rel_diff"][f"SciPy {method} vs LSODA"] = {k: rel_diff(other[k], ref_tight[k]) for k in TRACES}

    # Timing, alternating pamkit (Python, every method), pamkit (C++) and SciPy within every round.
    py = {run: float("inf") for run in runs}
    cxx = {run: None for run in runs}
    dopri5 = {tol: None for tol in tols}
    sp = {(m, tol): float("inf") for m in methods for tol in tols}
    nfev = {}
    pamkit_repeats = max(5 * repeats, 10)  # pamkit runs are short: more of them for a stable best
    for _ in range(rounds):
        for tol in tols:
            for method in METHODS:
                run = (method, tol)
                py[run] = min(py[run], best_time(lambda tol=tol, m=method: case.pamkit_run(tol, m), pamkit_repeats))
                if exe:
                    c = run_exe(exe, case, tol, method, pamkit_repeats)
                    if cxx[run] is not None:  # keep the best of each, over the rounds
                        for key in ("simulate_s", "evaluate_s", "evaluate_warm_s"):
                            if key in c:
                                c[key] = min(c[key], cxx[run][key])
                    cxx[run] = c
            if exe:
                d = run_exe(exe, case, tol, "bdf", pamkit_repeats, "dopri5")
                if dopri5[tol] is not None:
                    d["simulate_s"] = min(d["simulate_s"], dopri5[tol]["simulate_s"])
                dopri5[tol] = d
            for m in methods:
                repeats_m = repeats if m == "LSODA" else 1
                sp[(m, tol)] = min(sp[(m, tol)], best_time(lambda tol=tol, m=m: case.scipy_run(tol, m), repeats_m))
    for m in methods:
        for tol in tols:
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

    # The model's evaluation costs the same whichever method ran: the best over the runs' timings.
    evaluate_cxx = min((c["evaluate_s"] for c in cxx.values() if c), default=None)
    # an older pamkit_bench_simulate (--exe) times no warm evaluation
    warm = [c["evaluate_warm_s"] for c in cxx.values() if c and "evaluate_warm_s" in c]
    evaluate_warm_cxx = min(warm) if warm else None
    key = lambda run: f"{run[0]}@{run[1]:g}"  # noqa: E731
    res["times_s"] = {
        "pamkit_python": {key(run): py[run] for run in runs},
        "pamkit_cxx": {key(run): (cxx[run]["simulate_s"] if cxx[run] else None) for run in runs},
        "scipy": {f"{m}@{t:g}": sp[(m, t)] for (m, t) in sp},
        "evaluate_cxx": evaluate_cxx,
        "evaluate_warm_cxx": evaluate_warm_cxx,
        "evaluate_scipy": scipy_eval_s,
    }
    res["scipy_nfev"] = nfev
    res["speed_ratio"] = {m: {key(run): sp[(m, run[1])] / py[run] for run in runs} for m in methods}
    if exe:
        res["binding_overhead"] = {key(run): py[run] / cxx[run]["simulate_s"] - 1.0 for run in runs}
        res["rhs_bound"] = {}
        res["model_eval_bound"] = {}
        res["evaluation_floor"] = {}
        for run in runs:
            c = cxx[run]
            # Every evaluate() of a run: the RHS (the counter, difference-quotient Jacobians
            # included) and one per output sample, as callgrind counts them.
            all_evals = c["rhs_evaluations"] + c["samples"]
            res["rhs_bound"][key(run)] = c["simulate_s"] / (c["rhs_evaluations"] * evaluate_cxx)
            res["model_eval_bound"][key(run)] = c["simulate_s"] / (all_evals * evaluate_cxx)
            res["evaluation_floor"][key(run)] = (
                c["simulate_s"] / (all_evals * evaluate_warm_cxx) if evaluate_warm_cxx else None
            )
        res["per_evaluation_ratio"] = scipy_eval_s / evaluate_cxx
        res["dopri5"] = {
            f"{tol:g}": {
                "simulate_s": d["simulate_s"],
                "steps": d["steps"],
                "rhs_evaluations": d["rhs_evaluations"],
                "max_rel_diff": {k: rel_diff(d[k], ref_tight[k]) for k in TRACES},
                # Its evaluate calls: seven stages a step, less the first same as the last (FSAL),
                # counted by the right-hand side itself, and one per output sample.
                "evaluation_floor": d["simulate_s"] / ((d["rhs_evaluations"] + d["samples"]) * evaluate_warm_cxx),
            }
            for tol, d in dopri5.items()
        }
        res["over_dopri5"] = {key(run): cxx[run]["simulate_s"] / dopri5[run[1]]["simulate_s"] for run in runs}
    return res


def jacobians_lu_newton(s):
    return f"{s['jacobian_evaluations']} / {s['linear_solver_setups']} / {s['nonlinear_iterations']}"


def fmt_ratio(x):
    return "n/a" if x is None else (f"{x:,.0f}x" if x >= 100 else f"{x:.1f}x")


def report(results, methods, exe):
    lines = []
    w = 52
    c = 20  # a column: "2132 / 2132 / 0" and the like
    d, t = f"{DEFAULT:g}", f"{TIGHT:g}"

    def row(label, values, fmt, target=""):
        """One line per method: values["method@tol"] formatted by `fmt`, at both tolerances."""
        for method in METHODS:
            a, b = fmt(values[f"{method}@{d}"]), fmt(values[f"{method}@{t}"])
            lines.append(f"{label + ', ' + method:{w}}{a:>{c}}{b:>{c}}   {target}")

    for res in results:
        ran = {tol: res["statistics"][f"auto@{tol}"]["method"] for tol in (d, t)}
        stiffness = res["stiffness"]
        lines.append(
            f"\n== {res['case']}  ({res['samples']} samples; auto ran {ran[d]} at {d}, {ran[t]} at {t}: "
            f"stiffness ratio {stiffness[d]:.3g}, {stiffness[t]:.3g})"
        )
        lines.append(f"{'':{w}}{'rtol ' + d:>{c}}{'rtol ' + t:>{c}}   target")
        for m in methods:
            tgt = f">= {TARGETS['speed_ratio']:.0f}x at {d}" if m == "LSODA" else "(info)"
            row(f"speed ratio SciPy {m} / pamkit", res["speed_ratio"][m], fmt_ratio, tgt)
        mixed = res["times_s"]["scipy"]["LSODA@" + t] / res["times_s"]["pamkit_python"]["bdf@" + d]
        lines.append(
            f"{'speed ratio SciPy LSODA@' + t + ' / pamkit bdf@' + d:{w}}{fmt_ratio(mixed):>{c}}{'':>{c}}   (info)"
        )
        for k in TRACES:
            by_run = {run: diffs[k] for run, diffs in res["max_rel_diff"].items() if not run.startswith("SciPy")}
            row(
                f"max rel diff vs SciPy@1e-11, {k}",
                by_run,
                "{:.1e}".format,
                f"<= {TARGETS['max_rel_diff']:.0e} (at {t})",
            )
        for m in methods[1:]:
            worst = max(res["max_rel_diff"][f"SciPy {m} vs LSODA"].values())
            lines.append(f"{'max rel diff SciPy ' + m + ' vs LSODA (F, p, T)':{w}}{'':>{c}}{worst:>{c}.1e}   (info)")
        if exe:
            percent = "{:.2%}".format
            times = "{:.2f}x".format
            overhead = f"<= {100 * TARGETS['binding_overhead']:.0f} %"
            row("binding overhead (Python / C++ - 1)", res["binding_overhead"], percent, overhead)
            row("wall / (RHS evals x one evaluate)", res["rhs_bound"], times, f"<= {TARGETS['rhs_bound']:.0f}x")
            row("wall / (all evaluate calls x one evaluate)", res["model_eval_bound"], times, "(info)")
            if res["evaluation_floor"][f"bdf@{d}"] is not None:
                floor = f"<= {TARGETS['evaluation_floor']:.1f}x"
                row("wall / (all evaluate calls x one warm evaluate)", res["evaluation_floor"], times, floor)
            lines.append(
                f"{'one evaluate: SciPy reference / C++':{w}}{fmt_ratio(res['per_evaluation_ratio']):>{c}}"
                f"{'':>{c}}   (info)"
            )
            row("wall, pamkit / DOPRI5 on the same RHS", res["over_dopri5"], times, "(info)")
            explicit = res["dopri5"]
            for label, cell in (
                ("DOPRI5 max rel diff vs SciPy@1e-11 (F, p, T)", lambda e: f"{max(e['max_rel_diff'].values()):.1e}"),
                ("DOPRI5 wall / (all evaluate calls x warm one)", lambda e: f"{e['evaluation_floor']:.2f}x"),
                ("DOPRI5 steps / RHS evals", lambda e: f"{e['steps']} / {e['rhs_evaluations']}"),
            ):
                lines.append(f"{label:{w}}{cell(explicit[d]):>{c}}{cell(explicit[t]):>{c}}   (info)")
        st = res["statistics"]
        row("steps / RHS evals", st, lambda s: f"{s['steps']} / {s['rhs_evaluations']}")
        row("Jacobians / LU / Newton iterations", st, jacobians_lu_newton)
        lines.append(
            f"{'output evaluations (one per sample)':{w}}{st['bdf@' + d]['output_evaluations']:>{c}}"
            f"{st['bdf@' + t]['output_evaluations']:>{c}}"
        )
        lines.append(
            f"{'SciPy LSODA RHS evals (4 states at once)':{w}}{res['scipy_nfev']['LSODA@' + d]:>{c}}"
            f"{res['scipy_nfev']['LSODA@' + t]:>{c}}"
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
