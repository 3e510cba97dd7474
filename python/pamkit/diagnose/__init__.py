"""Diagnosis: show what the simulation gets wrong, name the cause, extend the model and
measure the gain on cycles it was not fitted to.

    from pamkit.diagnose import diagnose, to_json, verdict
    d = diagnose("experiment.toml")
    print(verdict(d)); to_json(d)
"""

from pamkit.diagnose.engine import MIN_GAIN, Diagnosis, diagnose
from pamkit.diagnose.report import plot, to_json, verdict

__all__ = ["MIN_GAIN", "Diagnosis", "diagnose", "plot", "to_json", "verdict"]
