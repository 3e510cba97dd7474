"""Simulator.run_sensitivities from Python, as the README shows it: the derivatives are views into
the result that keep it alive, and bad steps are refused by name (the algorithm itself:
tests/cpp/sensitivities.test.cpp)."""

import gc

import numpy as np
import pytest

import pamkit

P0 = 236.63e3  # table C.2's gauge pressure [Pa]


def sealed(gauge_Pa: float) -> pamkit.MuscleModel:
    params = pamkit.MuscleParams(
        gas=pamkit.GasParams(process=pamkit.GasProcess.heat_transfer, heat_transfer_time_constant_s=5.0)
    )
    return pamkit.MuscleModel(params, pamkit.InitialState(length_m=0.167, gauge_pressure_Pa=gauge_Pa))


def test_the_readmes_pressure_sensitivity_is_the_sealed_gas_closed_form():
    h = 1e-6 * P0
    s = pamkit.Simulator().run_sensitivities(sealed(P0), [sealed(P0 + h)], [h], pamkit.thesis_protocol(0.0523))
    derivative = s.derivatives[0]
    del s
    gc.collect()  # the derivatives hold the result alive
    atmosphere = pamkit.GasParams().atmospheric_pressure_Pa
    run = pamkit.Simulator().run(sealed(P0), pamkit.thesis_protocol(0.0523))
    # The mass is proportional to p_abs(0), the temperature independent of it (heat per unit mass);
    # measured 8.5e-10 off, the closed form near 1.5.
    closed_form = (np.asarray(run.gauge_pressure_Pa) + atmosphere) / (P0 + atmosphere)
    assert np.max(np.abs(np.asarray(derivative.gauge_pressure_Pa) - closed_form)) < 1e-8
    assert not np.any(derivative.elongation_m)


def test_a_zero_step_is_refused_by_its_index():
    with pytest.raises(ValueError, match="step 1 is 0"):
        pamkit.Simulator().run_sensitivities(
            sealed(P0), [sealed(P0 + 1.0), sealed(P0 + 2.0)], [1.0, 0.0], pamkit.thesis_protocol(0.03, cycles=1)
        )
