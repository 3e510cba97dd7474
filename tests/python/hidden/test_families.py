"""Families of tests that hide a cause in measured data made outside pamkit (docs/validation.md,
"Data pamkit did not make"). tests/independent writes each dataset with its own model of a braided muscle and
of the bench's instruments (it never imports pamkit); `pamkit diagnose` sees the TOML and CSV
only. One seed per family here; bench/bench_families.py sweeps more.

The assertions marked ACCEPTANCE are the diagnosis's promises: a catalog name only when it is the
truth ("never a wrong name"), `none` only when every channel's held-out RMSE is within the
report's stated factor of its noise (rule 5 of docs/diagnosis.md; the factor and its source are in
python/pamkit/diagnosis/series/decide.py), and the hidden effect named when it is in the catalog.
"""

import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

SOURCE_DIR = Path(os.environ.get("PAMKIT_SOURCE_DIR", Path(__file__).resolve().parents[3]))
sys.path.insert(0, str(SOURCE_DIR / "tests"))  # tests/independent: a folder, not an installed package

from independent.families import FAMILIES, HONEST, Dataset  # noqa: E402 (needs the path above)
from independent.physics import Build, Geometry, Motion, Physics, SealedMuscle  # noqa: E402

SEED = 1
# The catalog families, named as a rate over seeds 1-3 (bench/bench_families.py's): at least two of
# three, the target the diagnosis is held to. The load cell's two are not met and are expected to
# fail (strict: a pass fails the suite until the figure here is updated): the independent wall keeps its thickness
# where pamkit's conserves its volume, which leaves force and pressure about 1.9x the noise even
# with the braid's wind calibrated, and a load cell's offset or nonlinearity explains only a share
# of that force (1.8-2.0x left): indistinguishable from the share it takes of the same misfit on
# the family's nulls, so it is refused (rule 6 of docs/diagnosis.md), never named wrongly.
CATALOG_FAMILIES = (
    "independent_heat_transfer",
    "independent_leak",
    "dmsp_map_one_within",
    "dmsp_isotonic",
    "dmsp_map_transducer_offset",
    "independent_dead_volume_two_inflations",
)
LOAD_CELL_FAMILIES = ("load_cell_tare", "load_cell_nonlinear")
# The dead volume is not met either (strict, as above): fibres that stretch under the hoop
# stress's pull (fiber_compliance, EA 90-180 N per fibre fitted, inside its plausible range: a
# 0.25 mm nylon strand has 100-250 N) soften the pressure's swing with the stroke as a dead volume
# does, and on one sealed test at one inflation pressure the two gain alike (0.66 and 0.66, 0.75 and
# 0.75 on seeds 1 and 2, the paired difference's interval holding zero). What the user must get
# then is the pair: the verdict names the truth as one of two the data do not tell apart, and the
# test that would part them (a higher inflation). That test run too, the two diagnosed as one
# campaign name the dead volume: independent_dead_volume_two_inflations, a catalog family above.
TIED_FAMILIES = ("independent_dead_volume",)
TIE = "the data do not tell the two apart"
RATE_SEEDS = (1, 2, 3)
MIN_NAMED = 2
# Another team's muscle with nothing hidden, over fifteen seeds (bench_families' independent_null):
# its misfit, read as a load cell's offset of -12 to -19 N, named a load cell at seeds 8, 12, 14
# and 15 before a load cell had to gain MISREAD_GAIN on the force (rule 6 of docs/diagnosis.md,
# chosen on seeds 1-12); now at seed 12 only, gaining 0.11.
NULL_SEEDS = range(1, 16)
MAX_NULLS_NAMED = 1


def diagnose(toml: Path) -> dict:
    report = toml.with_name("report.json")
    done = subprocess.run(
        [sys.executable, "-m", "pamkit", "diagnose", str(toml), "--json", str(report), "--quiet"],
        check=False,
        capture_output=True,
        text=True,
        env=os.environ.copy(),
        timeout=600,
    )
    assert done.returncode == 0, f"diagnose failed: {done.stderr.strip()[-500:]}"
    return json.loads(report.read_text())


def named(dataset: Dataset, report: dict) -> set[str]:
    """The catalog names a report gives, less the physics the dataset shows by construction."""
    return {c["effect"].split(":")[0] for c in report["causes"]} - set(dataset.present)


