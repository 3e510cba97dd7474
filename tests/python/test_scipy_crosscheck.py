"""pamkit against an independent implementation of the same equations in NumPy/SciPy
(bench/scipy_reference.py: brentq for the braid closure, derivatives by another route,
solve_ivp LSODA for the gas temperature and the energy integrals). Two cycles of the thesis
protocol, both gas processes, friction sharp enough (Kf = 200 s/m) to jump at every corner.
No timing here: bench/bench_simulate.py times them.
"""

import importlib.util
import os
import pathlib

import numpy as np
import pytest

import pamkit


def _load_reference():
    root = os.environ.get("PAMKIT_SOURCE_DIR") or pathlib.Path(__file__).resolve().parents[2]
    path = pathlib.Path(root) / "bench" / "scipy_reference.py"
    spec = importlib.util.spec_from_file_location("pamkit_scipy_reference", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


reference = _load_reference()

TOL = 1e-11  # both integrators
MAX_REL_DIFF = 1e-6  # max |pamkit - SciPy| / max |SciPy| over a trace
INITIAL = {"length_m": 0.167, "gauge_pressure_Pa": 236.63e3}  # table C.2, 207 kPa / 90 %
SHARPNESS = 200.0  # Kf [s/m]: tanh(Kf v) = 0.46 at 2.5 mm/s


def rel_diff(a, b):
    a, b = np.asarray(a), np.asarray(b)
    return float(np.max(np.abs(a - b)) / np.max(np.abs(b)))


def both_models(process, tau_s=5.0, polytropic_index=1.0, build=None):
    build = build or pamkit.MuscleBuild()
    gas = pamkit.GasParams(
        process=getattr(pamkit.GasProcess, process),
        heat_transfer_time_constant_s=tau_s,
        polytropic_index=polytropic_index,
    )
    friction = pamkit.FrictionParams(sharpness_s_per_m=SHARPNESS)
    model = pamkit.MuscleModel(
        pamkit.MuscleParams(build, pamkit.BladderLaw.thesis(), friction, gas), pamkit.InitialState(**INITIAL)
    )
    ref = reference.ReferenceMuscle(
        build=build.to_dict(),
        initial_length_m=INITIAL["length_m"],
        initial_gauge_pressure_Pa=INITIAL["gauge_pressure_Pa"],
        friction=friction.to_dict(),
        gas={**gas.to_dict(), "process": process},
    )
    return model, ref


@pytest.mark.parametrize(
    "process, polytropic_index", [("heat_transfer", 1.0), ("polytropic", 1.0), ("polytropic", 1.2)]
)
def test_simulation_matches_scipy_reference(process, polytropic_index):
    # n = 1.2, not 1.4: with n = gamma the process is adiabatic and the heat is rounding noise.
    model, ref = both_models(process, polytropic_index=polytropic_index)
    trajectory = pamkit.thesis_protocol(0.0523, cycles=2)
    config = pamkit.SimulatorConfig(relative_tolerance=TOL, absolute_tolerance_K=TOL, absolute_tolerance_J=TOL)
    ours = pamkit.Simulator(config).run(model, trajectory)
    theirs = ref.simulate(
        np.array(trajectory.time_s), np.array(trajectory.elongation_m), rtol=TOL, atol_K=TOL, atol_J=TOL
    )

    assert ref.mass == pytest.approx(model.gas_mass, rel=1e-14)
    for name in (
        "force_N",
        "gauge_pressure_Pa",
        "temperature_K",
        "friction_force_N",
        "work_J",
        "friction_dissipated_J",
        "heat_lost_J",
    ):
        assert rel_diff(getattr(ours, name), theirs[name]) <= MAX_REL_DIFF, name
    # The check has teeth: the temperature moves when it should, friction jumps at corners.
    if process == "heat_transfer" or polytropic_index != 1.0:
        assert np.ptp(theirs["temperature_K"]) > 1.0
    assert np.max(np.abs(theirs["friction_force_N"])) > 0.1 * np.max(np.abs(theirs["force_N"]))


@pytest.mark.parametrize("cone_generator_m", [0.0095, 0.0])
def test_shape_matches_scipy_reference(cone_generator_m):
    build = pamkit.MuscleBuild(cone_generator_m=cone_generator_m)
    geometry = pamkit.BraidGeometry(build)
    ref = reference.ReferenceMuscle(build=build.to_dict(), initial_length_m=0.167)
    lo, hi = geometry.min_length, geometry.max_length
    for length in np.linspace(lo, hi, 23)[1:-1]:
        ours, theirs = geometry.shape(length), ref.shape(length)
        for name in (
            "diameter",
            "cylinder_length",
            "total_volume",
            "gas_volume",
            "d_diameter",
            "d_cylinder_length",
            "d_total_volume",
            "d_gas_volume",
        ):
            assert getattr(ours, name) == pytest.approx(theirs[name], rel=1e-9, abs=1e-15), (length, name)


def test_reference_derivatives_match_finite_differences():
    ref = reference.ReferenceMuscle(initial_length_m=0.167)
    h = 1e-6  # central differences: error ~ h^2 f''' / 6, well under 1e-7 relative here
    for length in (0.15, 0.167, 0.19, 0.215):
        s, up, down = ref.shape(length), ref.shape(length + h), ref.shape(length - h)
        for value, derivative in (
            ("diameter", "d_diameter"),
            ("cylinder_length", "d_cylinder_length"),
            ("total_volume", "d_total_volume"),
            ("bladder_volume", "d_bladder_volume"),
            ("gas_volume", "d_gas_volume"),
        ):
            fd = (up[value] - down[value]) / (2 * h)
            assert fd == pytest.approx(s[derivative], rel=1e-7), (length, value)
