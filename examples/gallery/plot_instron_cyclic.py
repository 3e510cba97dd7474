"""
An Instron cyclic test: read the machine's export and simulate it
=================================================================

A sealed PAM 1 of the thesis at 35 kPa stretched by 10 mm and back on an Instron tensile machine,
its Bluehill raw-data export read as it is (quoted cells, a units row): pamkit recognises the
machine by the header and converts its units. The model predicts the force, the gas pressure and
temperature from the crosshead's motion alone.
"""

# %%
from pathlib import Path

import matplotlib.pyplot as plt

import pamkit

data = Path("../../data") / "experiments"
experiment = pamkit.load_experiment(data / "machines" / "instron_bluehill.toml")
measured = experiment.to_frame()
measured.attrs["units"], measured.head()

# %%
# Simulate it twice: the thesis's model as declared, and with the gas exchanging heat with the
# wall in 2 s (``pamkit effects`` lists every effect and its parameters).
predicted = pamkit.simulate(experiment)
with_heat = pamkit.simulate(experiment, effects=["heat_transfer:time_constant_s=2"])
predicted.attrs["solver_statistics"]

# %%
fig, (force, pressure) = plt.subplots(1, 2, figsize=(10, 4), layout="constrained")
force.plot(1e3 * measured["elongation_m"], measured["force_N"], ".", ms=3, label="measured (Bluehill export)")
force.plot(1e3 * predicted["elongation_m"], predicted["force_N"], label="predicted")
force.set(xlabel="elongation [mm]", ylabel="force [N]")
force.legend()
# The frames are SI (gauge_pressure_Pa); the figure gives the pressure in kPa, as people read it.
pressure.plot(predicted["time_s"], predicted["gauge_pressure_Pa"] / 1e3, label="polytropic gas")
pressure.plot(with_heat["time_s"], with_heat["gauge_pressure_Pa"] / 1e3, label="heat exchanged in 2 s")
pressure.set(xlabel="time [s]", ylabel="gauge pressure [kPa]")
pressure.legend()
plt.show()
