"""What a diagnosis imports before it starts: heavy optional modules only where they are used
(figures, discovery's sparse regression, clusters, tables), never at `import pamkit.diagnosis`.
Which modules are loaded does not depend on the machine's load; the time they cost is measured
by bench/bench_import.py, not here."""

import json
import os
import subprocess
import sys
from pathlib import Path

from pamkit.synth.dataset import synthesize

# Each costs a user a sizeable share of a second at start-up (python -X importtime): scipy.signal
# (which brings scipy.stats), scipy.ndimage, matplotlib, scikit-learn, pandas, Dask.
DEFERRED = ("scipy.signal", "scipy.stats", "scipy.ndimage", "matplotlib", "sklearn", "pandas", "dask", "distributed")


def loaded_after(code: str) -> list[str]:
    """The DEFERRED modules a fresh interpreter holds after running `code`."""
    probe = f"{code}\nimport json, sys\nprint(json.dumps([m for m in {DEFERRED!r} if m in sys.modules]))"
    done = subprocess.run(
        [sys.executable, "-c", probe], capture_output=True, text=True, env=os.environ.copy(), timeout=300
    )
    assert done.returncode == 0, done.stderr
    return json.loads(done.stdout.splitlines()[-1])


def test_the_probe_sees_a_deferred_module_when_it_is_imported():
    """The check below can fail: importing one of the modules is seen."""
    assert "scipy.signal" in loaded_after("import scipy.signal")
    assert loaded_after("import matplotlib") == ["matplotlib"]


def test_importing_the_diagnosis_imports_no_heavy_optional_module():
    assert loaded_after("import pamkit.diagnosis") == []


def test_a_diagnosis_without_a_figure_never_imports_matplotlib(tmp_path: Path):
    """`pamkit diagnose` draws only with --plot; a JSON report needs no figure. (scikit-learn,
    should discovery run, does not import scipy.signal either.)"""
    files = synthesize("none", 1000, tmp_path / "data")
    report = tmp_path / "report.json"
    arguments = ["diagnose", str(files.experiment), "--json", str(report), "--quiet", "--threads", "1"]
    loaded = loaded_after(f"from pamkit.cli import main\nassert main({arguments!r}) == 0")
    assert report.exists()
    assert "matplotlib" not in loaded
    assert "scipy.signal" not in loaded


def test_a_diagnosis_that_runs_the_sparse_regression_never_imports_scikit_learn(tmp_path: Path):
    """Discovery's matching pursuit is numpy's (scikit-learn's import cost 1.6 s of a 2.4 s
    diagnosis): an out-of-catalog friction, which leaves a remainder, is searched without it."""
    from conftest import SOURCE_DIR

    sys.path.insert(0, str(SOURCE_DIR / "tests"))  # tests/independent: a folder, not an installed package
    from independent.families import FAMILIES

    dataset = FAMILIES["coulomb_alternating"](1, tmp_path / "data")
    report = tmp_path / "report.json"
    arguments = ["diagnose", str(dataset.experiment), "--json", str(report), "--quiet", "--threads", "1"]
    loaded = loaded_after(f"from pamkit.cli import main\nassert main({arguments!r}) == 0")
    # No term, the offset, then one model per step of the pursuit: it ran.
    assert len(json.loads(report.read_text())["discovered"]["heldout_rmse_path"]) > 2, "no pursuit ran"
    assert "sklearn" not in loaded
