"""A user's own effects, written in Python: subclasses of pamkit.Effect added to a catalog with
catalog.add(name, factory), parsed from `--effect` text, and acting at each stage of a simulated
measurement (the model's parameters, the muscle's motion, the instruments' readings) through
pamkit.simulate_measurement and pamkit.simulation.simulate_experiment.

Each Python effect re-implements something the catalog has in C++, so that its result can be
checked bit for bit against the built-in one."""

import gc

import numpy as np
import pytest

import pamkit
from pamkit.effects import catalog as builtin_catalog
from pamkit.effects import parse_effects
from pamkit.io.experiment import load_experiment
from pamkit.io.guards import ExperimentError
from pamkit.simulation import simulate_experiment

CHANNELS = ("time_s", "elongation_m", "force_N", "gauge_pressure_Pa", "temperature_K")


class ParametricPythonEffect(pamkit.Effect):
    """Numeric parameters declared once, in PARAMETERS: key -> (default, unit, min, max,
    realistic min, realistic max, description)."""

    NAME = ""
    DESCRIPTION = ""
    PARAMETERS: dict = {}

    def __init__(self):
        super().__init__()
        self.values = {key: spec[0] for key, spec in self.PARAMETERS.items()}

    def name(self):
        return self.NAME

    def description(self):
        return self.DESCRIPTION

    def parameters(self):
        return [pamkit.EffectParameter(key, self.values[key], *spec[1:]) for key, spec in self.PARAMETERS.items()]

    def set(self, key, value):
        if key not in self.PARAMETERS:
            raise ValueError(f"effect {self.NAME} has no parameter {key!r} ({', '.join(self.PARAMETERS)})")
        try:
            number = float(value)
        except ValueError:
            raise ValueError(f"effect {self.NAME}: {key} = {value!r} is not a number") from None
        low, high = self.PARAMETERS[key][2:4]
        if not low <= number <= high:
            raise ValueError(f"effect {self.NAME}: {key} = {number} is outside [{low}, {high}]")
        self.values[key] = number


class HoseVolume(ParametricPythonEffect):
    """Stage 1 (parameters): the transducer's hose as dead volume, like the built-in dead_volume."""

    NAME = "hose_volume"
    DESCRIPTION = "gas in the transducer's hose (appendix B: about 5 % of the muscle's volume)"
    PARAMETERS = {"volume_fraction": (0.05, "1", 0.0, 10.0, 0.03, 0.3, "hose volume / muscle gas volume")}

    def apply_to_params(self, params):
        params.extensions.dead_volume_fraction = self.values["volume_fraction"]
        return params

    def why_not(self, mode):
        return None if mode == "sealed" else "hose_volume acts on the sealed gas; a supplied test measures its pressure"


class LoosePin(ParametricPythonEffect):
    """Stage 2 (motion): play in the clevis pins, the same backlash operator as fixture_slack."""

    NAME = "loose_pin"
    DESCRIPTION = "play between the crosshead and the muscle"
    PARAMETERS = {"slack_m": (1e-3, "m", 0.0, 0.05, 0.5e-3, 3e-3, "play")}

    def apply_to_elongation(self, time_s, crosshead_m):
        slack = self.values["slack_m"]
        position = crosshead_m[0]
        muscle = []
        for crosshead in crosshead_m:
            low, high = crosshead - slack, crosshead
            position = low if position < low else (high if high < position else position)
            muscle.append(position)
        return muscle


class ThermometerOffset(ParametricPythonEffect):
    """Stage 3 (readings): the TMP36's offset error (its data sheet allows ±2 °C)."""

    NAME = "thermometer_offset"
    DESCRIPTION = "offset of the gas-temperature reading"
    PARAMETERS = {"offset_K": (0.0, "K", -10.0, 10.0, -2.0, 2.0, "reading minus truth")}

    def apply_to_measurement(self, measurement):
        measurement.temperature_K = measurement.temperature_K + self.values["offset_K"]
        return measurement


