"""Discovery of what the catalog lacks (pamkit.diagnosis.discover): a known term hidden in a
residual is found with its coefficient and held-out gain, noise alone is not a discovery, a
pressurise/vent hysteresis is found in an isometric sweep, and a discovered term saved as a
user effect adds the same correction in the next simulation."""

import json

import numpy as np
import pytest
from scipy.signal import savgol_coeffs

import pamkit
from pamkit.diagnosis.discover import DiscoveryError, discover, feature_library
from pamkit.diagnosis.discovered import discovered_effect, load_effect, save_effect
from pamkit.effects import catalog as builtin_catalog

SIGMA_N = 2.0  # white load-cell noise of the stretch record [N]
COULOMB = 3e-4  # N/Pa: the friction hidden in it, 0.3 N per kPa (60 N at 200 kPa)


def stretch_record(n=10_000, cycles=10, seed=0):
    """A sealed cyclic test: 25 mm sinusoidal stretch, 10 cycles in 200 s, a 10 µm encoder,
    a pressure that follows the stretch and drifts slowly (so p·tanh(v/v0) and tanh(v/v0)
    differ), with 0.3 kPa transducer noise, in Pa. Even cycles are fitted, odd ones held out;
    the held-out units are half-cycles."""
    rng = np.random.default_rng(seed)
    time_s = np.linspace(0.0, 200.0, n)
    phase = 2 * np.pi * cycles * time_s / time_s[-1]
    elongation_m = np.round(0.025 * (1 - np.cos(phase)) / 1e-5) * 1e-5
    pressure_Pa = 1e3 * (200 + 60 * np.sin(phase / 2.5) + 30 * (1 - np.cos(phase)) + rng.normal(0, 0.3, n))
    cycle = np.minimum(np.floor(cycles * time_s / time_s[-1]), cycles - 1)
    half_cycle = np.minimum(np.floor(2 * cycles * time_s / time_s[-1]), 2 * cycles - 1)
    fit = cycle % 2 == 0
    return time_s, elongation_m, pressure_Pa, cycle, half_cycle, fit, ~fit


def step_sweep(sweeps=6, rate_hz=100.0, seed=0):
    """An isometric pressure sweep of a commercial muscle: held at 20 mm, the
    pressure stepped 0 -> 600 kPa by 100 kPa and back (2 s plateaus, 0.1 s steps), 0.5 kPa
    transducer noise, in Pa; the record starts with the first step up. Returns the programmed
    direction too: +1 after a step up (pressurising), -1 after a step down (venting)."""
    levels = np.r_[np.arange(100, 601, 100), np.arange(500, -1, -100)]
    hold_s, step_s = 2.0, 0.1
    period = levels.size * hold_s
    time_s = np.arange(0.0, sweeps * period, 1 / rate_hz)
    k = np.floor((time_s % period) / hold_s).astype(int)
    into = time_s % period - k * hold_s
    previous = np.r_[0, levels][k]
    pressure = previous + (levels[k] - previous) * np.clip(into / step_s, 0, 1)
    direction = np.sign(levels[k] - previous).astype(float)
    rng = np.random.default_rng(seed)
    sweep = np.floor(time_s / period)
    pressure_Pa = 1e3 * (pressure + rng.normal(0, 0.5, time_s.size))
    return time_s, np.full(time_s.size, 0.02), pressure_Pa, direction, sweep


def by_name(features, name):
    return next(values for term, values in features.items() if term.name == name)


@pytest.fixture(scope="module")
def coulomb_case():
    time_s, elongation_m, pressure_Pa, cycle, half_cycle, fit, held = stretch_record()
    features = feature_library(time_s, elongation_m, pressure_Pa, cycle=cycle)
    friction = by_name(features, "tanh(v/v0)*p")
    residual = COULOMB * friction + np.random.default_rng(1).normal(0, SIGMA_N, time_s.size)
    result = discover(features, residual, SIGMA_N, fit, held, half_cycle, "force_N", "N")
    return {
        "time_s": time_s,
        "elongation_m": elongation_m,
        "gauge_pressure_Pa": pressure_Pa,
        "features": features,
        "friction": friction,
        "residual": residual,
        "fit": fit,
        "held": held,
        "half_cycle": half_cycle,
        "result": result,
    }


