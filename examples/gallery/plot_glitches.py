"""
A record with holes and glitches, as a real rig's
=================================================

The bundled bench test (a sealed muscle on a tensile machine, the gas exchanging heat with its
wall) as a real rig might have logged it: 1 % of its force and pressure samples lost (empty cells,
``NaN``), and three samples of each thrown far off by line noise. pamkit reads the file as it is,
leaves out the rows that miss a value and the samples no model explains, says where, and names
the same cause as on the clean record.
"""

# %%
# The record: holes and glitches thrown into a copy of the bundled test.
import shutil
import tempfile
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np

import pamkit

source = Path("../../data") / "experiments" / "example"
folder = Path(tempfile.mkdtemp())
shutil.copy(source / "experiment.toml", folder)
rng = np.random.default_rng(4)
rows = [line.split(",") for line in (source / "experiment.csv").read_text().splitlines()]
header, cells = rows[0], rows[1:]  # time_s, elongation_m, force_N, pressure_kPa, temperature_C
for column, hole, glitch in ((2, "", 80.0), (3, "NaN", 30.0)):  # force [N], pressure [kPa]
    for row in rng.choice(len(cells), len(cells) // 100, replace=False):
        cells[row][column] = hole
    for row in rng.choice(np.arange(10, len(cells) - 10), 3, replace=False):
        if cells[row][column] != hole:
            cells[row][column] = f"{float(cells[row][column]) + rng.choice([-1, 1]) * glitch:.4f}"
lines = [",".join(row) for row in [header, *cells]]
(folder / "experiment.csv").write_text("\n".join(lines) + "\n")

# %%
# Diagnosed: the warnings say what reading and the glitch search left out, and the verdict names
# the heat exchange as on the clean record (its last clause: the glitches, where and how far off).
report = pamkit.diagnose(folder / "experiment.toml", threads=2)
print(report.verdict())
[w for w in report.to_dict()["warnings"] if "reading" in w or "glitches" in w]

# %%
# The figure draws each glitch where it was read (crosses), beside the model it was left out of.
report.figure()
plt.show()