@pytest.mark.parametrize("family", list(FAMILIES))
def test_diagnosis_of_a_family(family, tmp_path):
    dataset = FAMILIES[family](SEED, tmp_path / "seen")
    report = diagnose(dataset.experiment)
    cause, verdict = report["cause"], report["verdict"]
    # ACCEPTANCE ("never a wrong name"): every cause named is the truth, or physics the independent
    # model has built in and this dataset shows (its braid went slack where its force would turn
    # negative); for a cause outside the catalog or below what the sampling resolves, none.
    names = named(dataset, report)
    allowed = set() if dataset.expected == HONEST else {dataset.expected}
    assert names <= allowed, f"hidden {dataset.expected} {dataset.truth}, named {sorted(names)}: {verdict}"
    if cause == "none" and "evidence" in report:
        # ACCEPTANCE (rule 5 of docs/diagnosis.md): `none` only when nothing but noise is left.
        rmse, noise = report["baseline"]["rmse"], report["evidence"]["noise"]
        factor = report["evidence"]["none_within_noise"]
        left = {c: round(rmse[c] / noise[c], 2) for c in rmse if rmse[c] > factor * noise[c]}
        assert not left, f"none with held-out RMSE / noise {left}: {verdict}"
    elif cause == "none" and report.get("kind") == "campaign":
        # A campaign's `none`: every test's own diagnosis says none, under the rule above.
        assert all(test["cause"] == "none" for test in report["per_test"]), verdict
    elif cause == "none":
        # A table's `none` (rule 4 of its rules): every channel held out within the factor, which
        # its report states as nothing left.
        assert report["remainder"] is None, f"none with {report['remainder']['channels']} left: {verdict}"


def seed_reports(family: str, tmp_path) -> list[tuple[Dataset, dict]]:
    """Each of RATE_SEEDS's dataset and report; none names another cause (the test above's
    promise, asserted here too)."""
    runs = []
    for seed in RATE_SEEDS:
        dataset = FAMILIES[family](seed, tmp_path / str(seed))
        report = diagnose(dataset.experiment)
        assert named(dataset, report) <= {dataset.expected}, f"seed {seed}: {report['verdict']}"
        runs.append((dataset, report))
    return runs


def test_another_teams_null_is_named_a_cause_in_at_most_one_seed_of_fifteen(tmp_path):
    # ACCEPTANCE ("never a wrong name", as a rate): the base model's misfit is not a cause.
    named_at = {}
    for seed in NULL_SEEDS:
        dataset = FAMILIES["independent_null"](seed, tmp_path / str(seed))
        report = diagnose(dataset.experiment)
        if named(dataset, report):
            named_at[seed] = report["verdict"][:300]
    assert len(named_at) <= MAX_NULLS_NAMED, named_at


def verdicts(runs) -> str:
    return "\n".join(f"seed {seed}: {report['verdict'][:400]}" for seed, (_, report) in zip(RATE_SEEDS, runs))


def expected_to_fail(families, why):
    return [pytest.param(family, marks=pytest.mark.xfail(strict=True, reason=why)) for family in families]


@pytest.mark.parametrize(
    "family",
    [
        *CATALOG_FAMILIES,
        *expected_to_fail(TIED_FAMILIES, "see TIED_FAMILIES: a dead volume and compliant fibres gain alike"),
        *expected_to_fail(LOAD_CELL_FAMILIES, "see LOAD_CELL_FAMILIES: refused beside the independent wall's misfit"),
    ],
)
def test_a_catalog_cause_is_named_in_two_of_three_seeds(family, tmp_path):
    # ACCEPTANCE ("the truth when it is in the catalog", on data an independent implementation made).
    runs = seed_reports(family, tmp_path)
    hits = sum(dataset.expected in named(dataset, report) for dataset, report in runs)
    assert hits >= MIN_NAMED, verdicts(runs)


@pytest.mark.parametrize("family", TIED_FAMILIES)
def test_a_dead_volume_is_named_or_shown_tied_with_its_rival_in_two_of_three_seeds(family, tmp_path):
    # ACCEPTANCE (a weaker promise than naming, see TIED_FAMILIES): the truth named, or the verdict
    # says it and a rival explain the held-out units alike; no wrong name either way.
    runs = seed_reports(family, tmp_path)
    shown = sum(
        dataset.expected in named(dataset, report)
        or (TIE in report["verdict"] and dataset.expected in report["verdict"])
        for dataset, report in runs
    )
    assert shown >= MIN_NAMED, verdicts(runs)


# The generator itself: independent, deterministic, and physically consistent.


def test_the_generator_never_imports_pamkit(tmp_path):
    script = (
        "import sys; from pathlib import Path; from independent.families import FAMILIES\n"
        "for name, make in FAMILIES.items(): make(3, Path(sys.argv[1]) / name)\n"
        "assert not any(m == 'pamkit' or m.startswith('pamkit.') for m in sys.modules), 'pamkit was imported'\n"
    )
    env = {**os.environ, "PYTHONPATH": str(SOURCE_DIR / "tests")}
    done = subprocess.run(
        [sys.executable, "-c", script, str(tmp_path)], check=False, capture_output=True, text=True, env=env, timeout=300
    )
    assert done.returncode == 0, done.stderr


