"""
A Festo isometric map: calibrate a commercial muscle and name what its model lacks
==================================================================================

A Festo DMSP-10-250 held at five lengths while the supplied pressure is stepped up: the isometric
force map Martens and Boblan (2017) published. Its fibres are embedded in the membrane
(``construction = "embedded"``: the braid cannot push). Festo publishes no braid angle, so the
experiment file declares it unknown in ``[calibrate]``, beside the rest length within 1 % of the
nominal and what stretches in series with the braid (``series_compliance_m_per_N``: the fittings,
the load cell); the diagnosis calibrates them and predicts each held length from the other four.
"""

# %%
# The experiment file declares the muscle as its datasheet does and what is unknown.
from pathlib import Path

import matplotlib.pyplot as plt

import pamkit

data = Path("../../data") / "experiments"
festo = data / "festo" / "DMSP-10-250.toml"
experiment = pamkit.load_experiment(festo)
print(experiment.calibrate)  # name -> [lower, upper]
experiment.to_frame().head()

# %%
# Diagnose: calibrate the baseline on four lengths, predict the fifth, try every catalog effect.
report = pamkit.diagnose(festo, threads=2)
print(report.verdict())

# %%
# The candidates, ranked by their held-out gain; the cause named is the first credible one.
report.candidates[["effect", "score", "significant", "credible", "gain.force_N", "heldout_rmse.force_N"]]

# %%
# The named cause with its calibrated parameters.
report.causes.filter(regex="^(effect|score|params)")

# %%
# The map as measured and as the calibrated baseline and extended model predict it, each held
# length predicted by the model fitted without it.
report.figure()
plt.show()
