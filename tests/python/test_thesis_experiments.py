"""The thesis's bench tests in data/experiments/thesis are what validation/thesis_experiments.py
writes from the thesis's tables (3.4, 3.5, C.1-C.4): regenerated here and compared file by file."""

import importlib.util
import os
from pathlib import Path

SOURCE_DIR = Path(os.environ.get("PAMKIT_SOURCE_DIR", Path(__file__).resolve().parents[2]))
COMMITTED = SOURCE_DIR / "data" / "experiments" / "thesis"


def generator():
    spec = importlib.util.spec_from_file_location(
        "thesis_experiments", SOURCE_DIR / "validation" / "thesis_experiments.py"
    )
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_the_committed_thesis_tests_are_what_the_generator_writes(tmp_path):
    written = generator().write_all(tmp_path)
    # PAM 1 at six low pressures (tables 3.4-3.5) and PAM 2 at three pressures and three stretches
    # (tables C.1-C.3); table 3.4's free-inflation tables beside them are transcribed, not generated.
    assert len(written) == 15
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted(p.name for p in COMMITTED.glob("pam*pct.*"))
    for path in sorted(tmp_path.iterdir()):
        assert path.read_bytes() == (COMMITTED / path.name).read_bytes(), f"{path.name} differs: regenerate"