def test_the_library_holds_the_physical_terms_a_stretch_record_allows(coulomb_case):
    names = [term.name for term in coulomb_case["features"]]
    assert names == [
        "offset",
        "tanh(v/v0)*p",
        "tanh(v/v0)",
        "dahl(x; xc)",
        "v",
        "|v|",
        "x",
        "x^2",
        "x^3",
        "p",
        "dp/dt",
        "sign(dp/dt)",
        "sign(dp/dt)*p",
        "t",
        "cycle",
    ]
    # The smoothed derivative of the 10 µm encoder record follows the sinusoid's velocity
    # (peak 25 mm · 2π / 20 s = 7.85 mm/s) to within what the encoder's rounding leaves: white
    # noise of q / sqrt(12) through the derivative's weights (the quadratic's own error on a
    # 20 s sinusoid, x''' h² · 34/60 = 2e-4 mm/s, is 250 times smaller); 1.2 times that leaves
    # room for the RMS's scatter.
    time_s = coulomb_case["time_s"]
    v = by_name(coulomb_case["features"], "v")
    true_v = 25 * 2 * np.pi / 20 * np.sin(2 * np.pi * time_s / 20)
    weights = savgol_coeffs(5, 2, deriv=1, delta=time_s[1] - time_s[0])  # 5 samples: 50 ms is 2.5 at 50 Hz
    rounding = 0.01 / np.sqrt(12) * np.linalg.norm(weights)
    assert np.sqrt(np.mean((v - true_v)[5:-5] ** 2)) < 1.2 * rounding
    # v0 is 5 % of the median moving speed, which for a sinusoid lies between half its peak
    # (the median of |sin| is sin(π/4) = 0.71) and its peak.
    term = next(t for t in coulomb_case["features"] if t.name == "tanh(v/v0)*p")
    v0 = dict(term.parameters)["v0_mm_per_s"]
    assert 0.05 * 7.85 * 0.5 < v0 < 0.05 * 7.85
    assert term.unit == "Pa" and "Coulomb" in term.resembles


def test_a_hidden_coulomb_friction_is_found_with_its_coefficient_and_gain(coulomb_case):
    result, fit, held = coulomb_case["result"], coulomb_case["fit"], coulomb_case["held"]
    assert [term["name"] for term in result["terms"]] == ["tanh(v/v0)*p"]
    (term,) = result["terms"]
    assert term["unit"] == "N/Pa" and term["expression"].startswith("p · tanh(v / ")
    # Least squares of one term under white noise: standard error σ / sqrt(Σ f²) over the fitted
    # samples; 4 standard errors leave a 6e-5 chance of failing by noise.
    standard_error = SIGMA_N / np.sqrt(np.sum(coulomb_case["friction"][fit] ** 2))
    assert term["standard_error"] == pytest.approx(standard_error, rel=1e-9)
    assert term["coefficient"] == pytest.approx(COULOMB, abs=4 * standard_error)
    # A perfect explanation leaves the noise: gain 1 - σ / rms(residual). The noise's sample RMS
    # over n held-out samples scatters by σ / sqrt(2n); 4 of those bound the difference.
    held_rms = np.sqrt(np.mean(coulomb_case["residual"][held] ** 2))
    analytic = 1 - SIGMA_N / held_rms
    tolerance = 4 * SIGMA_N / np.sqrt(2 * held.sum()) / held_rms
    assert result["gain"]["force_N"] == pytest.approx(analytic, abs=tolerance)
    assert result["gain_attainable"]["force_N"] == pytest.approx(analytic, rel=1e-12)
    low, high = result["gain_ci95"]["force_N"]
    assert 0 < low <= result["gain"]["force_N"] <= high
    assert result["equation"].startswith("force_N residual ≈ 0.0003 N/Pa · p · tanh(v / ")
    json.dumps(result)  # JSON-ready


def test_the_gain_is_the_held_out_rmse_reduction_of_the_reported_terms(coulomb_case):
    """The definition, recomputed from the reported coefficient: 1 - rmse(r - fit) / rmse(r) on
    the held-out samples."""
    result, held = coulomb_case["result"], coulomb_case["held"]
    fitted = result["terms"][0]["coefficient"] * coulomb_case["friction"]
    r = coulomb_case["residual"]
    expected = 1 - np.sqrt(np.mean((r - fitted)[held] ** 2)) / np.sqrt(np.mean(r[held] ** 2))
    assert result["gain"]["force_N"] == pytest.approx(expected, rel=1e-9)


