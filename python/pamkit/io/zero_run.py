"""A time series' zero run (``[test] zero``): the rig's instruments read with no air and no load,
whose means are taken off the load cell's and the transducer's channels."""

from __future__ import annotations

import warnings
from pathlib import Path

import numpy as np

from pamkit.io.columns import file_name
from pamkit.io.guards import ExperimentWarning, fail, named_file
from pamkit.io.series import read_series

ZEROED_CHANNELS = ("force_N", "gauge_pressure_Pa")  # not temperature: with no air, the TMP36 reads the room

#: How far off the run's median, in the run's noise, a zero run's sample stands when it is a
#: glitch (as a time series' glitches, pamkit.diagnosis.series.glitches): one 150 N stray read in
#: a run of 200 samples would move the offset taken off the whole test by 0.75 N.
ZERO_RUN_GLITCH_SIGMAS = 12.0


def steady_mean(values: np.ndarray) -> tuple[float, int]:
    """The mean of a run that holds still, without its glitches (samples off its median by more
    than ZERO_RUN_GLITCH_SIGMAS times its noise: the median absolute deviation's, or a quantised
    channel's smallest step where most samples read alike), and how many were left out."""
    median = float(np.median(values))
    steps = np.abs(np.diff(values))
    noise = max(1.4826 * float(np.median(np.abs(values - median))), float(steps[steps > 0].min(initial=np.inf)))
    if not np.isfinite(noise):  # every sample alike
        return median, 0
    kept = np.abs(values - median) <= ZERO_RUN_GLITCH_SIGMAS * noise
    return float(np.mean(values[kept])), int(values.size - kept.sum())


def zero_offsets(
    path: Path, name, channels: list[str], preload_N: float | None, ignore: tuple[str, ...], atmosphere_Pa: float
) -> dict[str, float]:
    """What a run with no air (the rig's offset run, `name` relative to the experiment file
    `path`) reads on each of the load cell's and the transducer's channels the test has
    (`channels`): its means, its glitches left out (steady_mean), for a lab to take off as it
    zeroes its sensors. The offset run of a preloaded mount is read on the mounted muscle: its
    force holds the preload (`preload_N`), which is the muscle's, not the cell's, and stays in the
    data."""
    run = read_series(named_file(path, "[test] zero", name), ignore=ignore, atmospheric_pressure_Pa=atmosphere_Pa)
    shared = [c for c in ZEROED_CHANNELS if c in run and c in channels]
    if not shared:
        raise fail(
            path,
            f"[test] zero = {name!r} has none of the channels it could zero "
            f"({', '.join(file_name(channel) for channel in ZEROED_CHANNELS)})",
        )
    offsets = {}
    for channel in shared:
        offset, glitches = steady_mean(run[channel])
        if glitches:
            warnings.warn(
                f"{path}: [test] zero = {name!r}: {glitches} sample(s) of {file_name(channel)} stand over "
                f"{ZERO_RUN_GLITCH_SIGMAS:g} times the run's noise off its median: left out of its mean, as glitches",
                ExperimentWarning,
                3,
            )
        offsets[channel] = offset - preload_N if channel == "force_N" and preload_N is not None else offset
    return offsets
