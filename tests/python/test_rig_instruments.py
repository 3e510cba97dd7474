"""A real rig's instruments and mount (docs/experiments.md, "The rig and its instruments"): a preloaded mount
sets the muscle's length, a load cell and a transducer read only their range, and rows whose
supplied pressure the transducer clipped are censored."""

import numpy as np
import pytest

from pamkit import static_forces
from pamkit.io.experiment import load_experiment
from pamkit.io.guards import ExperimentError, ExperimentWarning
from pamkit.simulation import initial_length, muscle_params, simulate_experiment

MUSCLE = """[muscle]
length_m = 0.25
diameter_m = 0.010
braid_angle_deg = 24.0
cone_generator_m = 0.0

[bladder]
law = "neo_hookean"
shear_modulus_Pa = 1.5e6
"""


def write_rig(tmp_path, test_extra="", csv_text=None):
    """A supplied isometric series of a 10 mm muscle: the pressure ramped up and vented at its
    mounted length."""
    pressure = np.concatenate([np.linspace(0, 500, 11), np.linspace(450, 0, 10)])
    rows = csv_text or "time_s,elongation_m,pressure_kPa,force_N\n" + "".join(
        f"{k},0,{p},{0.5 * p}\n" for k, p in enumerate(pressure)
    )
    (tmp_path / "rig.csv").write_text(rows)
    path = tmp_path / "rig.toml"
    path.write_text(
        f'{MUSCLE}\n[test]\ngas = "supplied"\ninflation_pressure_kPa = 0.0\nambient_temperature_C = 20.0\n'
        f'data = "rig.csv"\n{test_extra}\n'
    )
    return path


def test_a_preloaded_mount_starts_where_the_deflated_muscle_carries_the_preload(tmp_path):
    experiment = load_experiment(write_rig(tmp_path, "preload_N = 20.0"))
    params = muscle_params(experiment)
    length = initial_length(experiment, params)
    assert length > params.build.length_m  # the membrane is stretched to carry it
    # The invariant: the model, deflated at that length, carries the preload (to the solve's 1e-9).
    assert static_forces(params, [length], [0.0])[0] == pytest.approx(20.0, rel=1e-6)
    predicted = simulate_experiment(experiment)
    assert predicted["force_N"][0] == pytest.approx(20.0, rel=1e-6)


def test_a_preload_needs_a_membrane_that_can_carry_it_and_excludes_a_given_length(tmp_path):
    path = write_rig(tmp_path, "preload_N = 20.0")
    path.write_text(path.read_text().replace('law = "neo_hookean"\nshear_modulus_Pa = 1.5e6', 'law = "none"'))
    experiment = load_experiment(path)
    with pytest.raises(ExperimentError, match="preload_N = 20 N: the deflated muscle does not carry it"):
        simulate_experiment(experiment)
    with pytest.raises(ExperimentError, match="both preload_N and initial_length_m"):
        load_experiment(write_rig(tmp_path, "preload_N = 20.0\ninitial_length_m = 0.26"))
    sealed = write_rig(tmp_path, "preload_N = 20.0")
    sealed.write_text(sealed.read_text().replace('gas = "supplied"', 'gas = "sealed"'))
    with pytest.raises(ExperimentError, match="preload_N belongs to a supplied time series"):
        load_experiment(sealed)


def test_the_offset_run_of_a_preloaded_mount_keeps_the_preload_in_the_force(tmp_path):
    # The offset run is recorded on the mounted muscle: its 23 N mean is the cell's 3 N tare and
    # the muscle's 20 N preload; only the tare is the instrument's.
    path = write_rig(tmp_path, 'preload_N = 20.0\nzero = "offset.csv"')
    (tmp_path / "offset.csv").write_text("time_s,elongation_m,force_N,pressure_kPa\n0,0,22,9\n1,0,24,9\n")
    experiment = load_experiment(path)
    assert experiment.zeroed == {"force_N": 3.0, "gauge_pressure_Pa": 9e3}  # the file's 9 kPa, in Pa
    assert experiment.columns["force_N"][0] == pytest.approx(0.5 * 0 - 3.0)