def test_several_hidden_terms_are_found_with_their_units(coulomb_case):
    """Coulomb friction, a 0.5 N/mm stiffness error and a 4 N load-cell tare together (the tare
    is 7 % of the friction: the selection judges terms against the noise, not against the
    largest term)."""
    features, fit, held = coulomb_case["features"], coulomb_case["fit"], coulomb_case["held"]
    hidden = {"tanh(v/v0)*p": COULOMB, "x": 0.5, "offset": 4.0}
    residual = sum(value * by_name(features, name) for name, value in hidden.items())
    residual = residual + np.random.default_rng(2).normal(0, SIGMA_N, residual.size)
    result = discover(features, residual, SIGMA_N, fit, held, coulomb_case["half_cycle"], "force_N", "N")
    found = {term["name"]: term for term in result["terms"]}
    assert sorted(found) == sorted(hidden)
    assert [found[name]["unit"] for name in hidden] == ["N/Pa", "N/mm", "N"]
    # Least squares on the three columns under white noise: covariance σ² (AᵀA)⁻¹ over the
    # fitted samples; each coefficient within 4 of its standard errors.
    design = np.column_stack([by_name(features, name)[fit] for name in hidden])
    errors = SIGMA_N * np.sqrt(np.diag(np.linalg.inv(design.T @ design)))
    for (name, value), error in zip(hidden.items(), errors):
        assert found[name]["standard_error"] == pytest.approx(error, rel=1e-9)
        assert found[name]["coefficient"] == pytest.approx(value, abs=4 * error)
    # Reported largest contribution first: friction (~70 N), stiffness (0.5 N/mm · ~30 mm), tare.
    assert [term["name"] for term in result["terms"]] == ["tanh(v/v0)*p", "x", "offset"]
    friction, stiffness, tare = (found[name]["coefficient"] for name in hidden)
    assert result["equation"] == (
        f"force_N residual ≈ {friction:.3g} N/Pa · {found['tanh(v/v0)*p']['expression']}"
        f" + {stiffness:.3g} N/mm · x + {tare:.3g} N"
    )


def test_an_offset_is_not_taken_for_terms_of_positive_mean(coulomb_case):
    """A transducer's offset and gain error on the pressure channel, 3 kPa - 2 % of p, 0.5 kPa
    noise. Pressure, x², time and cycle all have positive means: a pursuit on raw columns let
    them stand in for the offset. On centred columns, with the offset as the intercept, the two
    true terms come out."""
    features, fit, held = coulomb_case["features"], coulomb_case["fit"], coulomb_case["held"]
    pressure = coulomb_case["gauge_pressure_Pa"]
    residual = 3e3 - 0.02 * pressure + np.random.default_rng(4).normal(0, 500.0, pressure.size)
    result = discover(features, residual, 500.0, fit, held, coulomb_case["half_cycle"], "gauge_pressure_Pa", "Pa")
    found = {term["name"]: term for term in result["terms"]}
    assert sorted(found) == ["offset", "p"]
    assert (found["p"]["unit"], found["offset"]["unit"]) == ("1", "Pa")
    for name, value in (("p", -0.02), ("offset", 3e3)):
        assert found[name]["coefficient"] == pytest.approx(value, abs=4 * found[name]["standard_error"])


def test_dahl_friction_is_told_from_coulomb_friction(coulomb_case):
    """Dahl friction (a friction law other than the model's tanh), integrated here sample by sample from
    dF/dx = (Fc / xc) (1 - F sign(dx) / Fc) on the true stretch, Fc = 20 N, xc = 2 mm (the
    library's own slip distance is 5 % of the 50 mm stroke, 2.5 mm)."""
    time_s, fit, held = coulomb_case["time_s"], coulomb_case["fit"], coulomb_case["held"]
    true_mm = 25 * (1 - np.cos(2 * np.pi * 10 * time_s / time_s[-1]))
    dahl = np.zeros(time_s.size)
    for i in range(1, time_s.size):
        step = true_mm[i] - true_mm[i - 1]
        dahl[i] = dahl[i - 1] + (20.0 / 2.0) * (1 - dahl[i - 1] * np.sign(step) / 20.0) * step
    residual = dahl + np.random.default_rng(7).normal(0, SIGMA_N, time_s.size)
    features = coulomb_case["features"]
    result = discover(features, residual, SIGMA_N, fit, held, coulomb_case["half_cycle"], "force_N", "N")
    (term,) = result["terms"]
    assert (term["name"], term["unit"]) == ("dahl(x; xc)", "N") and "Dahl" in term["resembles"]
    # The least-squares coefficient of the true friction on the found feature, within 4
    # standard errors; and that feature explains it better than Coulomb's tanh(v/v0) would.
    feature, coulomb = by_name(features, "dahl(x; xc)")[fit], by_name(features, "tanh(v/v0)")[fit]
    expected = np.dot(dahl[fit], feature) / np.dot(feature, feature)
    assert term["coefficient"] == pytest.approx(expected, abs=4 * SIGMA_N / np.linalg.norm(feature))

    def left(column):
        return np.linalg.norm(dahl[fit] - np.dot(dahl[fit], column) / np.dot(column, column) * column)

    assert left(feature) < left(coulomb)


