"""A cause in no catalog, hidden in pamkit's own world: a load cell whose zero creeps at a constant
rate (a strain gauge warming up), written by `pamkit synth` as a user's own effect, at a realistic
rate drawn per seed (±0.2 N/s). The diagnosis must name no catalog effect for it, as a rate over
twelve seeds. It does not yet: where the creep is weak (2.3-4.4 N over the test) and the base
model exact, the viscoelastic bladder's start-up transient takes it on 3 of 12 seeds
(docs/validation.md, "Data pamkit did not make"); the test is expected to fail (strict), so that
the day it passes the figure is updated."""

from concurrent.futures import ThreadPoolExecutor

import numpy as np
import pytest

import pamkit
from pamkit.diagnosis import diagnose, to_json
from pamkit.effects import catalog as builtin_catalog
from pamkit.synth.dataset import synthesize

SEEDS = range(1, 13)


class LoadCellCreep(pamkit.Effect):
    """The load cell's reading plus rate · (t - t0)."""

    def __init__(self):
        super().__init__()
        self.rate = 0.05

    def name(self):
        return "load_cell_creep"

    def description(self):
        return "the load cell's zero creeps at a constant rate"

    def parameters(self):
        return [pamkit.EffectParameter("rate_N_per_s", self.rate, "N/s", -1.0, 1.0, -0.2, 0.2, "creep rate")]

    def set(self, key, value):
        self.rate = float(value)

    def apply_to_measurement(self, measurement):
        time_s = np.asarray(measurement.time_s)
        measurement.force_N = measurement.force_N + self.rate * (time_s - time_s[0])
        return measurement


WHY = "a weak creep is named bladder_viscoelasticity on 3 of 12 seeds (module docstring)"


@pytest.mark.xfail(strict=True, reason=WHY)
def test_a_creeping_load_cell_zero_is_named_no_catalog_effect(tmp_path):
    hidden = builtin_catalog()
    hidden.add("load_cell_creep", LoadCellCreep)

    def names(seed):
        files = synthesize("load_cell_creep", seed, tmp_path / str(seed), effect_catalog=hidden)
        return [c["effect"] for c in to_json(diagnose(files.experiment, threads=1))["causes"]]

    with ThreadPoolExecutor(2) as pool:
        named = dict(zip(SEEDS, pool.map(names, SEEDS)))
    assert not any(named.values()), named
