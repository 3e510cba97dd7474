"""pamkit.isotonic_motion from Python: numpy in and out, the same equilibrium as
isotonic_lengths, effects from the catalog, and bad input as ValueError naming it."""

from __future__ import annotations

from concurrent.futures import ThreadPoolExecutor

import numpy as np
import pytest

import pamkit

LOAD_N = 100.0


def pressure_step() -> tuple[np.ndarray, np.ndarray]:
    """200 kPa for 1 s, then 300 kPa over 10 ms, held to 10 s."""
    time = np.linspace(0.0, 10.0, 1001)
    return time, np.interp(time, [0.0, 1.0, 1.01, 10.0], [200e3, 200e3, 300e3, 300e3])


def test_a_pressure_step_moves_the_mass_between_the_two_equilibria():
    # The mass starts at rest on the 200 kPa equilibrium (the default start) and, the friction
    # damping it (relaxation time c / k ~ 0.35 s), comes to rest on the 300 kPa one: 9 s take
    # the 11.5 mm between them below the solver's 1e-10 m.
    params = pamkit.MuscleParams()
    time, pressure = pressure_step()
    motion = pamkit.isotonic_motion(params, time, pressure, LOAD_N, 2.0)
    static = pamkit.isotonic_lengths(params, np.array([200e3, 300e3]), LOAD_N, params.build.length_m)
    for column in (motion.time_s, motion.length_m, motion.velocity_m_per_s, motion.force_N):
        assert isinstance(column, np.ndarray)
        assert column.dtype == np.float64
        assert column.shape == time.shape
    np.testing.assert_array_equal(motion.gauge_pressure_Pa, pressure)
    assert motion.length_m[0] == static.length_m[0]
    assert motion.length_m[-1] == pytest.approx(static.length_m[1], abs=1e-9)
    assert motion.force_N[-1] == pytest.approx(LOAD_N, rel=1e-7)
    # Raising the pressure only shortens it (overdamped): no lengthening beyond the solver's
    # velocity tolerance.
    assert np.all(motion.velocity_m_per_s[time > 1.0] < pamkit.IsotonicMotionConfig().absolute_tolerance_m_per_s)
    assert motion.statistics.steps > 0


def test_effects_and_config_pass_through_and_threads_share_the_module():
    params = pamkit.MuscleParams()
    time, pressure = pressure_step()
    hysteresis = pamkit.EffectCatalog.builtin().parse("pressure_hysteresis:coefficient=0.05")
    config = pamkit.IsotonicMotionConfig(relative_tolerance=1e-9)
    plain = pamkit.isotonic_motion(params, time, pressure, LOAD_N, 2.0, config=config)
    with ThreadPoolExecutor(max_workers=2) as pool:  # the GIL is released while each runs
        runs = list(
            pool.map(
                lambda effects: pamkit.isotonic_motion(params, time, pressure, LOAD_N, 2.0, None, effects, config),
                [[hysteresis], [hysteresis]],
            )
        )
    np.testing.assert_array_equal(runs[0].length_m, runs[1].length_m)
    # Pressurising, the bladder-braid friction holds the muscle back: it stays longer.
    assert runs[0].length_m[-1] > plain.length_m[-1] + 1e-4


def test_bad_input_is_a_value_error_that_names_it():
    params = pamkit.MuscleParams()
    time, pressure = pressure_step()
    with pytest.raises(pamkit.InvalidParameter, match="mass_kg = -1 kg"):
        pamkit.isotonic_motion(params, time, pressure, LOAD_N, -1.0)
    with pytest.raises(ValueError, match="1000 pressures for 1001 times"):
        pamkit.isotonic_motion(params, time, pressure[:-1], LOAD_N, 1.0)
    with pytest.raises(ValueError, match="the longest the braid allows"):
        pamkit.isotonic_motion(params, time, pressure, 5000.0, 1.0)
