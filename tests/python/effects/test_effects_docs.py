"""docs/effects.md against the code: the catalog table, written from the catalog, says what the
effects' C++ headers say, every effect has its gallery plot, and the user-effect example runs
(through simulate and synth). Adding a catalog effect is its header, its test and its line in
catalog.hpp; its gallery figure is drawn by a generic plot unless it has one of its own."""

from __future__ import annotations

import gc
import importlib.util
import json
import os
import re
from pathlib import Path

import numpy as np
import pytest

import pamkit
from pamkit.effects import GIVES_IT_AWAY, catalog, describe, parse_effects, table_rows
from pamkit.io.experiment import load_experiment
from pamkit.simulation import simulate_experiment
from pamkit.synth.dataset import synthesize

SOURCE_DIR = Path(os.environ.get("PAMKIT_SOURCE_DIR", Path(__file__).resolve().parents[3]))
DOC = SOURCE_DIR / "docs" / "effects.md"
GALLERY_DIR = SOURCE_DIR / "docs" / "effects"
PARAMETER = re.compile(r"`(\w+)` \[([^\]]+)\]: (-?[\d.]+)–(-?[\d.]+) \(default (-?[\d.]+)\)")
OPTION = re.compile(r"`(\w+)` \(default `(\w+)`\)")


def test_the_table_lists_every_effect_with_the_catalogs_units_ranges_and_defaults():
    # The documentation's table is written from table_rows when the site is built: each row must
    # carry its effect's parameters as the header declares them, its options, and both halves of
    # its description.
    assert "```{eval-rst}\n.. pamkit-reference:: effect-table\n```" in DOC.read_text()
    rows = {name: row for name, *row in table_rows()}
    assert sorted(rows) == sorted(catalog().names())
    for name, (cell, what, away) in rows.items():
        effect = catalog().make(name)
        row_text = " ".join(f"{what} {GIVES_IT_AWAY} {away}".split())
        assert what and away and row_text == " ".join(effect.description().split()), name
        documented = {m.group(1): m.groups()[1:] for m in map(PARAMETER.search, cell.split("; ")) if m}
        assert sorted(documented) == sorted(p.name for p in effect.parameters()), name
        for p in effect.parameters():
            unit, lo, hi, default = documented[p.name]
            assert unit == p.unit, (name, p.name)
            assert (float(lo), float(hi), float(default)) == (p.realistic_min, p.realistic_max, p.value), (name, p.name)
        options = dict(m.groups() for m in map(OPTION.search, cell.split("; ")) if m)
        assert options == effect.options(), name


def gallery_module():
    spec = importlib.util.spec_from_file_location("effects_gallery", SOURCE_DIR / "validation" / "effects_gallery.py")
    gallery = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(gallery)
    return gallery


def test_every_effect_has_its_header_and_its_physics_test():
    for name in catalog().names():
        assert (SOURCE_DIR / "include" / "pamkit" / "effects" / "builtin" / f"{name}.hpp").is_file(), name
        test = SOURCE_DIR / "tests" / "cpp" / "effects" / f"{name}.test.cpp"
        assert re.search(rf'TEST_CASE\(\s*"{name}: ', test.read_text()), name


def test_every_effect_has_a_small_gallery_plot_shown_in_the_doc():
    # The page's gallery is written from the catalog when the site is built, each figure with its
    # caption (effects_gallery.caption): every effect needs its committed figure and a caption.
    assert "```{eval-rst}\n.. pamkit-reference:: effect-gallery\n```" in DOC.read_text()
    gallery = gallery_module()
    assert set(gallery.FIGURES) <= set(catalog().names())  # no figure for an effect that is gone
    for name in catalog().names():
        png = GALLERY_DIR / f"{name}.png"
        assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n", name
        assert png.stat().st_size < 150_000, name  # the README gallery's budget per plot
        own = gallery.FIGURES.get(name)
        assert own is None or own.__doc__, name  # a figure of its own says what it shows
        assert len(gallery.caption(name).split()) >= 5, name


def test_an_effect_without_a_figure_of_its_own_gets_the_generic_one(tmp_path):
    # The doc's user effect stands for a new catalog effect: a measurement effect on force_N.
    effects = user_effect_example()["effects"]
    png = gallery_module().generic("load_cell_drift", effects, tmp_path)
    assert png == tmp_path / "load_cell_drift.png"
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert png.stat().st_size < 150_000


def user_effect_example() -> dict:
    """Runs the doc's Python example; returns its namespace."""
    blocks = re.findall(r"```python\n(.*?)```", DOC.read_text(), flags=re.S)
    example = next(block for block in blocks if "class LoadCellDrift" in block)
    namespace: dict = {}
    exec(compile(example, str(DOC), "exec"), namespace)
    return namespace


def test_the_user_effect_example_runs_through_simulate_and_synth(tmp_path):
    namespace = user_effect_example()
    effects = namespace["effects"]
    assert "load_cell_drift" in effects.names() and "heat_transfer" in effects.names()
    drift = namespace["drift"]
    gc.collect()  # the effect made by the catalog outlives the factory's Python result
    assert drift.parameters()[0].value == 0.02
    assert "load_cell_drift" in describe(effects)

    experiment = load_experiment(SOURCE_DIR / "data" / "experiments" / "thesis" / "pam2_207kPa_90pct.toml")
    baseline = simulate_experiment(experiment)
    drifted = simulate_experiment(experiment, effects=parse_effects(["load_cell_drift:rate_N_per_s=0.02"], effects))
    # A zero drifting at 0.02 N/s: the force is up by 0.02 x t, the rest unchanged.
    np.testing.assert_allclose(drifted["force_N"] - baseline["force_N"], 0.02 * experiment.time_s, atol=1e-9)
    np.testing.assert_array_equal(drifted["gauge_pressure_Pa"], baseline["gauge_pressure_Pa"])

    files = synthesize("load_cell_drift", 3, tmp_path / "drift", effects)
    truth = json.loads(files.manifest.read_text())["effect"]
    assert truth["drawn"] == ["rate_N_per_s"]
    assert -0.05 <= truth["parameters"]["rate_N_per_s"] <= 0.05  # the example's realistic range

    with pytest.raises(ValueError, match="no parameter 'rate'"):
        effects.parse("load_cell_drift:rate=1")
    assert isinstance(drift, pamkit.Effect)