def test_a_nonlinear_load_cell_is_found_from_the_model_force(coulomb_case):
    """A load cell reading 0.02 % per newton high (a quadratic load cell): the
    residual is 2e-4 N⁻¹ · F² of the model's force F, here 1 N/kPa · p + 8 N/mm · x."""
    time_s, elongation_m, pressure = (coulomb_case[key] for key in ("time_s", "elongation_m", "gauge_pressure_Pa"))
    force = 1e-3 * pressure + 8.0 * 1e3 * elongation_m
    features = feature_library(time_s, elongation_m, pressure, force_N=force)
    residual = 2e-4 * force**2 + np.random.default_rng(6).normal(0, SIGMA_N, force.size)
    fit, held = coulomb_case["fit"], coulomb_case["held"]
    result = discover(features, residual, SIGMA_N, fit, held, coulomb_case["half_cycle"], "force_N", "N")
    (term,) = result["terms"]
    assert (term["name"], term["unit"]) == ("F^2", "1/N") and "nonlinear load cell" in term["resembles"]
    standard_error = SIGMA_N / np.linalg.norm(force[fit] ** 2)  # one term, white noise
    assert term["coefficient"] == pytest.approx(2e-4, abs=4 * standard_error)


@pytest.mark.parametrize("correlation", [0.0, 0.9])
def test_noise_alone_is_not_a_discovery(correlation):
    """White noise, and noise correlated from sample to sample (AR(1), 0.9: what a load cell's
    filter leaves), on the stretch record: over 20 seeds nothing is selected. (The one-standard-
    error rule alone selects a spurious term for about half of them, with gains below 1 %; the
    gates — 2 standard errors and a tenth of the noise better than no term — stop them: none
    selected over 50 seeds per case.)"""
    time_s, elongation_m, pressure_Pa, cycle, half_cycle, fit, held = stretch_record()
    features = feature_library(time_s, elongation_m, pressure_Pa, cycle=cycle)
    for seed in range(20):
        white = np.random.default_rng(1000 + seed).normal(0, SIGMA_N, time_s.size)
        noise = np.empty_like(white)
        noise[0] = white[0]
        for i in range(1, noise.size):
            noise[i] = correlation * noise[i - 1] + np.sqrt(1 - correlation**2) * white[i]
        result = discover(features, noise, SIGMA_N, fit, held, half_cycle, "force_N", "N", seed=seed)
        assert result["terms"] == [], (seed, result["equation"])
        assert result["gain"] == {"force_N": 0.0} and result["gain_ci95"] == {"force_N": [0.0, 0.0]}
        assert result["equation"] == "force_N residual ≈ 0 (no term beats zero on held-out data)"