def test_a_load_cell_reads_only_its_range(tmp_path):
    free = simulate_experiment(load_experiment(write_rig(tmp_path)))["force_N"]
    clipped_experiment = load_experiment(write_rig(tmp_path, "force_range_N = [-2.0, 150.0]"))
    clipped = simulate_experiment(clipped_experiment)["force_N"]
    assert free.max() > 150.0 and free.min() < -2.0  # the braid pushes, unclipped, when held short
    np.testing.assert_array_equal(clipped, np.clip(free, -2.0, 150.0))
    # A zero run shifts what the data calls the range's ends: the cell clips its raw reading.
    clipped_experiment.zeroed["force_N"] = 5.0
    assert clipped_experiment.reading_range("force_N") == (-7.0, 145.0)


def test_rows_at_the_transducers_range_end_are_censored(tmp_path):
    experiment = load_experiment(write_rig(tmp_path, "pressure_range_kPa = [0.0, 450.0]"))
    pressure = experiment.columns["gauge_pressure_Pa"]
    np.testing.assert_array_equal(experiment.censored, (pressure <= 0.0) | (pressure >= 450e3))
    assert experiment.censored.sum() == 5  # 0 kPa twice, 450 twice and 500 once
    assert not load_experiment(write_rig(tmp_path)).censored.any()


@pytest.mark.parametrize(
    "extra, message",
    [
        ("force_range_N = 100.0", r"force_range_N = 100.0 must be \[lowest, highest\]"),
        ("pressure_range_kPa = [500.0, 0.0]", r"pressure_range_kPa = \[500.0, 0.0\] needs lowest < highest"),
        ('force_range_N = [0.0, "a lot"]', "force_range_N = 'a lot' must be a number"),
        ("preload_N = -3.0", r"preload_N = -3.0 is outside \(0, 1e5\] N"),
    ],
)
def test_bad_instrument_keys_are_named(tmp_path, extra, message):
    with pytest.raises(ExperimentError, match=message):
        load_experiment(write_rig(tmp_path, extra))


def test_simulate_plots_a_supplied_test_against_its_pressure_and_an_isotonic_test_by_branch(tmp_path):
    from pamkit.cli import main

    rig = write_rig(tmp_path, "preload_N = 20.0")
    assert main(["simulate", str(rig), "-o", str(tmp_path / "rig_out.csv"), "--plot", str(tmp_path / "rig.png")]) == 0
    assert (tmp_path / "rig.png").stat().st_size > 0
    (tmp_path / "iso.csv").write_text("pressure_kPa,length_m\n0,0.25\n200,0.23\n400,0.21\n200,0.225\n0,0.249\n")
    (tmp_path / "iso.toml").write_text(f'{MUSCLE}\n[test]\nkind = "isotonic"\nload_N = 50.0\ndata = "iso.csv"\n')
    out = tmp_path / "iso_out.csv"
    assert main(["simulate", str(tmp_path / "iso.toml"), "-o", str(out), "--plot", str(tmp_path / "iso.png")]) == 0
    assert np.genfromtxt(out, delimiter=",", names=True)["length_m"].size == 5
    assert (tmp_path / "iso.png").stat().st_size > 0


def test_a_lab_log_with_an_offset_run_a_repeated_stamp_and_a_preloaded_mount_loads_as_is(tmp_path):
    # A lab's log as its rig writes it loads without hand editing.
    log = "time_s,elongation_m,pressure_kPa,force_N\n0.000,0,9,23\n0.001,0,59,48\n0.001,0,61,50\n0.002,0,109,73\n"
    path = write_rig(tmp_path, 'preload_N = 20.0\nzero = "offset.csv"\nforce_range_N = [-5.0, 1500.0]', csv_text=log)
    (tmp_path / "offset.csv").write_text("time_s,elongation_m,pressure_kPa,force_N\n0,0,9,23\n1,0,9,23\n")
    with pytest.warns(ExperimentWarning, match=r"rig.csv:4: 1 row\(s\) repeat the time stamp"):
        experiment = load_experiment(path)
    np.testing.assert_allclose(experiment.columns["gauge_pressure_Pa"], [0.0, 51e3, 100e3])  # merged, zeroed
    np.testing.assert_allclose(experiment.columns["force_N"], [20.0, 46.0, 70.0])  # the 3 N tare taken off
    assert experiment.reading_range("force_N") == (-8.0, 1497.0)
    assert simulate_experiment(experiment)["force_N"][0] == pytest.approx(20.0, rel=1e-6)


