"""
A load cell that reads off, and the zero run that shows by how much
====================================================================

A sealed muscle stretched on a tensile machine; its load cell reads 10 N low, and its membrane is
not the model's. On this one test the two trade: the diagnosis's best reading is a load cell
reading 33 N low beside a membrane with no stiffness at all, which it refuses (an offset no cell
of this kind plausibly has, a scale at its bound), and it asks for the test that reads the
instruments whatever the muscle does: a zero run, the muscle vented and unloaded. Data written by
an independent model of the muscle and rig (``data/experiments/zero_run``; it never imports
pamkit).
"""

# %%
# The test as first run: no cause named, what it looks like, and the zero run to check it.
from pathlib import Path

import matplotlib.pyplot as plt

import pamkit

folder = Path("../../data") / "experiments" / "zero_run"
first = pamkit.diagnose(folder / "test.toml", threads=2)
print(first.verdict())
first.separation["purpose"], first.separation["test"], first.separation["difference_over_noise"]

# %%
# The zero run was taken (``zero.csv``) and named in the test's ``[test] zero``
# (``zeroed.toml``). Its readings are taken off the data, and the offsets it read are known: no fit
# searches them again. The load cell read about 10 N low, not 33; what is left is the membrane, and
# the report says what it looks like.
zeroed = pamkit.diagnose(folder / "zeroed.toml", threads=2)
print(zeroed.verdict())

# %%
zeroed.figure()
plt.show()
