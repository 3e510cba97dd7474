"""pamkit: simulate and diagnose pneumatic artificial muscles used as passive air springs.

The compiled core (`pamkit._core`) holds the thesis's muscle model and its CVODES simulator;
this package adds experiment files, the command line and plots. SI units throughout, except
where a name carries its unit (``pressure_kPa``).

A notebook's three calls:

    experiment = pamkit.load_experiment("experiment.toml")  # the muscle, the test, the measured columns
    df = pamkit.simulate(experiment)  # DataFrame: time_s, elongation_m, force_N, pressure_kPa, temperature_C
    report = pamkit.diagnose("experiment.toml")  # .verdict(), .to_json(path), .plot(path)

``pamkit.simulate`` and ``pamkit.diagnose`` are modules too (``from pamkit.simulate import
simulate_experiment``); calling one calls its main function (pamkit._callable says why).
"""

import importlib

from pamkit._core import (
    BiaxialStress,
    BladderLaw,
    BraidGeometry,
    Construction,
    Effect,
    EffectCatalog,
    EffectParameter,
    EffectStage,
    ElongationTrajectory,
    Error,
    FiberTensions,
    FitScale,
    FreeInflation,
    FrictionParams,
    GasMode,
    GasParams,
    GasProcess,
    InitialState,
    IntegrationMethod,
    InvalidInput,
    InvalidParameter,
    IsotonicLengths,
    IsotonicMotion,
    IsotonicMotionConfig,
    Measurement,
    ModelExtensions,
    MuscleBuild,
    MuscleForces,
    MuscleModel,
    MuscleOutputs,
    MuscleParams,
    MuscleParamsFile,
    MuscleShape,
    Resolution,
    SimulationResult,
    Simulator,
    SimulatorConfig,
    SolverError,
    SolverStatistics,
    State,
    StiffnessEstimate,
    braid_cylinder_length,
    braid_diameter,
    braid_fiber_length,
    braid_tension,
    deflated_braid_angle_deg,
    estimate_stiffness,
    fiber_revolutions_for_braid_angle,
    free_inflation,
    inflated_and_sealed,
    isotonic_lengths,
    isotonic_motion,
    measured_channels,
    muscle_forces,
    newtonian_fiber_tensions,
    polytropic_pressure,
    polytropic_temperature,
    pressure_branches,
    read_muscle_params,
    read_muscle_params_file,
    simulate_measurement,
    simulate_supplied_measurement,
    static_forces,
    thesis_protocol,
    write_muscle_params,
)
from pamkit.io.experiment import Experiment, ExperimentError, load_experiment

__version__ = "0.1.0"

# Imported on first use: pamkit.diagnose takes seconds to import (SciPy, scikit-learn), and the
# command line and `import pamkit` should not wait for it.
_LAZY_MODULES = ("simulate", "diagnose")


def __getattr__(name: str):
    if name in _LAZY_MODULES:
        return importlib.import_module(f"pamkit.{name}")
    raise AttributeError(f"module 'pamkit' has no attribute {name!r}")


__all__ = [name for name in dir() if not name.startswith("_") and name != "importlib"] + list(_LAZY_MODULES)


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(_LAZY_MODULES))
