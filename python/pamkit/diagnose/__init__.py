"""Diagnosis: show what the simulation gets wrong, name the cause, extend the model and
measure the gain on cycles it was not fitted to.

Called as a function, ``pamkit.diagnose(path_or_experiments, effect_catalog=None,
progress=None, threads=None, seed=None)`` returns a :class:`Report` (:func:`diagnose_report`):

    report = pamkit.diagnose("experiment.toml")       # or a list of static tables of one muscle
    print(report.verdict())                           # one sentence: the cause and its held-out gain
    report.to_json("report.json")                     # JSON text (RMSEs in each channel's unit)
    report.plot("report.png")                         # measured vs baseline vs extended, residuals

The functions below are the implementation and stay importable:

    from pamkit.diagnose import diagnose, to_json, verdict
    d = diagnose("experiment.toml")
    print(verdict(d)); to_json(d)
"""

from pamkit._callable import make_callable
from pamkit.diagnose.engine import MIN_GAIN, Diagnosis, diagnose
from pamkit.diagnose.report import Report, diagnose_report, plot, to_json, verdict

__all__ = ["MIN_GAIN", "Diagnosis", "Report", "diagnose", "diagnose_report", "plot", "to_json", "verdict"]

make_callable(__name__, diagnose_report)
