"""Simulate an experiment: drive the model with the experiment's time and elongation and
predict force, pressure and temperature."""

from __future__ import annotations

import numpy as np

from collections.abc import Sequence

from pamkit._core import (
    BladderLaw,
    BraidGeometry,
    Effect,
    ElongationTrajectory,
    GasMode,
    InitialState,
    Measurement,
    MuscleParams,
    Simulator,
    SimulatorConfig,
    free_inflation,
    muscle_forces,
    simulate_measurement,
)
from pamkit.experiment import Experiment, ExperimentError

PASCAL_PER_KPA = 1e3


def muscle_params(experiment: Experiment, bladder: BladderLaw | None = None) -> MuscleParams:
    """The model parameters an experiment file describes (thesis bladder law unless given)."""
    return MuscleParams(
        build=experiment.build,
        bladder=bladder if bladder is not None else BladderLaw.thesis(),
        friction=experiment.friction,
        gas=experiment.gas_params,
    )


def initial_length(experiment: Experiment, params: MuscleParams) -> float:
    """Length at zero elongation: as given, else the free inflated length (sealed test) or the
    deflated length (supplied test), as DESIGN.md specifies."""
    if experiment.initial_length_m is not None:
        return experiment.initial_length_m
    if experiment.gas == "supplied":
        return experiment.build.length_m
    inflated = free_inflation(
        BraidGeometry(params.build),
        params.bladder,
        params.gas.atmospheric_pressure_Pa,
        experiment.inflation_pressure_kPa * PASCAL_PER_KPA,
    )
    return inflated.length_m


def simulate_experiment(
    experiment: Experiment,
    params: MuscleParams | None = None,
    config: SimulatorConfig | None = None,
    effects: Sequence[Effect] = (),
) -> dict[str, np.ndarray]:
    """Predicts the experiment's channels at its sample times, with `effects` applied.

    Returns the columns time_s, elongation_m, force_N, pressure_kPa (gauge), temperature_C. In
    a sealed test the gas is a closed mass integrated by CVODES; in a supplied test the
    measured pressure drives the model and the gas stays at ambient temperature.

    Raises:
        ExperimentError: for an effect that cannot act in this kind of test, or data the model
            cannot follow (naming the file and sample).
    """
    params = params if params is not None else muscle_params(experiment)
    mode = GasMode.supplied if experiment.gas == "supplied" else GasMode.sealed
    for effect in effects:
        acts, why_not = effect.acts_in(mode)
        if not acts:
            raise ExperimentError(f"{experiment.path}: effect {effect.name()} cannot act here: {why_not}")
    length0 = initial_length(experiment, params)
    try:
        if mode == GasMode.supplied:
            measurement = _measure_supplied(experiment, params, length0, effects)
        else:
            initial = InitialState(length_m=length0, gauge_pressure_Pa=experiment.inflation_pressure_kPa * PASCAL_PER_KPA)
            trajectory = ElongationTrajectory(experiment.time_s, experiment.elongation_m)
            simulator = Simulator(config if config is not None else SimulatorConfig())
            measurement = simulate_measurement(params, initial, trajectory, list(effects), simulator)
    except ValueError as error:
        raise ExperimentError(f"{experiment.data_path}: {error}") from None
    return {name: getattr(measurement, name) for name in ("time_s", "elongation_m", "force_N", "pressure_kPa", "temperature_C")}


def _measure_supplied(experiment: Experiment, params: MuscleParams, length0: float, effects: Sequence[Effect]) -> Measurement:
    """The static model at the measured pressure, sample by sample, through the effects."""
    for effect in effects:
        params = effect.apply_to_params(params)
    geometry = BraidGeometry(params.build)
    time = experiment.time_s
    crosshead = experiment.elongation_m
    motion = crosshead
    for effect in effects:
        motion = np.asarray(effect.apply_to_elongation(time, motion))
    gauge = experiment.columns["pressure_kPa"] * PASCAL_PER_KPA
    # The rate of the segment ending at each sample (of the first segment at the start), as
    # the sealed simulation uses.
    rate = np.diff(motion) / np.diff(time)
    velocity = np.concatenate([rate[:1], rate])
    atmosphere = params.gas.atmospheric_pressure_Pa
    force = np.empty_like(time)
    for k, (stretch, pressure, speed) in enumerate(zip(motion, gauge, velocity)):
        try:
            shape = geometry.shape(length0 + stretch)
        except ValueError as error:
            raise ExperimentError(f"{experiment.data_path}: data row {k + 1} (time_s = {time[k]}): {error}") from None
        force[k] = muscle_forces(geometry, shape, params.bladder, params.friction, pressure + atmosphere, atmosphere, speed).total
    measurement = Measurement()
    measurement.time_s = time
    measurement.elongation_m = crosshead
    measurement.force_N = force
    measurement.pressure_kPa = gauge / PASCAL_PER_KPA
    measurement.temperature_C = np.full_like(time, experiment.ambient_temperature_C)
    for effect in effects:
        measurement = effect.apply_to_measurement(measurement)
    return measurement
