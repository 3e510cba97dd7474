"""
One held length: a cut muscle pressurised and vented where it is mounted
=========================================================================

A lab's first test of a commercial muscle cut to length: its ends clamped at one length, the
supplied pressure stepped up to 600 kPa and vented, twice, the force read at each settled step.
The data come from an independent model of a DMSP-10-like muscle cut to 10 cm
(``tests/independent/dmsp.py``, which never imports pamkit), mounted 1.5 mm short of its rest
length: at low pressure it is slack and contracts until it pulls taut, and the friction between
its fibres and membrane keeps what it took up on the way. One held length cannot be held out
against others, so the diagnosis holds out each pressurising and venting run in turn.
"""

# %%
from pathlib import Path

import matplotlib.pyplot as plt

import pamkit

data = Path("../../data") / "experiments"
isometric = data / "isometric" / "isometric.toml"
report = pamkit.diagnose(isometric, threads=2)
print(report.verdict())

# %%
# Every candidate on the held-out runs. A transducer reading 29 kPa high fits the same line as the
# friction, but beyond the 15 kPa a calibration by hand leaves, and the rows read at 0 kPa after
# venting would then have held a vacuum, which a regulator never supplies: it is not named.
report.candidates[["effect", "score", "significant", "credible"]]

# %%
# Each run as measured and as predicted by the model fitted without it: dotted the calibrated
# baseline, which misses the force the friction took up while the slack muscle contracted.
report.figure()
plt.show()
