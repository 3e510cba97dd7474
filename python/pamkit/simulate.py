"""Simulate an experiment: drive the model with the experiment's time and elongation and
predict force, pressure and temperature."""

from __future__ import annotations

import numpy as np

from pamkit._core import (
    BladderLaw,
    BraidGeometry,
    ElongationTrajectory,
    InitialState,
    MuscleModel,
    MuscleParams,
    Simulator,
    SimulatorConfig,
    free_inflation,
    muscle_forces,
)
from pamkit.experiment import KELVIN_OFFSET, Experiment, ExperimentError

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
    experiment: Experiment, params: MuscleParams | None = None, config: SimulatorConfig | None = None
) -> dict[str, np.ndarray]:
    """Predicts the experiment's channels at its sample times.

    Returns columns time_s, elongation_m, force_N, pressure_kPa (gauge), temperature_C, and
    length_m, gas_volume_m3, braid_angle_rad. In a sealed test the gas is a closed mass
    integrated by CVODES; in a supplied test the measured pressure drives the model and the gas
    stays at ambient temperature.
    """
    params = params if params is not None else muscle_params(experiment)
    length0 = initial_length(experiment, params)
    if experiment.gas == "supplied":
        return _simulate_supplied(experiment, params, length0)
    model = MuscleModel(params, InitialState(length_m=length0, gauge_pressure_Pa=experiment.inflation_pressure_kPa * PASCAL_PER_KPA))
    trajectory = ElongationTrajectory(experiment.time_s, experiment.elongation_m)
    try:
        result = Simulator(config if config is not None else SimulatorConfig()).run(model, trajectory)
    except ValueError as error:
        raise ExperimentError(f"{experiment.data_path}: {error}") from None
    return {
        "time_s": np.array(result.time_s),
        "elongation_m": np.array(result.elongation_m),
        "force_N": np.array(result.force_N),
        "pressure_kPa": np.array(result.pressure_gauge_Pa) / PASCAL_PER_KPA,
        "temperature_C": np.array(result.temperature_K) - KELVIN_OFFSET,
        "length_m": np.array(result.length_m),
        "gas_volume_m3": np.array(result.gas_volume_m3),
        "braid_angle_rad": np.array(result.braid_angle_rad),
    }


def _simulate_supplied(experiment: Experiment, params: MuscleParams, length0: float) -> dict[str, np.ndarray]:
    geometry = BraidGeometry(params.build)
    time = experiment.time_s
    elongation = experiment.elongation_m
    gauge = experiment.columns["pressure_kPa"] * PASCAL_PER_KPA
    # The rate of the segment ending at each sample (of the first segment at the start), as
    # the sealed simulation uses.
    rate = np.diff(elongation) / np.diff(time)
    velocity = np.concatenate([rate[:1], rate])
    atmosphere = params.gas.atmospheric_pressure_Pa
    columns = {name: np.empty_like(time) for name in ("force_N", "length_m", "gas_volume_m3", "braid_angle_rad")}
    for k, (stretch, pressure, speed) in enumerate(zip(elongation, gauge, velocity)):
        length = length0 + stretch
        try:
            shape = geometry.shape(length)
        except ValueError as error:
            raise ExperimentError(f"{experiment.data_path}: data row {k + 1} (time_s = {time[k]}): {error}") from None
        forces = muscle_forces(geometry, shape, params.bladder, params.friction, pressure + atmosphere, atmosphere, speed)
        columns["force_N"][k] = forces.total
        columns["length_m"][k] = length
        columns["gas_volume_m3"][k] = shape.gas_volume
        columns["braid_angle_rad"][k] = shape.braid_angle
    return {
        "time_s": time.copy(),
        "elongation_m": elongation.copy(),
        "force_N": columns["force_N"],
        "pressure_kPa": gauge / PASCAL_PER_KPA,
        "temperature_C": np.full_like(time, experiment.ambient_temperature_C),
        "length_m": columns["length_m"],
        "gas_volume_m3": columns["gas_volume_m3"],
        "braid_angle_rad": columns["braid_angle_rad"],
    }