def _write_isotonic_series(tmp_path, times, pressures, extra="load_mass_kg = 10.0"):
    rows = "".join(f"{t},{p},0.25\n" for t, p in zip(times, pressures))
    (tmp_path / "iso.csv").write_text("time_s,pressure_kPa,length_m\n" + rows)
    (tmp_path / "iso.toml").write_text(
        f'{MUSCLE}\n[test]\nkind = "isotonic"\nload_N = 98.1\ndata = "iso.csv"\n{extra}\n'
    )
    return tmp_path / "iso.toml"


def test_a_hanging_mass_lags_a_slow_sweep_in_proportion_to_its_rate_and_a_fast_step_with_inertia(tmp_path):
    # The dynamic option: [test] load_mass_kg integrates the load's
    # motion (isotonic_motion). On a slow sweep the load follows the quasi-static path behind it
    # by the friction's lag, friction / stiffness; the thesis's tanh(Kf v) with Kf = 1 s/m is
    # linear at these speeds, so the lag halves when the sweep takes twice as long (the limit
    # the quasi-static solve is). A step in 10 ms is not followed: the 10 kg load is still on its way.
    def largest_lag(duration_s):
        times = np.linspace(0.0, duration_s, 241)
        sweep = np.interp(times, [0, duration_s / 2, duration_s], [100.0, 400.0, 100.0])
        dynamic = simulate_experiment(load_experiment(_write_isotonic_series(tmp_path, times, sweep)))
        static = simulate_experiment(load_experiment(_write_isotonic_series(tmp_path, times, sweep, extra="")))
        return float(np.max(np.abs(dynamic["length_m"] - static["length_m"])))

    slow, slower = largest_lag(120.0), largest_lag(240.0)
    assert slow == pytest.approx(2.0 * slower, rel=0.1)
    fast = np.array([0.0, 0.01, 0.02, 0.03])
    step = np.array([100.0, 400.0, 400.0, 400.0])
    dynamic = simulate_experiment(load_experiment(_write_isotonic_series(tmp_path, fast, step)))
    static = simulate_experiment(load_experiment(_write_isotonic_series(tmp_path, fast, step, extra="")))
    assert abs(dynamic["length_m"][1] - static["length_m"][1]) > 1e-3


def test_a_hanging_mass_needs_a_time_axis(tmp_path):
    path = _write_isotonic_series(tmp_path, [0, 1], [100, 200])
    (tmp_path / "iso.csv").write_text("pressure_kPa,length_m\n100,0.25\n200,0.24\n")
    with pytest.raises(ExperimentError, match="load_mass_kg integrates the load's motion in time: time_s is missing"):
        load_experiment(path)
    path.write_text(path.read_text().replace("load_mass_kg = 10.0", "load_mass_kg = 0.0"))
    with pytest.raises(ExperimentError, match=r"load_mass_kg = 0.0 is outside \(0, 1e4\] kg"):
        load_experiment(path)


def test_a_hanging_mass_without_its_weight_is_told_its_weight(tmp_path):
    # A lab that gives the mass it hung and no load_N: the load is the mass times standard gravity
    # (9.80665 m/s^2, units.hpp), which the error works out for it.
    path = _write_isotonic_series(tmp_path, [0, 1], [100, 200])
    path.write_text(path.read_text().replace("load_N = 98.1\n", ""))
    with pytest.raises(ExperimentError, match=r"load_N is missing.*load_N = 98.0665 for load_mass_kg = 10"):
        load_experiment(path)


def test_a_series_compliance_is_refused_where_the_model_is_integrated_in_time(tmp_path):
    # The rig's and fittings' stretch c F acts where each sample settles (this supplied test reads
    # less force with it); a sealed test's ODE, or a load's motion, would carry the braid's length
    # as an algebraic unknown, so the file is refused there, naming the key.
    path = write_rig(tmp_path)
    rigid = simulate_experiment(load_experiment(path))["force_N"]
    path.write_text(
        path.read_text().replace("cone_generator_m = 0.0", "cone_generator_m = 0.0\nseries_compliance_m_per_N = 5e-6")
    )
    compliant = simulate_experiment(load_experiment(path))["force_N"]
    pulled = rigid > 50.0
    assert pulled.any() and np.all(compliant[pulled] < rigid[pulled])
    path.write_text(path.read_text().replace('gas = "supplied"', 'gas = "sealed"'))
    with pytest.raises(
        ExperimentError, match=r"\[muscle\] series_compliance_m_per_N .* not in a sealed test's simulation"
    ):
        load_experiment(path)
