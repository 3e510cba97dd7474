"""How close the independent model comes to pamkit's simulation of the same bench test, and the
one-off calibration of its two free parameters (bladder shear modulus μ, friction per pressure
c_f) that put its force in pamkit's range. pamkit is reached through its command line only
(``python -m pamkit simulate``), never imported.

    PYTHONPATH=build/python python3 tests/independent/calibrate.py [--grid]

Without --grid: the noise-free force and pressure RMSE between the two models on two thesis
protocols (PAM 2 at 236.63 kPa, 10 cycles at 2.5 mm/s, table C.2; the same at 25 mm/s).
With --grid: for each μ of a grid, the best c_f (force is linear in it) and the RMSEs.
"""

from __future__ import annotations

import argparse
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from independent import bench
from independent.families import SealedPlan, crosshead
from independent.physics import Build, Physics, SealedMuscle

# Thesis table C.2: PAM 2 at 236.63 kPa, stretched 52.3 mm (90 %), 10 cycles, ambient 296 K.
THESIS = {"gauge_kPa": 236.63, "ambient_C": 22.85, "top_m": 0.0523, "cycles": 10}


def pamkit_prediction(folder: Path, physics: Physics, speed: float) -> tuple[dict, dict]:
    """(independent truth, pamkit simulate's prediction) on the same protocol, noise-free."""
    plan = SealedPlan(THESIS["gauge_kPa"], THESIS["ambient_C"], 0.9, [speed] * THESIS["cycles"], 1.0)
    muscle = SealedMuscle(Build(), physics, plan.gauge_kPa, plan.ambient_C)
    motion = crosshead(plan, THESIS["top_m"], 10.0)
    times = np.arange(0.0, motion.corner_t[-1] + 1e-9, 0.1)
    run = muscle.run(motion, times)
    truth = {"force_N": run.force_N, "pressure_kPa": run.gauge_kPa}
    path = bench.write_experiment(
        folder,
        "cal",
        vars(Build()).copy(),
        {
            "inflation_pressure_kPa": plan.gauge_kPa,
            "ambient_temperature_C": plan.ambient_C,
            "initial_length_m": muscle.free_length_m,
        },
        {"time_s": times, "elongation_m": run.elongation_m},
        "calibration",
    )
    out = folder / "cal_pamkit.csv"
    done = subprocess.run(
        [sys.executable, "-m", "pamkit", "simulate", str(path), "-o", str(out)],
        check=False,
        capture_output=True,
        text=True,
    )
    if done.returncode != 0:
        raise SystemExit(done.stderr)
    predicted = np.genfromtxt(out, delimiter=",", names=True)
    return truth, {c: predicted[c] for c in truth}, muscle


def rmse(a, b):
    return float(np.sqrt(np.mean((np.asarray(a) - np.asarray(b)) ** 2)))


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--grid", action="store_true")
    arguments = parser.parse_args()
    speeds = (2.5e-3, 25e-3)
    with tempfile.TemporaryDirectory() as scratch:
        folder = Path(scratch)
        if not arguments.grid:
            for speed in speeds:
                truth, predicted, muscle = pamkit_prediction(folder, Physics(), speed)
                print(
                    f"{speed * 1e3:4.1f} mm/s: free length {muscle.free_length_m * 1e3:.1f} mm; force RMSE "
                    f"{rmse(truth['force_N'], predicted['force_N']):.2f} N "
                    f"(range {np.ptp(predicted['force_N']):.0f} N), "
                    f"pressure RMSE {rmse(truth['pressure_kPa'], predicted['pressure_kPa']):.2f} kPa "
                    f"(range {np.ptp(predicted['pressure_kPa']):.0f} kPa)"
                )
            return 0
        for mu in (0.3e6, 0.45e6, 0.6e6, 0.8e6):
            # force = static + c_f * p * tanh(v / v_s): run without friction, fit c_f linearly
            rows = []
            for speed in speeds:
                truth, predicted, _ = pamkit_prediction(folder, Physics(shear_modulus_Pa=mu, friction_m2=0.0), speed)
                rows.append((truth, predicted, speed))
            a = np.concatenate(
                [
                    r[0]["pressure_kPa"] * 1e3 * np.tanh(_velocity(r[2]) / Physics().friction_velocity_m_per_s)
                    for r in rows
                ]
            )
            residual = np.concatenate([r[1]["force_N"] - r[0]["force_N"] for r in rows])
            friction = float(a @ residual / (a @ a))
            force = rmse(residual, friction * a)
            pressure = rmse(
                np.concatenate([r[0]["pressure_kPa"] for r in rows]),
                np.concatenate([r[1]["pressure_kPa"] for r in rows]),
            )
            print(
                f"mu {mu / 1e6:.2f} MPa: c_f {friction:.3g} m², "
                f"force RMSE {force:.2f} N, pressure RMSE {pressure:.2f} kPa"
            )
    return 0


def _velocity(speed):
    plan = SealedPlan(THESIS["gauge_kPa"], THESIS["ambient_C"], 0.9, [speed] * THESIS["cycles"], 1.0)
    motion = crosshead(plan, THESIS["top_m"], 10.0)
    times = np.arange(0.0, motion.corner_t[-1] + 1e-9, 0.1)
    return motion.velocity(times)


if __name__ == "__main__":
    raise SystemExit(main())
