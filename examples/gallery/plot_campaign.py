"""
A campaign: two free-inflation tables of one bladder, calibrated together
=========================================================================

Table 3.4 of the reference thesis: the free length and diameter of PAM 1 and PAM 2 inflated with
no load, nine rows. Both muscles share their bladder tube, so the two tables form a campaign: its
thickness, declared unknown, is calibrated on all rows at once, each row predicted by the model
fitted on the others.
"""

# %%
from pathlib import Path

import pamkit

thesis = Path("../../data") / "experiments" / "thesis"
tables = [thesis / "table_3_4_pam1.toml", thesis / "table_3_4_pam2.toml"]
report = pamkit.diagnose(tables, threads=2)
print(report.verdict())

# %%
# The bladder's thickness, calibrated on the nine rows with its jackknife interval.
baseline = report.to_dict()["baseline"]
baseline["params"], baseline["intervals"]

# %%
# Held-out error per channel against the noise: more than twice the noise is left, so the cause
# is ``unexplained`` and sparse regression says what the residual looks like.
report.channels_summary

# %%
print(report.to_dict()["discovered"]["equation"])