def test_pressurise_vent_hysteresis_is_found_in_an_isometric_sweep():
    """Venting force 40 N above pressurising force (a commercial muscle's loop): a residual of
    -20 N while pressurising and +20 N while venting, 0.24 N noise (that test's)."""
    time_s, elongation_m, pressure_Pa, direction, sweep = step_sweep()
    features = feature_library(time_s, elongation_m, pressure_Pa, cycle=sweep)
    names = [term.name for term in features]
    # Held at one length: no velocity terms and no elongation terms (constant: the offset's).
    assert names == ["offset", "p", "dp/dt", "sign(dp/dt)", "sign(dp/dt)*p", "t", "cycle"]
    sigma = 0.24
    residual = -20.0 * direction + np.random.default_rng(5).normal(0, sigma, time_s.size)
    fit = sweep % 2 == 0
    result = discover(features, residual, sigma, fit, ~fit, sweep, "force_N", "N")
    assert [term["name"] for term in result["terms"]] == ["sign(dp/dt)"]
    (term,) = result["terms"]
    assert term["unit"] == "N" and "hysteresis" in term["resembles"]
    # The branch follows the programmed direction except within its deadband after a step; the
    # least-squares coefficient of the true -20 N · direction on the branch b is
    # -20 <direction, b> / <b, b> over the fitted samples, within 4 standard errors.
    branch = by_name(features, "sign(dp/dt)")
    expected = -20.0 * np.dot(direction[fit], branch[fit]) / np.dot(branch[fit], branch[fit])
    assert expected == pytest.approx(-20.0, rel=0.01)  # the branch is the pressurise/vent state
    standard_error = sigma / np.sqrt(np.dot(branch[fit], branch[fit]))
    assert term["coefficient"] == pytest.approx(expected, abs=4 * standard_error)
    assert result["gain_ci95"]["force_N"][0] > 0.9


@pytest.fixture
def bench_measurement():
    """Table C.2's 90 % test (0.167 m, 236.63 kPa), two cycles of 5 cm at 2.5 mm/s with holds."""
    params = pamkit.MuscleParams()
    initial = pamkit.InitialState(length_m=0.167, gauge_pressure_Pa=236.63e3)
    crosshead = pamkit.thesis_protocol(0.05, 2.5e-3, 2, 0.1, 2.0)
    return params, initial, crosshead


def test_a_saved_effect_round_trips_and_adds_the_fitted_correction(coulomb_case, tmp_path, bench_measurement):
    result = coulomb_case["result"]
    path = tmp_path / "friction.json"
    save_effect(result, path)
    effect = load_effect(path)
    assert isinstance(effect, pamkit.Effect) and effect.name() == "discovered_force_N"
    (parameter,) = effect.parameters()
    assert (parameter.name, parameter.value, parameter.unit) == ("c0", result["terms"][0]["coefficient"], "N/Pa")
    assert parameter.realistic_min < parameter.value < parameter.realistic_max

    # On the record it was fitted to, the effect adds exactly the fitted correction.
    measurement = pamkit.Measurement()
    measurement.time_s = coulomb_case["time_s"]
    measurement.elongation_m = coulomb_case["elongation_m"]
    measurement.gauge_pressure_Pa = coulomb_case["gauge_pressure_Pa"]
    measurement.force_N = np.zeros(coulomb_case["time_s"].size)
    measurement.temperature_K = np.full(coulomb_case["time_s"].size, 293.15)
    corrected = effect.apply_to_measurement(measurement)
    np.testing.assert_allclose(corrected.force_N, parameter.value * coulomb_case["friction"], rtol=1e-12, atol=1e-12)
    np.testing.assert_array_equal(corrected.gauge_pressure_Pa, coulomb_case["gauge_pressure_Pa"])

    # In the next run: a simulation with the effect is the one without plus the correction,
    # the correction computed on that simulation's own record with the fitted record's v0.
    params, initial, crosshead = bench_measurement
    catalog = builtin_catalog()
    catalog.add(effect.name(), lambda: load_effect(path))
    with_effect = pamkit.simulate_measurement(params, initial, crosshead, [catalog.parse("discovered_force_N")])
    without = pamkit.simulate_measurement(params, initial, crosshead, [])
    expected = effect.correction(without.time_s, without.elongation_m, without.gauge_pressure_Pa, without.temperature_K)
    assert np.ptp(expected) > 10.0  # ±3e-4 N/Pa · ~240 kPa: it acts
    np.testing.assert_allclose(with_effect.force_N, without.force_N + expected, rtol=1e-12, atol=1e-9)
    # Its coefficient is a parameter like any effect's, set from `--effect` text.
    halved = catalog.parse(f"discovered_force_N:c0={parameter.value / 2}")
    np.testing.assert_allclose(
        pamkit.simulate_measurement(params, initial, crosshead, [halved]).force_N,
        without.force_N + expected / 2,
        rtol=1e-12,
        atol=1e-9,
    )
    with pytest.raises(ValueError, match="discovered_force_N has no parameter 'c1'"):
        catalog.parse("discovered_force_N:c1=1")


