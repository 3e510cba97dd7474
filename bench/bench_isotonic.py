"""The isotonic length solve: pamkit's isotonic_lengths (C++: a scan from the previous length and
TOMS 748, the whole sweep in one call) against SciPy's brentq on the same force function (pamkit's
static_forces, one Python call per evaluation), on the same sweep. Prints ratios only, measured
side by side in one run with the two taking turns (absolute times with --json).

    PYTHONPATH=build/python python3 bench/bench_isotonic.py [--rounds 5] [--points 41] [--json OUT]

The build is the Festo DMSP-10-250 as calibrated from its map (data/experiments/festo), under a
100 N load, swept 100-600 kPa and back. Both solvers must agree to 1 um on every row.
"""

from __future__ import annotations

import argparse
import json
import time

import numpy as np
from scipy.optimize import brentq

import pamkit

LOAD_N = 100.0


def festo_params() -> pamkit.MuscleParams:
    build = pamkit.MuscleBuild(
        length_m=0.25,
        diameter_m=0.01,
        bladder_diameter_m=0.00967,
        bladder_thickness_m=0.5e-3,
        fiber_count=100,
        fiber_thickness_m=0.0,
        end_diameter_m=0.005,
        cone_generator_m=0.0,
    )
    build.fiber_revolutions = pamkit.fiber_revolutions_for_braid_angle(build, 21.9)
    return pamkit.MuscleParams(build=build, bladder=pamkit.BladderLaw.neo_hookean(3.11e6))


def scipy_sweep(params, pressures, start):
    """Each row: bracket from the previous length toward the imbalance, then brentq."""
    lengths, length = [], start
    for p in pressures:

        def imbalance(x, p=p):
            return float(pamkit.static_forces(params, [x], [p])[0]) - LOAD_N

        here = imbalance(length)
        step = -1e-4 if here > 0 else 1e-4
        a = length
        while (imbalance(a + step) > 0) == (here > 0):
            a += step
        length = brentq(imbalance, min(a, a + step), max(a, a + step), xtol=1e-12)
        lengths.append(length)
    return np.array(lengths)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rounds", type=int, default=5)
    parser.add_argument("--points", type=int, default=41, help="settled steps per sweep (up and down)")
    parser.add_argument("--json", help="write the raw times")
    arguments = parser.parse_args()
    params = festo_params()
    up = np.linspace(100.0, 600.0, (arguments.points + 1) // 2)
    pressures = np.concatenate([up, up[-2::-1]])
    start = params.build.length_m
    times = {"pamkit": [], "scipy": []}
    for _ in range(arguments.rounds):
        began = time.perf_counter()
        ours = pamkit.isotonic_lengths(params, pressures, LOAD_N, start).length_m
        times["pamkit"].append(time.perf_counter() - began)
        began = time.perf_counter()
        theirs = scipy_sweep(params, pressures, start)
        times["scipy"].append(time.perf_counter() - began)
    largest = float(np.max(np.abs(ours - theirs)))
    assert largest < 1e-6, f"the two solves disagree by {largest} m"
    ratio = np.median(times["scipy"]) / np.median(times["pamkit"])
    print(f"isotonic sweep of {len(pressures)} settled steps under {LOAD_N:g} N, {arguments.rounds} rounds:")
    print(f"  SciPy brentq on pamkit's force / pamkit isotonic_lengths: {ratio:.1f}x (medians)")
    print(f"  largest difference between the two: {largest:.1e} m")
    if arguments.json:
        with open(arguments.json, "w") as handle:
            json.dump({"seconds": times, "points": len(pressures), "largest_difference_m": largest}, handle, indent=2)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
