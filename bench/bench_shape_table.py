#!/usr/bin/env python3
"""Times one simulation of a long sealed record with and without a ShapeTable, side by side.

The record: PAM 2 at 0.167 m and 236.63 kPa (table C.2, 90 %), the thesis protocol to 52.3 mm at
2.5 mm/s for 10 cycles sampled every --period s (0.03 s: 13 961 samples, the length of the
diagnosis's longer records), heat transfer (tau = 5 s) and the thesis's friction, at the
diagnosis's tolerances (rtol 1e-6, atol 1e-6 K: diagnosis/series/model.py's Predictor). Each round runs
`simulate_measurement` without a table, then with one built beforehand, alternately; the
inflation pressure changes every round (as a diagnosis's runs differ), the table does not.

Times are the process's CPU time (time.process_time: the run holds one thread), which the other
jobs on a shared machine disturb far less than wall time. It prints the median and the best of
each, their ratio, the time to build the table (what its
first run pays: the shapes a plain run solves itself) and checks the two runs' channels equal, bit
for bit (the table solves the shapes as the run's output path does).

Usage:
  PYTHONPATH=build/python python3 bench/bench_shape_table.py [--rounds 21] [--period 0.03] [--json OUT]
"""

from __future__ import annotations

import argparse
import json
import statistics
import time

import numpy as np

import pamkit._core as core

CHANNELS = ("force_N", "gauge_pressure_Pa", "temperature_K")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rounds", type=int, default=21, help="runs of each kind (default 21)")
    parser.add_argument("--period", type=float, default=0.03, help="sample period of the record [s] (default 0.03)")
    parser.add_argument("--json", help="write the raw times here")
    args = parser.parse_args()

    params = core.MuscleParams()
    gas = params.gas
    gas.process = core.GasProcess.heat_transfer
    gas.heat_transfer_time_constant_s = 5.0
    params.gas = gas
    crosshead = core.thesis_protocol(0.0523, 2.5e-3, 10, args.period)
    simulator = core.Simulator(core.SimulatorConfig(relative_tolerance=1e-6, absolute_tolerance_K=1e-6))
    length_m = 0.167

    plain_s, table_s, build_s = [], [], []
    for k in range(args.rounds):
        start = time.process_time()
        table = core.ShapeTable(params, length_m, crosshead)
        build_s.append(time.process_time() - start)
        initial = core.InitialState(length_m=length_m, gauge_pressure_Pa=(236.63 + 0.1 * k) * 1e3)
        start = time.process_time()
        plain = core.simulate_measurement(params, initial, crosshead, [], simulator)
        plain_s.append(time.process_time() - start)
        start = time.process_time()
        tabulated = core.simulate_measurement(params, initial, crosshead, [], simulator, shapes=table)
        table_s.append(time.process_time() - start)
        assert tabulated.statistics.tabulated_shapes == len(crosshead), "the table did not apply"
        for name in CHANNELS:
            a, b = np.asarray(getattr(plain, name)), np.asarray(getattr(tabulated, name))
            assert a.tobytes() == b.tobytes(), f"{name} differs with the table"

    median = statistics.median
    print(f"sealed record of {len(crosshead)} samples, heat transfer, friction, rtol 1e-6; {args.rounds} rounds")
    print(f"{'':34}{'median':>10}{'best':>10}")
    for label, times in (
        ("one simulation, no table", plain_s),
        ("one simulation, with a table", table_s),
        ("building the table", build_s),
    ):
        print(f"  {label:32}{1e3 * median(times):8.2f} ms{1e3 * min(times):7.2f} ms")
    print(
        f"  {'ratio no table / with table':32}{median(plain_s) / median(table_s):9.2f}x"
        f"{min(plain_s) / min(table_s):9.2f}x"
    )
    print("  channels with and without the table: identical, bit for bit")
    if args.json:
        with open(args.json, "w") as out:
            json.dump({"samples": len(crosshead), "plain_s": plain_s, "table_s": table_s, "build_s": build_s}, out)


if __name__ == "__main__":
    main()
