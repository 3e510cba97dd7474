"""The example tests of data/experiments/isometric, isotonic, supplied, tie and zero_run are what
validation/example_data.py writes with the independent model (tests/independent): regenerated here
and compared file by file."""

import importlib.util
import os
from pathlib import Path

SOURCE_DIR = Path(os.environ.get("PAMKIT_SOURCE_DIR", Path(__file__).resolve().parents[2]))
EXPERIMENTS = SOURCE_DIR / "data" / "experiments"


def generator():
    spec = importlib.util.spec_from_file_location("example_data", SOURCE_DIR / "validation" / "example_data.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_the_committed_examples_are_what_the_generator_writes(tmp_path):
    written = generator().write(tmp_path)
    assert [p.relative_to(tmp_path).as_posix() for p in written] == [
        "isometric/isometric.csv",
        "isometric/isometric.toml",
        "isotonic/isotonic.csv",
        "isotonic/isotonic.toml",
        "supplied/isometric_sweep.csv",
        "supplied/isometric_sweep.toml",
        "tie/campaign.toml",
        "tie/first/test.csv",
        "tie/first/test.toml",
        "tie/second/test.csv",
        "tie/second/test.toml",
        "zero_run/test.csv",
        "zero_run/test.toml",
        "zero_run/zero.csv",
        "zero_run/zeroed.toml",
    ]
    for path in written:
        relative = path.relative_to(tmp_path)
        assert path.read_bytes() == (EXPERIMENTS / relative).read_bytes(), f"{relative} differs: regenerate"
