"""A time series' zero run (``[test] zero``): the rig's instruments read with no air and no load,
whose means are taken off the load cell's and the transducer's channels."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from pamkit.io.columns import file_name
from pamkit.io.guards import fail, named_file
from pamkit.io.series import read_series

if TYPE_CHECKING:
    from pamkit.io.experiment import Experiment

ZEROED_CHANNELS = ("force_N", "gauge_pressure_Pa")  # not temperature: with no air, the TMP36 reads the room


def zero(experiment: Experiment, path: Path, name, ignore: tuple[str, ...], atmosphere_Pa: float) -> None:
    """Takes the means of a run with no air (the rig's offset run) off the load cell's and the
    transducer's channels, as a lab zeroes its sensors; records what it took. The offset run of
    a preloaded mount is recorded on the mounted muscle: its force holds the preload, which is
    the muscle's, not the cell's, and stays in the data."""
    run = read_series(named_file(path, "[test] zero", name), ignore=ignore, atmospheric_pressure_Pa=atmosphere_Pa)
    shared = [c for c in ZEROED_CHANNELS if c in run and c in experiment.columns]
    if not shared:
        raise fail(
            path,
            f"[test] zero = {name!r} has none of the channels it could zero "
            f"({', '.join(file_name(channel) for channel in ZEROED_CHANNELS)})",
        )
    for channel in shared:
        offset = float(np.mean(run[channel]))
        if channel == "force_N" and experiment.preload_N is not None:
            offset -= experiment.preload_N
        experiment.columns[channel] = experiment.columns[channel] - offset
        experiment.zeroed[channel] = offset
