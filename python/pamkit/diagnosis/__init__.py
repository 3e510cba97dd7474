"""Diagnosis: show what the simulation gets wrong, name the cause, extend the model and
measure the gain on cycles it was not fitted to.

``pamkit.diagnose(path_or_experiments)`` runs it and returns a :class:`pamkit.Report`. The
stages are this package's modules (kinds, calibrate, candidates, decide, discover, report); the
functions below are the implementation and stay importable:

    from pamkit.diagnosis import diagnose, to_json, verdict
    d = diagnose("experiment.toml")
    print(verdict(d)); to_json(d)
"""

from pamkit.diagnosis.engine import MIN_GAIN, diagnose
from pamkit.diagnosis.report import plot, to_json, verdict
from pamkit.diagnosis.series.result import Diagnosis

__all__ = ["MIN_GAIN", "Diagnosis", "diagnose", "plot", "to_json", "verdict"]