@pytest.fixture
def catalog():
    catalog = builtin_catalog()
    for effect in (HoseVolume, LoosePin, ThermometerOffset):
        catalog.add(effect.NAME, effect)
    return catalog


@pytest.fixture
def bench():
    """Table C.2's 90 % test (0.167 m, 236.63 kPa), two cycles of 5 cm at 2.5 mm/s with holds."""
    return (
        pamkit.MuscleParams(),
        pamkit.InitialState(length_m=0.167, gauge_pressure_Pa=236.63e3),
        pamkit.thesis_protocol(0.05, 2.5e-3, 2, 0.1, 2.0),
    )


def assert_identical(a, b, channels=CHANNELS):
    """Bit for bit, channel by channel (dicts of arrays or Measurements)."""
    get = (lambda m, c: m[c]) if isinstance(a, dict) else getattr
    for channel in channels:
        x, y = np.asarray(get(a, channel)), np.asarray(get(b, channel))
        assert x.shape == y.shape and x.tobytes() == y.tobytes(), f"{channel} differs"


def test_python_effects_are_added_and_parsed_from_text(catalog):
    assert {"hose_volume", "loose_pin", "thermometer_offset", "dead_volume"} <= set(catalog.names())
    effect = catalog.parse("thermometer_offset:offset_K=0.75")
    assert isinstance(effect, ThermometerOffset)
    assert [(p.name, p.value, p.unit) for p in effect.parameters()] == [("offset_K", 0.75, "K")]
    assert catalog.make("loose_pin").parameters()[0].value == 1e-3  # the default
    with pytest.raises(ValueError, match="loose_pin has no parameter 'play'"):
        catalog.parse("loose_pin:play=1")
    with pytest.raises(ValueError, match="offset_K = 'warm' is not a number"):
        catalog.parse("thermometer_offset:offset_K=warm")
    with pytest.raises(ValueError, match="outside"):
        catalog.parse("hose_volume:volume_fraction=-1")
    with pytest.raises(ValueError, match="unknown effect 'hose'"):
        catalog.parse("hose")


def test_parameter_stage_matches_the_builtin_dead_volume(catalog, bench):
    params, initial, crosshead = bench
    effects = [catalog.parse("hose_volume:volume_fraction=0.2")]
    gc.collect()  # the effect lives on in the list and in C++, not only as a temporary
    python = pamkit.simulate_measurement(params, initial, crosshead, effects)
    builtin = pamkit.simulate_measurement(
        params, initial, crosshead, [catalog.parse("dead_volume:volume_fraction=0.2")]
    )
    baseline = pamkit.simulate_measurement(params, initial, crosshead, [])
    assert_identical(python, builtin)
    assert np.ptp(python.gauge_pressure_Pa) < np.ptp(baseline.gauge_pressure_Pa)  # it did act
    assert params.extensions.dead_volume_fraction == 0.0  # on a copy, not on the caller's parameters


def test_elongation_stage_matches_the_builtin_fixture_slack(catalog, bench):
    params, initial, crosshead = bench
    python = pamkit.simulate_measurement(params, initial, crosshead, [catalog.parse("loose_pin:slack_m=0.002")])
    builtin = pamkit.simulate_measurement(params, initial, crosshead, [catalog.parse("fixture_slack:slack_m=0.002")])
    assert_identical(python, builtin)
    # The record keeps the crosshead's elongation; the force saw the muscle's.
    assert python.elongation_m.tobytes() == np.asarray(crosshead.elongation_m).tobytes()
    baseline = pamkit.simulate_measurement(params, initial, crosshead, [])
    assert python.force_N.max() < baseline.force_N.max()


def test_measurement_stage_shifts_the_reading_only(catalog, bench):
    params, initial, crosshead = bench
    python = pamkit.simulate_measurement(params, initial, crosshead, [catalog.parse("thermometer_offset:offset_K=0.5")])
    baseline = pamkit.simulate_measurement(params, initial, crosshead, [])
    assert_identical(python, baseline, ("time_s", "elongation_m", "force_N", "gauge_pressure_Pa"))
    assert python.temperature_K.tobytes() == (baseline.temperature_K + 0.5).tobytes()