def test_bad_input_is_named():
    time_s, elongation_m, pressure_Pa, _, half_cycle, fit, held = stretch_record(n=2000)
    features = feature_library(time_s, elongation_m, pressure_Pa)
    residual = np.zeros(time_s.size)
    with pytest.raises(DiscoveryError, match="gauge_pressure_Pa has 1999 samples, time_s has 2000"):
        feature_library(time_s, elongation_m, pressure_Pa[:-1])
    with pytest.raises(DiscoveryError, match="time_s must increase strictly"):
        feature_library(time_s[::-1], elongation_m, pressure_Pa)
    with pytest.raises(DiscoveryError, match="fit_mask and held_mask share 2000 sample"):
        discover(features, residual, 1.0, fit | held, fit | held, half_cycle, "force_N", "N")
    with pytest.raises(DiscoveryError, match="held_mask covers 1 unit"):
        discover(features, residual, 1.0, fit, held & (half_cycle == 3), half_cycle, "force_N", "N")
    with pytest.raises(DiscoveryError, match="noise_sigma = 0.0 must be a positive number"):
        discover(features, residual, 0.0, fit, held, half_cycle, "force_N", "N")


def test_nothing_discovered_is_no_effect_and_a_bad_file_is_named(tmp_path):
    with pytest.raises(DiscoveryError, match="no terms were discovered for force_N"):
        discovered_effect({"channel": "force_N", "terms": [], "equation": ""})
    broken = tmp_path / "broken.json"
    broken.write_text('{"format": "pamkit.discovered_effect",\n "version": 2,\n "terms": [}\n')
    with pytest.raises(DiscoveryError, match=r"broken.json:3: not JSON"):
        load_effect(broken)
    other = tmp_path / "other.json"
    other.write_text(
        '{"format": "pamkit.discovered_effect", "version": 2, "channel": "force_N", '
        '"terms": [{"name": "creep", "expression": "c", "coefficient": 1, "unit": "N"}]}'
    )
    with pytest.raises(DiscoveryError, match=r"other.json: discovered effect: terms\[0\].name = 'creep' is not"):
        load_effect(other)


def sklearn_path(columns, target, max_terms):
    """scikit-learn's orthogonal matching pursuit path, as the columns chosen at each step."""
    import warnings

    from sklearn.linear_model import orthogonal_mp

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)  # a path that ends early says so
        coefficients = orthogonal_mp(columns, target, n_nonzero_coefs=max_terms, return_path=True)
    coefficients = coefficients.reshape(columns.shape[1], -1)
    return [np.flatnonzero(coefficients[:, step]).tolist() for step in range(coefficients.shape[1])]


@pytest.mark.parametrize("seed", range(40))
def test_the_pursuit_takes_the_path_of_scikit_learns_orthogonal_matching_pursuit(seed):
    # Random unit-norm designs: a sparse truth in noise, with duplicated and dependent columns
    # (where the path must end early, as scikit-learn's does) on every fourth seed.
    from pamkit.diagnosis.discover import pursuit

    rng = np.random.default_rng(seed)
    samples, count = int(rng.integers(8, 200)), int(rng.integers(2, 14))
    columns = rng.normal(size=(samples, count))
    if seed % 4 == 0:
        columns[:, -1] = columns[:, 0] - 0.5 * columns[:, 1]
    columns /= np.linalg.norm(columns, axis=0)
    truth = np.zeros(count)
    truth[rng.choice(count, size=min(3, count), replace=False)] = rng.normal(0, 3, size=min(3, count))
    target = columns @ truth + rng.normal(0, 0.1, samples)
    steps = min(5, count)
    assert pursuit(columns, target, steps) == sklearn_path(columns, target, steps)


def test_the_pursuit_takes_scikit_learns_path_on_a_stretch_records_library(coulomb_case):
    from pamkit.diagnosis.discover import pursuit

    X = np.column_stack([values for term, values in coulomb_case["features"].items() if term.name != "offset"])
    fit = coulomb_case["fit"]
    columns = X[fit] - X[fit].mean(axis=0)
    usable = np.linalg.norm(columns, axis=0) > 1e-9
    columns = columns[:, usable] / np.linalg.norm(columns[:, usable], axis=0)
    target = coulomb_case["residual"][fit] - coulomb_case["residual"][fit].mean()
    assert pursuit(columns, target, 5) == sklearn_path(columns, target, 5)