@pytest.mark.parametrize("family", ["independent_leak", "dahl", "isometric_transducer_offset"])
def test_the_same_seed_writes_the_same_bytes(family, tmp_path):
    first = FAMILIES[family](5, tmp_path / "a")
    second = FAMILIES[family](5, tmp_path / "b")
    assert first.experiment.with_suffix(".csv").read_bytes() == second.experiment.with_suffix(".csv").read_bytes()
    other = FAMILIES[family](6, tmp_path / "c")
    assert other.experiment.with_suffix(".csv").read_bytes() != first.experiment.with_suffix(".csv").read_bytes()


def test_static_tension_is_the_derivative_of_the_stored_energy():
    """F = dE/dL − p dV/dL (virtual work): against a central difference of the enthalpy-like
    potential E(L) − p V(L) at fixed p, computed from volume and energy independently."""
    geometry = Geometry(Build())
    mu, gauge = 0.6e6, 150e3

    def potential(length):
        build = geometry.build
        d = geometry.diameter(length)
        mid = build.bladder_diameter_m - build.bladder_thickness_m
        hoop = (d - 2 * build.fiber_thickness_m - build.bladder_thickness_m) / mid
        axial = (length - 2 * geometry.cone_height_m) / geometry.braided_length0_m
        rubber = np.pi * mid * build.bladder_thickness_m * geometry.braided_length0_m
        energy = mu / 2 * (hoop**2 + axial**2 + hoop**-2 * axial**-2 - 3) * rubber
        return energy - gauge * geometry.volume_and_slope(length)[0]

    for length in (0.17, 0.19, 0.21):
        h = 1e-6
        numeric = (potential(length + h) - potential(length - h)) / (2 * h)
        assert geometry.static_tension(length, gauge, mu) == pytest.approx(numeric, rel=1e-6)
    # and the free length pulls nothing
    free = geometry.free_length(gauge, mu)
    assert abs(geometry.static_tension(free, gauge, mu)) < 1e-6


def test_a_sealed_isothermal_gas_keeps_boyles_product():
    """Isothermal, sealed, no dead volume: (p_gauge + p_atm) V is the same at every instant."""
    muscle = SealedMuscle(Build(), Physics(), 150.0, 22.0)
    motion = Motion(np.array([0.0, 5.0, 10.0]), np.array([0.0, 0.04, 0.0]))
    run = muscle.run(motion, np.linspace(0, 10, 41))
    volume, _ = muscle.geometry.volume_and_slope(muscle.free_length_m + run.elongation_m)
    product = (run.gauge_kPa * 1e3 + 101325.0) * volume
    assert np.ptp(product) / product.mean() < 1e-9
    assert run.gauge_kPa[20] > run.gauge_kPa[0] + 10  # stretching shrinks the volume


def test_a_muscle_sealed_at_a_declared_length_starts_there():
    """Sealed while held 5 mm past its free length (a test that declares its initial length, as
    bench/bench_campaign.py's thesis tests do): at rest it holds the declared pressure and pulls
    the static tension of that length (no motion, no friction), and from there on it keeps
    Boyle's product."""
    gauge_kPa = 150.0
    length = SealedMuscle(Build(), Physics(), gauge_kPa, 22.0).free_length_m + 0.005
    muscle = SealedMuscle(Build(), Physics(), gauge_kPa, 22.0, sealed_length_m=length)
    motion = Motion(np.array([0.0, 1.0, 6.0]), np.array([0.0, 0.0, 0.03]))
    run = muscle.run(motion, np.linspace(0, 6, 25))
    assert run.gauge_kPa[0] == pytest.approx(gauge_kPa, rel=1e-12)
    static = float(muscle.geometry.static_tension(length, gauge_kPa * 1e3, Physics().shear_modulus_Pa))
    assert static > 1.0 and run.force_N[0] == pytest.approx(static, rel=1e-9)
    volume, _ = muscle.geometry.volume_and_slope(length + run.elongation_m)
    product = (run.gauge_kPa * 1e3 + 101325.0) * volume
    assert np.ptp(product) / product.mean() < 1e-9


def test_an_out_of_catalog_coulomb_friction_is_left_as_a_loop_the_model_lacks(tmp_path):
    # Friction of constant size that flips with the motion's direction is in no catalog effect:
    # what it leaves changes sign between the stretch and the return of every cycle, the same in
    # each cycle, and the report must say so (docs/reference/report.md, `remainder.where`).
    for _, report in seed_reports("coulomb_alternating", tmp_path):
        where = report["remainder"]["where"]["force_N"]
        assert where["halves"] == "loop" and where["pattern"] == "spread", report["verdict"]
        assert "a loop the model lacks" in report["verdict"]
