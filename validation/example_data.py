"""Writes the example tests of data/experiments/ that pamkit did not make: measured-style data from
the independent muscle and rig of tests/independent (its own braid, membrane, friction and
instruments; it never imports pamkit), so that the examples show the diagnosis on data it did not
simulate itself.

    data/experiments/isotonic/   a 10 mm commercial-style muscle under a hanging 100 N, the supplied
                                 pressure swept from 0 to 600 kPa and back three times in settled
                                 steps, pressurise/vent friction hidden (tests/independent/static_map.py)
    data/experiments/supplied/   PAM 2 of the thesis held at a fixed length on a pressure regulator, the
                                 pressure stepped up to its top and vented, force and pressure logged
                                 at 20 Hz (tests/independent/families.py, isometric_sweep, seed 3)
    data/experiments/isometric/  a DMSP-10-like muscle cut to 10 cm, mounted 1.5 mm short of its rest
                                 length, pressurised in 25 kPa steps to 600 kPa and vented twice at that
                                 one held length, friction with memory hidden (tests/independent/dmsp.py)
    data/experiments/tie/        a sealed cyclic test of a muscle with a dead volume (first/), which on
                                 its own ties with stretching fibres, and the same test inflated half
                                 as high again (second/), an inflation that tells them apart (the
                                 tie's report names twice the pressure, which parts them more);
                                 campaign.toml diagnoses the two together
                                 (independent_dead_volume_two_inflations, seed 1)
    data/experiments/zero_run/   a sealed cyclic test whose load cell reads 10 N low, on a muscle whose
                                 membrane is not the model's (test.toml), and the same test with the
                                 zero run its report asks for (zeroed.toml, zero.csv)
                                 (tests/independent/near_families.py, load_cell strong, seed 9)

Run ``python validation/example_data.py [-o data/experiments]``; the committed files are what it
writes (tests/python/test_example_data.py).
"""

from __future__ import annotations

import argparse
import shutil
import sys
import tempfile
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests"))  # tests/independent: a folder, not an installed package

from independent.dmsp import DmspTruth, write_dmsp_isometric  # noqa: E402
from independent.families import independent_dead_volume_two_inflations, isometric_sweep  # noqa: E402
from independent.near_families import FAMILIES  # noqa: E402
from independent.static_map import write_isotonic  # noqa: E402

# A 10 mm muscle as the independent model builds it (Gaylord's braid, a neo-Hookean wall
# pre-stretched on the braid): the values tests/python/diagnose/test_tables.py hides.
ISOTONIC_TRUTH = dict(
    rest_length_m=0.25,
    diameter_m=0.01,
    braid_angle_deg=24.0,
    shear_modulus_Pa=1.5e6,
    thickness_m=0.5e-3,
    prestretch=1.06,
)
ISOTONIC_LOAD_N = 100.0
ISOTONIC_HYSTERESIS = 0.1
SUPPLIED_SEED = 3
TIE_SEED = 1
ZERO_RUN_SEED = 9
# A DMSP-10 cut to 10 cm: the braid and friction of tests/python/diagnose/test_dmsp.py's seed 21.
ISOMETRIC_TRUTH = DmspTruth(
    rest_length_m=0.10, braid_angle_deg=23.0, end_zone_m=0.008, slip_force_N=150.0, slip_distance_m=0.02
)
ISOMETRIC_HELD_M = 0.0985


def write(folder: Path) -> list[Path]:
    """Writes the examples under `folder` (data/experiments); returns the files written."""
    up = list(np.arange(0.0, 601.0, 50.0))
    sweep = up + up[::-1][1:]
    isotonic = folder / "isotonic"
    toml = write_isotonic(
        isotonic,
        sweeps=[sweep] * 3,
        load_N=ISOTONIC_LOAD_N,
        hysteresis=ISOTONIC_HYSTERESIS,
        seed=7,
        **ISOTONIC_TRUTH,
    )
    # The load hangs from the muscle and was weighed: the file declares it, not [calibrate].
    text = toml.read_text().replace("load_N = [1.0, 500.0]\n", "")
    text = text.replace('kind = "isotonic"\n', f'kind = "isotonic"\nload_N = {ISOTONIC_LOAD_N}\n')
    toml.write_text(
        "# An isotonic test written by validation/example_data.py with the independent model of\n"
        "# tests/independent (not pamkit): a 10 mm muscle under a weighed 100 N, the supplied pressure swept\n"
        "# 0-600 kPa and back three times in settled steps. Its braid angle and membrane are to calibrate.\n\n" + text
    )
    with tempfile.TemporaryDirectory() as work:
        dataset = isometric_sweep(SUPPLIED_SEED, Path(work))
        supplied = folder / "supplied"
        supplied.mkdir(parents=True, exist_ok=True)
        for source in Path(work).iterdir():
            shutil.copy(source, supplied / source.name.replace("test", "isometric_sweep"))
        toml_text = (supplied / "isometric_sweep.toml").read_text().replace("test.csv", "isometric_sweep.csv")
        toml_text = "# validation/example_data.py: the independent rig's sweep of seed 3.\n" + toml_text
        (supplied / "isometric_sweep.toml").write_text(toml_text)
        del dataset
    isometric = write_dmsp_isometric(
        folder / "isometric", ISOMETRIC_TRUTH, lengths_m=[ISOMETRIC_HELD_M], top_kPa=600, seed=21
    )
    isometric.write_text(
        "# validation/example_data.py: the independent model's DMSP-10-like muscle (tests/independent/dmsp.py),\n"
        "# cut to 10 cm and mounted 1.5 mm short, pressurised to 600 kPa and vented twice at one held length.\n"
        + isometric.read_text()
    )
    tie = folder / "tie"
    campaign = independent_dead_volume_two_inflations(TIE_SEED, tie).experiment
    campaign.write_text(
        "# validation/example_data.py: a dead volume the first test alone cannot tell from stretching fibres,\n"
        "# and another inflation of it, which tells them apart, run on the same independent muscle.\n"
        + campaign.read_text()
    )
    zero_run = folder / "zero_run"
    FAMILIES["load_cell"].make(ZERO_RUN_SEED, zero_run, "strong", {"zero_run": True})
    zeroed = (zero_run / "test.toml").read_text()
    (zero_run / "test.toml").write_text(
        "# validation/example_data.py: a sealed cyclic test whose load cell reads off, as first run (no zero run).\n"
        + zeroed.replace('zero = "zero.csv"\n', "")
    )
    (zero_run / "zeroed.toml").write_text(
        "# validation/example_data.py: the same test with the zero run its report asks for.\n" + zeroed
    )
    examples = [
        *isotonic.iterdir(),
        *isometric.parent.iterdir(),
        *supplied.iterdir(),
        *tie.rglob("*"),
        *zero_run.iterdir(),
    ]
    return sorted(p for p in examples if p.is_file())


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("-o", "--output", default=str(ROOT / "data" / "experiments"), help="the folder to write into")
    for path in write(Path(parser.parse_args().output)):
        print(f"wrote {path}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
