"""
The controller loop: a fitted muscle's force at each sample
===========================================================

A device controller asks, at every sample, what force the muscle exerts at the length its encoder
reads and the pressure its transducer reads. Here the muscle is the one the diagnosis calibrated
on the bundled bench test (``pamkit diagnose ... --params-out``), read back from its
muscle-parameters file as a C++ controller reads it (``pamkit::read_muscle_params``, the
header-only ``pamkit::params``), and the loop runs at 1 kHz over a 2 s stroke.
"""

# %%
import shutil
import tempfile
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np

import pamkit
from pamkit.cli import main

example = Path("../../data") / "experiments" / "example" / "experiment.toml"
folder = Path(tempfile.mkdtemp())
main(["diagnose", str(example), "--params-out", str(folder / "calibrated.toml"), "--quiet"])
print((folder / "calibrated.toml").read_text()[:600])

# %%
# The loop: one geometry built before it, then one force evaluation per sample (C++:
# ``pamkit::RealtimeMuscle::force``, allocation-free and ``noexcept``).
params = pamkit.read_muscle_params(folder / "calibrated.toml")
geometry = pamkit.BraidGeometry(params.build)
atmosphere = params.gas.atmospheric_pressure_Pa
period_s = 1e-3
time_s = np.arange(0.0, 2.0, period_s)
length_m = 0.19 + 0.015 * np.sin(np.pi * time_s)  # encoder
velocity = 0.015 * np.pi * np.cos(np.pi * time_s)
gauge_Pa = 100e3 + 100e3 * time_s  # transducer
force_N = np.empty_like(time_s)
for k in range(time_s.size):
    shape = geometry.shape(length_m[k])
    forces = pamkit.muscle_forces(
        geometry, shape, params.bladder, params.friction, atmosphere + gauge_Pa[k], atmosphere, velocity[k]
    )
    force_N[k] = forces.total

# %%
fig, (stroke, force) = plt.subplots(2, 1, sharex=True, figsize=(8, 5), layout="constrained")
stroke.plot(time_s, 1e3 * length_m)
stroke.set(ylabel="length [mm]")
force.plot(time_s, force_N)
force.set(xlabel="time [s]", ylabel="force [N]")
plt.show()
shutil.rmtree(folder)
