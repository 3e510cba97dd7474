"""
A design sweep on Dask: force and stored energy over pressure and braid angle
=============================================================================

PAM 2's bench test (thesis table C.2) simulated over a grid of inflation pressures and braid
angles, one run per point, on a local Dask cluster of two worker processes (``pip install
'pamkit[scale]'``). The same spec runs from the command line: ``pamkit sweep
data/sweeps/pam2_pressure_angle.toml -o sweep.parquet --workers 2``; ``--scheduler ADDRESS``
sends it to a running cluster instead.
"""

# %%
import tempfile
from pathlib import Path

import matplotlib.pyplot as plt
import pandas as pd

from pamkit.cluster import client
from pamkit.sweep import load_spec, sweep

spec = load_spec(Path("../../data") / "sweeps" / "pam2_pressure_angle.toml")
print(f"{len(spec.runs)} runs of {spec.names}, {spec.design} design")

# %%
# The workers are processes: started from a script, they import it again, which the guard keeps
# from starting a cluster of their own.
if __name__ == "__main__":
    with tempfile.TemporaryDirectory() as folder, client(workers=2) as connected:
        rows = sweep(spec, Path(folder) / "sweep.csv", connected)
    table = pd.DataFrame(rows)
    print(table[["inflation_pressure_kPa", "braid_angle_deg", "peak_force_N", "stored_energy_J", "error"]])

# %%
if __name__ == "__main__":
    for pressure, runs in table.groupby("inflation_pressure_kPa"):
        plt.plot(runs["braid_angle_deg"], runs["peak_force_N"], "o-", label=f"{pressure:g} kPa")
    plt.xlabel("braid angle [°]")
    plt.ylabel("peak force over the first two cycles [N]")
    plt.legend(title="inflation pressure")
    plt.show()