class PointwiseThermometerOffset(ThermometerOffset):
    """The same offset, declaring that it reads each sample alone."""

    def reads_samples_alone(self):
        return True


def test_which_effects_read_each_sample_alone(catalog):
    # A fit asks the simulator for derivatives at its own rows only where every effect reads each
    # sample alone (series/jacobian.py): a lag or a skew reads its neighbours, and a Python effect
    # that edits the readings is taken to, unless it says otherwise.
    alone = {name: catalog.make(name).reads_samples_alone() for name in catalog.names()}
    assert not alone["time_skew"] and not alone["sensor_lag"] and not alone["thermometer_offset"]
    assert alone["load_cell"] and alone["sensor_offset"] and alone["thermometer"]
    assert alone["dead_volume"] and alone["fixture_slack"] and alone["hose_volume"] and alone["loose_pin"]
    assert PointwiseThermometerOffset().reads_samples_alone()


def test_all_three_stages_through_simulate_experiment(catalog, thesis_dir):
    experiment = load_experiment(thesis_dir / "pam2_207kPa_90pct.toml")
    specs = [
        "hose_volume:volume_fraction=0.05",
        "loose_pin:slack_m=0.001",
        "thermometer_offset:offset_K=-1.25",
        "heat_transfer:time_constant_s=2",
    ]
    python = simulate_experiment(experiment, effects=parse_effects(specs, catalog))
    builtin = simulate_experiment(
        experiment,
        effects=parse_effects(
            ["dead_volume:volume_fraction=0.05", "fixture_slack:slack_m=0.001", "heat_transfer:time_constant_s=2"]
        ),
    )
    assert_identical(python, builtin, ("time_s", "elongation_m", "force_N", "gauge_pressure_Pa"))
    assert python["temperature_K"].tobytes() == (builtin["temperature_K"] - 1.25).tobytes()
    # The heat exchange makes the gas temperature swing; the offset moved the whole record.
    assert np.ptp(python["temperature_K"]) > 0.1
    # The gas starts at the room's temperature, which the file gives once.
    assert python["temperature_K"][0] == experiment.gas_params.ambient_temperature_K - 1.25


def test_an_effect_that_cannot_act_says_why(catalog, write_experiment):
    hose = catalog.parse("hose_volume:volume_fraction=0.1")
    assert hose.acts_in(pamkit.GasMode.sealed) == (True, None)
    acts, why = hose.acts_in(pamkit.GasMode.supplied)
    assert not acts and why.startswith("hose_volume acts on the sealed gas")
    supplied = load_experiment(
        write_experiment(
            csv_text="time_s,elongation_m,pressure_kPa\n0,0,200\n1,0.001,210\n2,0.002,220\n3,0.003,230\n",
            toml_test_extra='gas = "supplied"',
        )
    )
    with pytest.raises(ExperimentError, match="effect hose_volume cannot act here: hose_volume acts on the sealed gas"):
        simulate_experiment(supplied, effects=[hose])


def test_motion_and_reading_stages_act_in_a_supplied_test(catalog, write_experiment):
    supplied = load_experiment(
        write_experiment(
            csv_text="time_s,elongation_m,pressure_kPa\n0,0,200\n1,0.001,210\n2,0.002,220\n3,0.003,230\n",
            toml_test_extra='gas = "supplied"',
        )
    )
    python = simulate_experiment(
        supplied, effects=parse_effects(["loose_pin:slack_m=0.0015", "thermometer_offset:offset_K=0.5"], catalog)
    )
    builtin = simulate_experiment(supplied, effects=parse_effects(["fixture_slack:slack_m=0.0015"]))
    assert_identical(python, builtin, ("time_s", "elongation_m", "force_N", "gauge_pressure_Pa"))
    np.testing.assert_array_equal(python["temperature_K"], supplied.gas_params.ambient_temperature_K + 0.5)
