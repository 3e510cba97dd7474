"""What a regulated supply can do, as evidence against a transducer's error: a regulator
supplies air or vents it to the atmosphere, never a vacuum. A supplied test's transducer error
whose correction would put the muscle below zero gauge pressure where a row or sample was read
(a transducer said to read 12 kPa high, on rows read at 0 kPa after venting) is not what the rig
did. Used by a static table's findings (tables/engine.py) and a supplied time series' objections
(series/decide.py)."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from pamkit._core import PRESSURE_BRANCH_PLAY_PA, Effect

# How far below zero gauge a supplied pressure may seem before it is a vacuum: a settled step's
# noise, which a pressure's branch ignores too.
VACUUM_TOLERANCE_PA = PRESSURE_BRANCH_PLAY_PA


def implied_vacuum(effects: Sequence[Effect], time_s, reading_Pa) -> tuple[int, float] | None:
    """The row (or sample) where the transducer errors among `effects` put the true gauge pressure
    lowest, and that pressure [Pa], if it is below -VACUUM_TOLERANCE_PA; else None. `time_s` is
    empty for a table's settled rows."""
    readers = [e for e in effects if e.reads_supplied_pressure()]
    if not readers or len(reading_Pa) == 0:
        return None
    driving = np.asarray(reading_Pa, dtype=float)
    for effect in readers:
        driving = effect.apply_to_supplied_pressure(time_s, driving)
    lowest = int(np.argmin(driving))
    return (lowest, float(driving[lowest])) if driving[lowest] < -VACUUM_TOLERANCE_PA else None
