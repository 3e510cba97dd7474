"""The declared build beside a named pressure transducer's error (series/declared.py): where a muscle
declared a millimetre off draws the transducer's gain, the two are a tie and neither is named; where
the transducer is off, it is named."""

import sys

import numpy as np
from conftest import SOURCE_DIR

from pamkit import Report
from pamkit.diagnosis import diagnose
from pamkit.diagnosis.report import to_json, verdict
from pamkit.diagnosis.series.declared import FREED
from pamkit.io.experiment import load_experiment
from pamkit.synth.dataset import synthesize
from pamkit.synth.mismatch import draw_mismatch

sys.path.insert(0, str(SOURCE_DIR / "tests"))  # tests/independent: a folder, not an installed package
from independent.families import FAMILIES  # noqa: E402

# Every test of bench_families seeds 1-15 where a transducer's gain (1.05-1.07) was named for
# another team's muscle declared off in length (1-2 mm) or diameter (0.3-0.6 mm).
DECLARED_OFF = [("declared_length", 13), ("declared_length", 15), ("declared_diameter", 7), ("declared_diameter", 13)]
# Every transducer's offset bench_diagnose names in its --mismatch worlds (seeds 1000-1077 and
# 3000-3077): its own error, the muscle built otherwise than declared in other ways.
TRANSDUCER_OFF = [1009, 1045, 3033, 3045, 3057]


def test_a_build_declared_off_ties_with_the_transducers_gain(tmp_path):
    for family, seed in DECLARED_OFF:
        data = FAMILIES[family](seed, tmp_path / f"{family}-{seed}")
        d = diagnose(data.experiment, threads=2)
        found = Report(to_json(d)).declared_build
        assert d.cause == "unexplained", (family, seed)
        assert d.decision.rejected.fit.name == "sensor_offset", (family, seed)
        assert found["explains_as_well"], (family, seed)
        assert d.decision.margins["over_declared_build"] <= 0.0, (family, seed)
        assert "a reference gauge on the transducer does" in verdict(d)
        field = "length_m" if family == "declared_length" else "diameter_m"
        declared = getattr(load_experiment(data.experiment).build, field)
        assert found["declared"][field] == declared
        built = declared - data.truth["error_m"]  # the file's value is the built one plus the error
        # the freed field moves toward the muscle as built, within its tolerance
        assert abs(found["values"][field] - built) < abs(declared - built), (family, seed)
        assert abs(found["values"][field] - declared) <= FREED[field] * (1 + 1e-9)
        # a field calibrated at its tolerance's edge is said to be (a bound is a finding)
        for name, value in found["values"].items():
            at_edge = abs(value - found["declared"][name]) >= FREED[name] * (1 - 1e-6)
            assert (name in found["at_tolerance"]) == at_edge
            if at_edge:
                assert f"{name} {1e3 * value:.4g} mm at its tolerance's edge" in verdict(d)


def test_a_transducers_own_error_is_not_offered_a_declared_build(tmp_path):
    for seed in TRANSDUCER_OFF:
        muscle = draw_mismatch(np.random.default_rng([seed, 7]))
        files = synthesize("sensor_offset", seed, tmp_path / str(seed), true_muscle=muscle)
        d = diagnose(load_experiment(files.experiment), threads=2)
        assert d.cause == "sensor_offset", seed
        found = to_json(d)["declared_build"]
        assert not found["explains_as_well"], seed
        assert "reference gauge" not in verdict(d)
        assert "over_declared_build" not in d.decision.margins
