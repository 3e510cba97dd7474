"""
An isotonic sweep: the length under a hanging load as the pressure goes up and down
====================================================================================

A 10 mm muscle carries a weighed 100 N while the supplied pressure is swept from 0 to 600 kPa and
back three times, the length read at each settled step. The data come from an independent model
of a braided muscle (``tests/independent``, which never imports pamkit) with pressurise/vent
friction hidden in it. The diagnosis holds out each sweep in turn.
"""

# %%
from pathlib import Path

import matplotlib.pyplot as plt

import pamkit

data = Path("../../data") / "experiments"
isotonic = data / "isotonic" / "isotonic.toml"
report = pamkit.diagnose(isotonic, threads=2)
print(report.verdict())

# %%
# What each candidate gains on the held-out sweeps.
report.candidates[["effect", "score", "significant", "credible"]]

# %%
# The calibrated braid angle and membrane, with their 95 % intervals (a jackknife over sweeps).
extended = report.to_dict()["extended"]
{name: (value, extended["intervals"].get(name)) for name, value in extended["params"].items()}

# %%
# The baseline predicts one length per pressure; the named cause opens the loop the data show.
measured = pamkit.load_experiment(isotonic).to_frame()
baseline = pamkit.simulate(isotonic)
# The frames are SI (gauge_pressure_Pa, length_m); the figure is in kPa and mm.
plt.plot(measured["gauge_pressure_Pa"] / 1e3, 1e3 * measured["length_m"], ".", label="measured")
plt.plot(baseline["gauge_pressure_Pa"] / 1e3, 1e3 * baseline["length_m"], label="declared model (before calibration)")
plt.xlabel("supplied gauge pressure [kPa]")
plt.ylabel("length [mm]")
plt.legend()
plt.show()
