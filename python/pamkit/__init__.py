"""pamkit: simulate and diagnose pneumatic artificial muscles used as passive air springs.

The compiled core (`pamkit._core`) holds the thesis's muscle model and its CVODES simulator;
this package adds experiment files, the command line and plots. SI units throughout, except
where a name carries its unit (``pressure_kPa``).
"""

from pamkit._core import (
    BiaxialStress,
    BladderLaw,
    BraidGeometry,
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
    InvalidInput,
    InvalidParameter,
    IsotonicLengths,
    Measurement,
    ModelExtensions,
    MuscleBuild,
    MuscleForces,
    MuscleModel,
    MuscleOutputs,
    MuscleParams,
    MuscleShape,
    Resolution,
    SimulationResult,
    Simulator,
    SimulatorConfig,
    SolverError,
    SolverStatistics,
    State,
    braid_cylinder_length,
    braid_diameter,
    braid_fiber_length,
    braid_tension,
    deflated_braid_angle_deg,
    fiber_revolutions_for_braid_angle,
    free_inflation,
    inflated_and_sealed,
    isotonic_lengths,
    measured_channels,
    muscle_forces,
    newtonian_fiber_tensions,
    polytropic_pressure,
    polytropic_temperature,
    pressure_branches,
    simulate_measurement,
    simulate_supplied_measurement,
    static_forces,
    thesis_protocol,
)

__version__ = "0.1.0"

__all__ = [name for name in dir() if not name.startswith("_")]
