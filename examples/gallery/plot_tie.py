"""
Two causes one test cannot tell apart, and the test that can
============================================================

A sealed muscle stretched on a tensile machine, its gas reaching a volume outside the muscle (a
hose, the transducer's cavity: a dead volume). On one test at one inflation pressure, fibres that
stretch under their tension explain the data as well: the diagnosis names neither, and says which
test would tell them apart. That test was run on the same muscle; diagnosed together, the two
tests name the cause. Data written by an independent model of the muscle and rig
(``data/experiments/tie``; it never imports pamkit).
"""

# %%
# The first test alone: a tie, and the test that would break it.
from pathlib import Path

import matplotlib.pyplot as plt

import pamkit

tie = Path("../../data") / "experiments" / "tie"
first = pamkit.diagnose(tie / "first" / "test.toml", threads=2)
print(first.verdict())

# %%
# The test named, and how far apart the two fitted models are there and on the test as run, in
# units of each channel's noise.
separation = first.separation
separation["purpose"], separation["test"], separation["difference_over_noise"], separation["here_over_noise"]

# %%
# The figure's last row: the two models on that test.
first.figure()
plt.show()

# %%
# The named test was run (``second/``: the same muscle inflated half as high again). Diagnosed
# beside the first as one campaign, each candidate of the tie is carried from one test to the
# other: the dead volume's one fraction gains on both, the fibres' two stiffnesses do not agree.
# Alone, the second test names the fibres (where the independent muscle departs from pamkit's, at
# the higher pressure, their stiffness takes the misfit): one test is one reading, the campaign
# asks that a cause hold on both.
both = pamkit.diagnose(tie / "campaign.toml", threads=2)
print(both.verdict())
