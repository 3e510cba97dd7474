"""
pamkit's compiled core: the muscle model of the thesis and its CVODES simulator (SI units).
"""
from __future__ import annotations
import collections.abc
import numpy
import numpy.typing
import os
import typing
from . import logger
from . import units
__all__: list[str] = ['BatchResult', 'BiaxialStress', 'BladderLaw', 'BraidGeometry', 'Clutch', 'ClutchMode', 'ClutchParams', 'Construction', 'DeviceRun', 'Effect', 'EffectCatalog', 'EffectParameter', 'EffectStage', 'ElongationTrajectory', 'Error', 'FiberTensions', 'FitScale', 'FreeInflation', 'FrictionParams', 'GaitCycle', 'GaitData', 'GaitEvents', 'GasMode', 'GasParams', 'GasProcess', 'IdealSpring', 'InitialState', 'IntegrationMethod', 'InvalidInput', 'InvalidParameter', 'IsotonicLengths', 'IsotonicMotion', 'IsotonicMotionConfig', 'Jig', 'JigParams', 'JigSample', 'LinearSpring', 'Linkage', 'LinkageParams', 'LinkagePose', 'Measurement', 'ModelExtensions', 'MuscleBuild', 'MuscleForces', 'MuscleModel', 'MuscleOutputs', 'MuscleParams', 'MuscleParamsFile', 'MuscleShape', 'PRESSURE_BRANCH_PLAY_PA', 'PamStaticSpring', 'ParameterSets', 'PlayParams', 'Resolution', 'RunFailure', 'ScriptKinematics', 'SensitivityResult', 'ShapeTable', 'SimulationResult', 'Simulator', 'SimulatorConfig', 'SolverError', 'SolverStatistics', 'State', 'StiffnessEstimate', 'Table42Row', 'ThesisPolynomialSpring', 'WINTER_SUBJECT_MASS_KG', 'braid_cylinder_length', 'braid_diameter', 'braid_fiber_length', 'braid_tension', 'deflated_braid_angle_deg', 'detect_gait_events', 'estimate_stiffness', 'fiber_revolutions_for_braid_angle', 'fit_clutch', 'free_inflation', 'ideal_spring', 'inflated_and_sealed', 'isotonic_lengths', 'isotonic_motion', 'logger', 'measured_channels', 'muscle_forces', 'newtonian_fiber_tensions', 'polytropic_pressure', 'polytropic_temperature', 'pressure_branches', 'read_muscle_params', 'read_muscle_params_file', 'reproduce_g3_script', 'resample_cycle', 'run_device', 'simulate_measurement', 'simulate_measurement_blocks', 'simulate_supplied_measurement', 'static_forces', 'table_4_2', 'thesis_protocol', 'units', 'walking_trajectory', 'winter_appendix_g3', 'with_ankle_range', 'write_muscle_params']
class Error(RuntimeError):
    pass
class SolverError(RuntimeError):
    pass
class InvalidInput(ValueError):
    pass
class InvalidParameter(ValueError):
    pass
class Construction:
    """
    How the fibres and the membrane are put together.
    
    Members:
    
      sleeve : a bladder inside a braided sleeve (the thesis's muscle)
    
      embedded : fibres embedded in the membrane: the braid cannot push
    """
    __members__: typing.ClassVar[dict[str, Construction]]
    embedded: typing.ClassVar[Construction]
    sleeve: typing.ClassVar[Construction]
    @typing.overload
    def __eq__(self, other: Construction) -> bool:
        ...
    @typing.overload
    def __eq__(self, other: typing.Any) -> bool:
        ...
    def __getstate__(self) -> int:
        ...
    def __hash__(self) -> int:
        ...
    def __index__(self) -> int:
        ...
    def __init__(self, value: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    def __int__(self) -> int:
        ...
    @typing.overload
    def __ne__(self, other: Construction) -> bool:
        ...
    @typing.overload
    def __ne__(self, other: typing.Any) -> bool:
        ...
    def __repr__(self) -> str:
        ...
    def __setstate__(self, state: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    def __str__(self) -> str:
        ...
    @property
    def name(self) -> str:
        ...
    @property
    def value(self) -> int:
        ...
class MuscleBuild:
    """
    The muscle as built and deflated (SI units; thesis tables 3.4, C.4).
    """
    @staticmethod
    def fields() -> dict:
        """
        Field names mapped to their unit, allowed range and meaning.
        """
    def __init__(self, **kwargs) -> None:
        """
        Keyword construction; fields not given keep their documented defaults.
        """
    def __repr__(self) -> str:
        ...
    def to_dict(self) -> dict:
        ...
    def validate(self) -> None:
        """
        Raises ValueError naming the first field out of range.
        """
    @property
    def bladder_diameter_m(self) -> float:
        """
        deflated bladder outer diameter [m], allowed [0.001000, 0.500000]
        """
    @bladder_diameter_m.setter
    def bladder_diameter_m(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def bladder_thickness_m(self) -> float:
        """
        bladder wall thickness [m], allowed [0.000000, 0.010000]
        """
    @bladder_thickness_m.setter
    def bladder_thickness_m(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def cone_generator_m(self) -> float:
        """
        slant length of each end cone Lz (0: flat ends) [m], allowed [0.000000, 0.500000]
        """
    @cone_generator_m.setter
    def cone_generator_m(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def construction(self) -> Construction:
        """
        sleeve (a bladder in a braided sleeve, the thesis's) or embedded (fibres in the membrane)
        """
    @construction.setter
    def construction(self, arg0: Construction) -> None:
        ...
    @property
    def diameter_m(self) -> float:
        """
        deflated braid diameter [m], allowed [0.001000, 0.500000]
        """
    @diameter_m.setter
    def diameter_m(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def end_diameter_m(self) -> float:
        """
        end cap diameter d [m], allowed [0.000100, 0.500000]
        """
    @end_diameter_m.setter
    def end_diameter_m(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def end_zone_m(self) -> float:
        """
        flat ends: braid at each flange that keeps its deflated shape (0: none) [m], allowed [0.000000, 0.500000]
        """
    @end_zone_m.setter
    def end_zone_m(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def fiber_count(self) -> float:
        """
        number of braid fibers N [1], allowed [2.000000, 5000.000000]
        """
    @fiber_count.setter
    def fiber_count(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def fiber_revolutions(self) -> float:
        """
        fiber turns n over the cylinder [1], allowed [0.100000, 100.000000]
        """
    @fiber_revolutions.setter
    def fiber_revolutions(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def fiber_thickness_m(self) -> float:
        """
        thickness of one fiber [m], allowed [0.000000, 0.010000]
        """
    @fiber_thickness_m.setter
    def fiber_thickness_m(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def length_m(self) -> float:
        """
        deflated length between the end caps [m], allowed [0.010000, 5.000000]
        """
    @length_m.setter
    def length_m(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def series_compliance_m_per_N(self) -> float:
        """
        stretch in series with the braid per newton of pull, in tables and supplied tests (0: rigid) [m/N], allowed [0.000000, 0.001000]
        """
    @series_compliance_m_per_N.setter
    def series_compliance_m_per_N(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
class BiaxialStress:
    """
    Stresses or tangent moduli of the bladder in its two directions [Pa].
    """
    def __repr__(self) -> str:
        ...
    @property
    def hoop(self) -> float:
        ...
    @property
    def longitudinal(self) -> float:
        ...
class BladderLaw:
    """
    The bladder's membrane law: the thesis's polynomials of each strain, or an incompressible neo-Hookean membrane.
    """
    class Form:
        """
        Members:
        
          polynomial
        
          neo_hookean
        """
        __members__: typing.ClassVar[dict[str, BladderLaw.Form]]
        neo_hookean: typing.ClassVar[BladderLaw.Form]
        polynomial: typing.ClassVar[BladderLaw.Form]
        @typing.overload
        def __eq__(self, other: BladderLaw.Form) -> bool:
            ...
        @typing.overload
        def __eq__(self, other: typing.Any) -> bool:
            ...
        def __getstate__(self) -> int:
            ...
        def __hash__(self) -> int:
            ...
        def __index__(self) -> int:
            ...
        def __init__(self, value: typing.SupportsInt | typing.SupportsIndex) -> None:
            ...
        def __int__(self) -> int:
            ...
        @typing.overload
        def __ne__(self, other: BladderLaw.Form) -> bool:
            ...
        @typing.overload
        def __ne__(self, other: typing.Any) -> bool:
            ...
        def __repr__(self) -> str:
            ...
        def __setstate__(self, state: typing.SupportsInt | typing.SupportsIndex) -> None:
            ...
        def __str__(self) -> str:
            ...
        @property
        def name(self) -> str:
            ...
        @property
        def value(self) -> int:
            ...
    @staticmethod
    def neo_hookean(shear_modulus_Pa: typing.SupportsFloat | typing.SupportsIndex) -> BladderLaw:
        """
        An incompressible neo-Hookean membrane of shear modulus mu [Pa].
        """
    @staticmethod
    def none() -> BladderLaw:
        """
        No bladder stress.
        """
    @staticmethod
    def thesis() -> BladderLaw:
        """
        Eqs. 3.1.12-3.1.13 (with the lost '+' of the eps^4 term restored).
        """
    def __init__(self) -> None:
        ...
    def stresses(self, longitudinal_strain: typing.SupportsFloat | typing.SupportsIndex, hoop_strain: typing.SupportsFloat | typing.SupportsIndex) -> BiaxialStress:
        """
        Engineering stresses [Pa] at the two strains.
        """
    def tangent_moduli(self, longitudinal_strain: typing.SupportsFloat | typing.SupportsIndex, hoop_strain: typing.SupportsFloat | typing.SupportsIndex) -> BiaxialStress:
        """
        d sigma / d eps [Pa] of each direction in its own strain.
        """
    @property
    def form(self) -> BladderLaw.Form:
        """
        polynomial or neo_hookean
        """
    @form.setter
    def form(self, arg0: BladderLaw.Form) -> None:
        ...
    @property
    def hoop_Pa(self) -> typing.Annotated[list[float], "FixedSize(7)"]:
        """
        coefficients c0..c6 of sigma_h(eps_h) [Pa]
        """
    @hoop_Pa.setter
    def hoop_Pa(self, arg0: typing.Annotated[collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex], "FixedSize(7)"]) -> None:
        ...
    @property
    def longitudinal_Pa(self) -> typing.Annotated[list[float], "FixedSize(7)"]:
        """
        coefficients c0..c6 of sigma_l(eps_l) [Pa]
        """
    @longitudinal_Pa.setter
    def longitudinal_Pa(self, arg0: typing.Annotated[collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex], "FixedSize(7)"]) -> None:
        ...
    @property
    def shear_modulus_Pa(self) -> float:
        """
        neo-Hookean shear modulus mu [Pa]
        """
    @shear_modulus_Pa.setter
    def shear_modulus_Pa(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
class FrictionParams:
    """
    Fiber-fiber and fiber-bladder friction (eqs. 3.1.19-3.1.24).
    """
    @staticmethod
    def fields() -> dict:
        """
        Field names mapped to their unit, allowed range and meaning.
        """
    def __init__(self, **kwargs) -> None:
        """
        Keyword construction; fields not given keep their documented defaults.
        """
    def __repr__(self) -> str:
        ...
    def to_dict(self) -> dict:
        ...
    def validate(self) -> None:
        """
        Raises ValueError naming the first field out of range.
        """
    @property
    def contact_length_m(self) -> float:
        """
        fiber length z in one crossing [m], allowed [0.000000, 0.010000]
        """
    @contact_length_m.setter
    def contact_length_m(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def fiber_bladder_coefficient(self) -> float:
        """
        fiber-bladder friction coefficient [1], allowed [0.000000, 5.000000]
        """
    @fiber_bladder_coefficient.setter
    def fiber_bladder_coefficient(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def fiber_fiber_coefficient(self) -> float:
        """
        fiber-fiber friction coefficient [1], allowed [0.000000, 5.000000]
        """
    @fiber_fiber_coefficient.setter
    def fiber_fiber_coefficient(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def fiber_width_m(self) -> float:
        """
        fiber width w [m], allowed [0.000000, 0.010000]
        """
    @fiber_width_m.setter
    def fiber_width_m(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def sharpness_s_per_m(self) -> float:
        """
        Kf of tanh(Kf v) [s/m], allowed [0.000000, 10000000.000000]
        """
    @sharpness_s_per_m.setter
    def sharpness_s_per_m(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
class MuscleShape:
    """
    Shape of the muscle at one length (SI units, angles in rad).
    """
    @property
    def bladder_volume(self) -> float:
        ...
    @property
    def braid_angle(self) -> float:
        ...
    @property
    def cone_angle(self) -> float:
        ...
    @property
    def cone_length(self) -> float:
        ...
    @property
    def cylinder_length(self) -> float:
        ...
    @property
    def d_bladder_volume(self) -> float:
        ...
    @property
    def d_cylinder_length(self) -> float:
        ...
    @property
    def d_diameter(self) -> float:
        ...
    @property
    def d_gas_volume(self) -> float:
        ...
    @property
    def d_total_volume(self) -> float:
        ...
    @property
    def diameter(self) -> float:
        ...
    @property
    def end_braid_angle(self) -> float:
        ...
    @property
    def gas_volume(self) -> float:
        ...
    @property
    def length(self) -> float:
        ...
    @property
    def mean_braid_angle(self) -> float:
        ...
    @property
    def total_volume(self) -> float:
        ...
class BraidGeometry:
    """
    Braid kinematics and volumes of one build (eqs. 3.1.1-3.1.3, 3.1.9-3.1.11).
    """
    def __init__(self, build: MuscleBuild) -> None:
        ...
    def shape(self, length_m: typing.SupportsFloat | typing.SupportsIndex) -> MuscleShape:
        """
        Shape at muscle length [m].
        """
    @property
    def build(self) -> MuscleBuild:
        ...
    @property
    def deflated_cylinder_length(self) -> float:
        """
        cylinder length of the deflated build [m]
        """
    @property
    def fiber_length(self) -> float:
        """
        fiber length over the cylinder Lym [m]
        """
    @property
    def max_length(self) -> float:
        """
        longest allowed length [m]
        """
    @property
    def min_length(self) -> float:
        """
        shortest allowed length [m]
        """
class MuscleForces:
    """
    Axial force and its parts [N], tension > 0.
    """
    @property
    def bladder(self) -> float:
        ...
    @property
    def friction(self) -> float:
        ...
    @property
    def pressure(self) -> float:
        ...
    @property
    def total(self) -> float:
        ...
class FiberTensions:
    """
    Fiber tensions of the Newtonian model [N per fiber] and its force [N].
    """
    @property
    def cone_hoop(self) -> float:
        ...
    @property
    def cylinder_hoop(self) -> float:
        ...
    @property
    def force(self) -> float:
        ...
    @property
    def longitudinal(self) -> float:
        ...
class FreeInflation:
    """
    Free (zero-force) length and diameter after inflation.
    """
    def __repr__(self) -> str:
        ...
    @property
    def contracted(self) -> bool:
        ...
    @property
    def diameter_m(self) -> float:
        ...
    @property
    def length_m(self) -> float:
        ...
class GasProcess:
    """
    How the gas exchanges heat with the wall.
    
    Members:
    
      polytropic : p V^n = const (eq. 3.1.14)
    
      heat_transfer : energy balance with gas-wall exchange, time constant tau
    """
    __members__: typing.ClassVar[dict[str, GasProcess]]
    heat_transfer: typing.ClassVar[GasProcess]
    polytropic: typing.ClassVar[GasProcess]
    @typing.overload
    def __eq__(self, other: GasProcess) -> bool:
        ...
    @typing.overload
    def __eq__(self, other: typing.Any) -> bool:
        ...
    def __getstate__(self) -> int:
        ...
    def __hash__(self) -> int:
        ...
    def __index__(self) -> int:
        ...
    def __init__(self, value: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    def __int__(self) -> int:
        ...
    @typing.overload
    def __ne__(self, other: GasProcess) -> bool:
        ...
    @typing.overload
    def __ne__(self, other: typing.Any) -> bool:
        ...
    def __repr__(self) -> str:
        ...
    def __setstate__(self, state: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    def __str__(self) -> str:
        ...
    @property
    def name(self) -> str:
        ...
    @property
    def value(self) -> int:
        ...
class GasParams:
    """
    Air, ambient conditions and the gas process (SI units).
    """
    @staticmethod
    def fields() -> dict:
        """
        Field names mapped to their unit, allowed range and meaning.
        """
    def __init__(self, **kwargs) -> None:
        """
        Keyword construction; fields not given keep their documented defaults.
        """
    def __repr__(self) -> str:
        ...
    def to_dict(self) -> dict:
        ...
    def validate(self) -> None:
        """
        Raises ValueError naming the first field out of range.
        """
    @property
    def ambient_temperature_K(self) -> float:
        """
        ambient and initial gas temperature [K], allowed [150.000000, 500.000000]
        """
    @ambient_temperature_K.setter
    def ambient_temperature_K(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def atmospheric_pressure_Pa(self) -> float:
        """
        absolute ambient pressure [Pa], allowed [1000.000000, 1000000.000000]
        """
    @atmospheric_pressure_Pa.setter
    def atmospheric_pressure_Pa(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def gas_constant_J_per_kgK(self) -> float:
        """
        specific gas constant R [J/(kg K)], allowed [1.000000, 100000.000000]
        """
    @gas_constant_J_per_kgK.setter
    def gas_constant_J_per_kgK(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def heat_capacity_ratio(self) -> float:
        """
        cp / cv [1], allowed [1.000100, 1.700000]
        """
    @heat_capacity_ratio.setter
    def heat_capacity_ratio(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def heat_transfer_time_constant_s(self) -> float:
        """
        gas-wall heat exchange time constant (0: isothermal) [s], allowed [0.000000, 1000000000.000000]
        """
    @heat_transfer_time_constant_s.setter
    def heat_transfer_time_constant_s(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def polytropic_index(self) -> float:
        """
        polytropic exponent n [1], allowed [1.000000, 1.700000]
        """
    @polytropic_index.setter
    def polytropic_index(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def process(self) -> GasProcess:
        """
        GasProcess: polytropic or heat_transfer
        """
    @process.setter
    def process(self, arg0: GasProcess) -> None:
        ...
    @property
    def specific_heat_cv(self) -> float:
        """
        cv = R / (gamma - 1) [J/(kg K)]
        """
class ModelExtensions:
    """
    Physics beyond the thesis's model, all off (zero) by default; effects switch them on.
    """
    @staticmethod
    def fields() -> dict:
        """
        Field names mapped to their unit, allowed range and meaning.
        """
    def __init__(self, **kwargs) -> None:
        """
        Keyword construction; fields not given keep their documented defaults.
        """
    def __repr__(self) -> str:
        ...
    def to_dict(self) -> dict:
        ...
    def validate(self) -> None:
        """
        Raises ValueError naming the first field out of range.
        """
    @property
    def dead_volume_fraction(self) -> float:
        """
        dead gas volume / initial gas volume [1], allowed [0.000000, 10.000000]
        """
    @dead_volume_fraction.setter
    def dead_volume_fraction(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def fiber_compliance_per_N(self) -> float:
        """
        1 / fiber axial stiffness [1/N], allowed [0.000000, 1.000000]
        """
    @fiber_compliance_per_N.setter
    def fiber_compliance_per_N(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def leak_rate_per_s(self) -> float:
        """
        leak rate (1 / time constant) [1/s], allowed [0.000000, 1000.000000]
        """
    @leak_rate_per_s.setter
    def leak_rate_per_s(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def pressure_hysteresis(self) -> float:
        """
        pressurise/vent friction over the pressure force p pi D^2/4 [1], allowed [0.000000, 10.000000]
        """
    @pressure_hysteresis.setter
    def pressure_hysteresis(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def slack_band_N(self) -> float:
        """
        width of the slack braid's smooth transition (0: the braid pushes) [N], allowed [0.000000, 10000.000000]
        """
    @slack_band_N.setter
    def slack_band_N(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def slip_distance_m(self) -> float:
        """
        Maxwell-slip friction: break-away displacements spread over (0, this] [m], allowed [0.000001, 1.000000]
        """
    @slip_distance_m.setter
    def slip_distance_m(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def slip_force_N(self) -> float:
        """
        Maxwell-slip friction with memory: slip force of its elements together [N], allowed [0.000000, 100000.000000]
        """
    @slip_force_N.setter
    def slip_force_N(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def viscoelastic_strength(self) -> float:
        """
        bladder Maxwell-branch modulus ratio [1], allowed [0.000000, 100.000000]
        """
    @viscoelastic_strength.setter
    def viscoelastic_strength(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def viscoelastic_time_constant_s(self) -> float:
        """
        bladder relaxation time [s], allowed [0.000100, 1000000.000000]
        """
    @viscoelastic_time_constant_s.setter
    def viscoelastic_time_constant_s(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
class MuscleParams:
    """
    Everything that defines a muscle: build, bladder law, friction, gas.
    """
    bladder: BladderLaw
    build: MuscleBuild
    extensions: ModelExtensions
    friction: FrictionParams
    gas: GasParams
    @typing.overload
    def __init__(self) -> None:
        ...
    @typing.overload
    def __init__(self, build: MuscleBuild = ..., bladder: BladderLaw = ..., friction: FrictionParams = ..., gas: GasParams = ...) -> None:
        ...
    @typing.overload
    def __init__(self, build: MuscleBuild, bladder: BladderLaw, friction: FrictionParams, gas: GasParams, extensions: ModelExtensions) -> None:
        ...
    def validate(self) -> None:
        ...
class InitialState:
    """
    The test at zero elongation: inflated, sealed, at rest.
    """
    @staticmethod
    def fields() -> dict:
        """
        Field names mapped to their unit, allowed range and meaning.
        """
    def __init__(self, **kwargs) -> None:
        """
        Keyword construction; fields not given keep their documented defaults.
        """
    def __repr__(self) -> str:
        ...
    def to_dict(self) -> dict:
        ...
    def validate(self) -> None:
        """
        Raises ValueError naming the first field out of range.
        """
    @property
    def gauge_pressure_Pa(self) -> float:
        """
        gauge pressure at zero elongation [Pa], allowed [0.000000, 2000000.000000]
        """
    @gauge_pressure_Pa.setter
    def gauge_pressure_Pa(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def length_m(self) -> float:
        """
        muscle length at zero elongation [m], allowed [0.001000, 5.000000]
        """
    @length_m.setter
    def length_m(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
class State:
    """
    ODE state: gas temperature and mass, bladder viscous stresses, energy integrals (SI).
    """
    friction_dissipated_J: typing.ClassVar[int] = 6
    gas_mass_kg: typing.ClassVar[int] = 1
    heat_lost_J: typing.ClassVar[int] = 5
    temperature_K: typing.ClassVar[int] = 0
    viscous_stress_h_Pa: typing.ClassVar[int] = 3
    viscous_stress_l_Pa: typing.ClassVar[int] = 2
    work_J: typing.ClassVar[int] = 4
    def __getitem__(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> float:
        ...
    @typing.overload
    def __init__(self) -> None:
        ...
    @typing.overload
    def __init__(self, values: typing.Annotated[collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex], "FixedSize(7)"]) -> None:
        ...
    @property
    def values(self) -> typing.Annotated[list[float], "FixedSize(7)"]:
        """
        the state as a list, in the order of the index constants
        """
    @values.setter
    def values(self, arg0: typing.Annotated[collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex], "FixedSize(7)"]) -> None:
        ...
class MuscleOutputs:
    """
    What the model says at one instant (SI units).
    """
    @property
    def absolute_pressure_Pa(self) -> float:
        ...
    @property
    def fiber_length_m(self) -> float:
        ...
    @property
    def fiber_length_rate_m_per_s(self) -> float:
        ...
    @property
    def fiber_tension_N(self) -> float:
        ...
    @property
    def forces(self) -> MuscleForces:
        ...
    @property
    def gas_volume_m3(self) -> float:
        ...
    @property
    def gauge_pressure_Pa(self) -> float:
        ...
    @property
    def heat_loss_rate_W(self) -> float:
        ...
    @property
    def rate(self) -> State:
        """
        d(state)/dt
        """
    @property
    def shape(self) -> MuscleShape:
        ...
class MuscleModel:
    """
    A muscle in a test: parameters and the sealed gas mass. Immutable.
    """
    def __init__(self, params: MuscleParams, initial: InitialState) -> None:
        ...
    def evaluate(self, length_m: typing.SupportsFloat | typing.SupportsIndex, velocity_m_per_s: typing.SupportsFloat | typing.SupportsIndex, state: State) -> MuscleOutputs:
        """
        Outputs and d(state)/dt at a length [m], elongation rate [m/s] and state.
        """
    def initial(self) -> State:
        """
        the state at zero elongation
        """
    @property
    def dead_volume(self) -> float:
        """
        dead gas volume [m^3]
        """
    @property
    def gas_mass(self) -> float:
        """
        sealed air mass [kg]
        """
    @property
    def geometry(self) -> BraidGeometry:
        ...
    @property
    def initial_gas_volume(self) -> float:
        """
        gas volume at zero elongation [m^3]
        """
    @property
    def initial_state(self) -> InitialState:
        ...
    @property
    def initial_temperature(self) -> float:
        """
        gas temperature at the start [K]
        """
    @property
    def params(self) -> MuscleParams:
        ...
class ElongationTrajectory:
    """
    Elongation [m] against time [s], linear between samples.
    """
    def __init__(self, time_s: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], elongation_m: typing.Annotated[numpy.typing.ArrayLike, numpy.float64]) -> None:
        ...
    def __len__(self) -> int:
        ...
    @property
    def elongation_m(self) -> numpy.typing.NDArray[numpy.float64]:
        ...
    @property
    def time_s(self) -> numpy.typing.NDArray[numpy.float64]:
        ...
class IntegrationMethod:
    """
    How a run is integrated: bdf (CVODES, dense Newton), adams (CVODES, fixed-point iteration), dopri5 (explicit Dormand-Prince 5(4) with dense output, Boost.Odeint), rosenbrock4 (Boost.Odeint's Rosenbrock 4(3), linearly implicit, on the states that move and the energies), or auto (dopri5 where estimate_stiffness finds the run non-stiff, else rosenbrock4, or bdf at a relative tolerance below 1e-9).
    
    Members:
    
      auto
    
      bdf
    
      adams
    
      dopri5
    
      rosenbrock4
    """
    __members__: typing.ClassVar[dict[str, IntegrationMethod]]
    adams: typing.ClassVar[IntegrationMethod]
    auto: typing.ClassVar[IntegrationMethod]
    bdf: typing.ClassVar[IntegrationMethod]
    dopri5: typing.ClassVar[IntegrationMethod]
    rosenbrock4: typing.ClassVar[IntegrationMethod]
    @typing.overload
    def __eq__(self, other: IntegrationMethod) -> bool:
        ...
    @typing.overload
    def __eq__(self, other: typing.Any) -> bool:
        ...
    def __getstate__(self) -> int:
        ...
    def __hash__(self) -> int:
        ...
    def __index__(self) -> int:
        ...
    def __init__(self, value: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    def __int__(self) -> int:
        ...
    @typing.overload
    def __ne__(self, other: IntegrationMethod) -> bool:
        ...
    @typing.overload
    def __ne__(self, other: typing.Any) -> bool:
        ...
    def __repr__(self) -> str:
        ...
    def __setstate__(self, state: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    def __str__(self) -> str:
        ...
    @property
    def name(self) -> str:
        ...
    @property
    def value(self) -> int:
        ...
class SimulatorConfig:
    """
    Integrator settings.
    """
    @staticmethod
    def fields() -> dict:
        """
        Field names mapped to their unit, allowed range and meaning.
        """
    def __init__(self, **kwargs) -> None:
        """
        Keyword construction; fields not given keep their documented defaults.
        """
    def __repr__(self) -> str:
        ...
    def to_dict(self) -> dict:
        ...
    def validate(self) -> None:
        """
        Raises ValueError naming the first field out of range.
        """
    @property
    def absolute_tolerance_J(self) -> float:
        """
        absolute tolerance on energies (large: leave them out of the error test) [J], allowed [0.000000, 1000000000000.000000]
        """
    @absolute_tolerance_J.setter
    def absolute_tolerance_J(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def absolute_tolerance_K(self) -> float:
        """
        absolute tolerance on temperature [K], allowed [0.000000, 1.000000]
        """
    @absolute_tolerance_K.setter
    def absolute_tolerance_K(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def corner_threshold(self) -> float:
        """
        rate jump that restarts, share of the largest rate [1], allowed [0.000000, 2.000000]
        """
    @corner_threshold.setter
    def corner_threshold(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def max_step_s(self) -> float:
        """
        largest step (0: no limit) [s], allowed [0.000000, 1000000000.000000]
        """
    @max_step_s.setter
    def max_step_s(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def max_steps(self) -> float:
        """
        most steps between samples [1], allowed [10.000000, 1000000000.000000]
        """
    @max_steps.setter
    def max_steps(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def method(self) -> IntegrationMethod:
        """
        integration method: bdf, adams, dopri5, rosenbrock4 or auto (dopri5 where the run is not stiff, else rosenbrock4, or bdf at a relative tolerance below 1e-9)
        """
    @method.setter
    def method(self, arg0: IntegrationMethod) -> None:
        ...
    @property
    def relative_tolerance(self) -> float:
        """
        relative tolerance [1], allowed [0.000000, 0.010000]
        """
    @relative_tolerance.setter
    def relative_tolerance(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
class StiffnessEstimate:
    """
    The stiffness test of IntegrationMethod.auto: the model's fastest rate times the step the tolerance allows on the trajectory's longest piece; above 1, stiff.
    """
    def __repr__(self) -> str:
        ...
    @property
    def expected_step_s(self) -> float:
        """
        longest_piece_s * rtol^(1/6), at most max_step_s [s]
        """
    @property
    def fastest_rate_per_s(self) -> float:
        """
        the model's fastest relaxation rate [1/s]
        """
    @property
    def longest_piece_s(self) -> float:
        """
        longest stretch between the trajectory's corners [s]
        """
    @property
    def ratio(self) -> float:
        """
        fastest_rate_per_s * expected_step_s [1]
        """
    @property
    def stiff(self) -> bool:
        """
        ratio > 1: auto runs rosenbrock4 (bdf below a relative tolerance of 1e-9)
        """
class SolverStatistics:
    """
    The integrator's counters over one run.
    """
    def __repr__(self) -> str:
        ...
    @property
    def error_test_failures(self) -> int:
        """
        steps rejected by the local error test (dopri5: not counted)
        """
    @property
    def jacobian_evaluations(self) -> int:
        """
        dense Jacobian evaluations (none with adams or dopri5)
        """
    @property
    def linear_solver_setups(self) -> int:
        """
        LU factorisations: Newton's (bdf) or a step's (rosenbrock4)
        """
    @property
    def method(self) -> IntegrationMethod:
        """
        the method that ran: never auto
        """
    @property
    def nonlinear_convergence_failures(self) -> int:
        """
        failures of those iterations to converge
        """
    @property
    def nonlinear_iterations(self) -> int:
        """
        Newton (bdf) or fixed-point (adams) iterations
        """
    @property
    def output_evaluations(self) -> int:
        """
        model evaluations to report the samples
        """
    @property
    def restarts(self) -> int:
        """
        restarts at trajectory corners
        """
    @property
    def rhs_evaluations(self) -> int:
        """
        right-hand-side evaluations, difference-quotient Jacobians' included
        """
    @property
    def sensitivity_rhs_evaluations(self) -> int:
        """
        moved models' right-hand sides for the sensitivities (Simulator.run_sensitivities; 0 otherwise)
        """
    @property
    def steps(self) -> int:
        """
        internal time steps (dopri5, rosenbrock4: accepted ones)
        """
    @property
    def tabulated_shapes(self) -> int:
        """
        output evaluations whose braid shape a ShapeTable gave (0: none, or it did not apply)
        """
class SimulationResult:
    """
    Time series of one run, one entry per trajectory sample.
    """
    @property
    def braid_angle_rad(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        braid angle of the cylinder [rad]
        """
    @property
    def diameter_m(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        braid diameter [m]
        """
    @property
    def elongation_m(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        prescribed elongation [m]
        """
    @property
    def force_N(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        axial force, tension > 0, friction included [N]
        """
    @property
    def friction_dissipated_J(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        friction work since the start [J]
        """
    @property
    def friction_force_N(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        friction part of the force [N]
        """
    @property
    def gas_mass_kg(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        mass of air inside [kg]
        """
    @property
    def gas_volume_m3(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        gas volume, dead volume included [m^3]
        """
    @property
    def gauge_pressure_Pa(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        gas pressure above ambient [Pa]
        """
    @property
    def heat_lost_J(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        heat from gas to wall since the start [J]
        """
    @property
    def length_m(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        muscle length [m]
        """
    @property
    def statistics(self) -> SolverStatistics:
        ...
    @property
    def temperature_K(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        gas temperature [K]
        """
    @property
    def time_s(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        sample times [s]
        """
    @property
    def work_J(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        work done on the muscle since the start [J]
        """
class ShapeTable:
    """
    The braid's shape (kinematics and cylinder braid angle) at every sample length initial_length_m + elongation_m[k] of a trajectory, solved once for one build and shared, immutable, by the runs along it that differ only in pressure, friction, bladder law, gas or effects that leave the build, the motion and the fibres' stiffness alone (Simulator.run, simulate_measurement: shapes=). A run that reads it gives the same numbers bit for bit; a run it does not apply to ignores it.
    """
    @typing.overload
    def __init__(self, build: MuscleBuild, initial_length_m: typing.SupportsFloat | typing.SupportsIndex, trajectory: ElongationTrajectory) -> None:
        """
        Solves the shapes of `build` at initial_length_m [m] plus each elongation [m] of the muscle's trajectory (after any motion effect). Releases the GIL. ValueError naming a sample outside the braid's range.
        """
    @typing.overload
    def __init__(self, params: MuscleParams, initial_length_m: typing.SupportsFloat | typing.SupportsIndex, trajectory: ElongationTrajectory) -> None:
        """
        The table of params.build (the rest of params does not shape the braid).
        """
    def __len__(self) -> int:
        ...
    def applies_to(self, model: MuscleModel, trajectory: ElongationTrajectory) -> bool:
        """
        Whether a run of `model` along `trajectory` reads its shapes here: the same build field for field, the same sample lengths bit for bit, inextensible fibres (fiber_compliance_per_N = 0).
        """
    def shape(self, k: typing.SupportsInt | typing.SupportsIndex) -> MuscleShape:
        """
        the shape at sample k (its end, cone and mean braid angles are NaN: not tabulated)
        """
    @property
    def build(self) -> MuscleBuild:
        ...
    @property
    def initial_length_m(self) -> float:
        """
        muscle length at zero elongation [m]
        """
    @property
    def length_m(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        muscle length at each sample [m]
        """
class SensitivityResult:
    """
    A run and its forward sensitivities (Simulator.run_sensitivities).
    """
    @property
    def derivatives(self) -> list:
        """
        per parameter, a SimulationResult whose output columns are the derivatives of run's (per unit of the parameter); elongation_m is the muscle's motion's (zero unless moved_motions moves it), statistics empty. Views into this result, which they keep alive.
        """
    @property
    def run(self) -> SimulationResult:
        """
        the run at the nominal parameters
        """
class ParameterSets:
    """
    One muscle's parameters and sealed start, varied run by run: each run sets its own values of the named fields on a shared base (Simulator.run_batch).
    """
    def __init__(self, base: MuscleParams, start: InitialState, names: collections.abc.Sequence[str], values: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], inflated_start: bool = False) -> None:
        """
        base: MuscleParams every run starts from; start: the InitialState every run shares but for the fields it sets; names: the fields each run sets, 'build.<MuscleBuild field>', 'build.braid_angle_deg' (the revolutions that give the deflated build this angle [deg], as fiber_revolutions_for_braid_angle takes it), 'bladder.shear_modulus_Pa' (a neo-Hookean bladder), 'friction.<field>', 'gas.<field>', 'extensions.<field>', 'initial.length_m', 'initial.gauge_pressure_Pa'; values: (runs, len(names)), each in its field's unit; inflated_start: a run starts at the free length its pressure inflates the muscle to (inflated_and_sealed) unless it sets initial.length_m. ValueError for an unknown or repeated name.
        """
    def at(self, run: typing.SupportsInt | typing.SupportsIndex) -> tuple[MuscleParams, InitialState]:
        """
        Run `run`'s (MuscleParams, InitialState), as run_batch makes them. ValueError for a value its field or the muscle refuses, IndexError past the last run.
        """
    @property
    def names(self) -> list[str]:
        """
        the fields each run sets, in the values' column order
        """
    @property
    def runs(self) -> int:
        """
        how many runs
        """
class RunFailure:
    """
    Why a run of Simulator.run_batch failed.
    
    Members:
    
      none : it ran
    
      parameters : its parameters were refused before a model was built (a field out of its range, a braid angle the build cannot reach, a pressure it cannot inflate to freely)
    
      input : the model could not follow the trajectory (outside the braid's range)
    
      solver : the integrator failed
    """
    __members__: typing.ClassVar[dict[str, RunFailure]]
    input: typing.ClassVar[RunFailure]
    none: typing.ClassVar[RunFailure]
    parameters: typing.ClassVar[RunFailure]
    solver: typing.ClassVar[RunFailure]
    @typing.overload
    def __eq__(self, other: RunFailure) -> bool:
        ...
    @typing.overload
    def __eq__(self, other: typing.Any) -> bool:
        ...
    def __getstate__(self) -> int:
        ...
    def __hash__(self) -> int:
        ...
    def __index__(self) -> int:
        ...
    def __init__(self, value: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    def __int__(self) -> int:
        ...
    @typing.overload
    def __ne__(self, other: RunFailure) -> bool:
        ...
    @typing.overload
    def __ne__(self, other: typing.Any) -> bool:
        ...
    def __repr__(self) -> str:
        ...
    def __setstate__(self, state: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    def __str__(self) -> str:
        ...
    @property
    def name(self) -> str:
        ...
    @property
    def value(self) -> int:
        ...
class BatchResult:
    """
    The runs of Simulator.run_batch, in the order given; arrays have one row per run.
    """
    @property
    def channels(self) -> list[str]:
        """
        the channels kept, in the order asked
        """
    @property
    def errors(self) -> list[str]:
        """
        per run, why it failed; '' where it ran
        """
    @property
    def failed(self) -> numpy.typing.NDArray[numpy.bool]:
        """
        (runs,) bool: the run failed (its message in errors)
        """
    @property
    def failures(self) -> numpy.typing.NDArray[numpy.uint8]:
        """
        (runs,) RunFailure values: why each run failed (0 none: it ran)
        """
    @property
    def maximum(self) -> dict:
        """
        channel name -> (runs,) array of each run's largest value over every sample (NaN for a failed run)
        """
    @property
    def minimum(self) -> dict:
        """
        channel name -> (runs,) array of each run's smallest value over every sample
        """
    @property
    def rejected(self) -> numpy.typing.NDArray[numpy.bool]:
        """
        (runs,) bool: failures == RunFailure.parameters, its parameters refused before a model was built
        """
    @property
    def rows(self) -> numpy.typing.NDArray[numpy.uint64]:
        """
        the sample indices each channel is kept at
        """
    @property
    def runs(self) -> int:
        """
        how many runs
        """
    @property
    def statistics(self) -> dict:
        """
        counter name (SolverStatistics's) -> (runs,) array of each run's count, and 'method': each run's IntegrationMethod as its integer value (zero counters for a failed run)
        """
    @property
    def values(self) -> dict:
        """
        channel name -> (runs, len(rows)) array of its values at the rows (NaN for a failed run); views into this result
        """
class Simulator:
    """
    Integrates a MuscleModel along a trajectory with CVODES. Re-entrant.
    """
    def __init__(self, config: SimulatorConfig = ...) -> None:
        ...
    def run(self, model: MuscleModel, trajectory: ElongationTrajectory, shapes: ShapeTable = None) -> SimulationResult:
        """
        Simulates the model along the trajectory; releases the GIL while it runs. shapes: a ShapeTable whose braid shapes the samples read where it applies to this run (statistics.tabulated_shapes counts them), with the same result bit for bit; None or a table that does not apply: the shapes are solved.
        """
    @typing.overload
    def run_batch(self, models: collections.abc.Sequence[MuscleModel], trajectory: ElongationTrajectory, channels: collections.abc.Sequence[str] = ['force_N', 'gauge_pressure_Pa', 'temperature_K'], rows: collections.abc.Sequence[typing.SupportsInt | typing.SupportsIndex] | None = None, threads: typing.SupportsInt | typing.SupportsIndex = 0, shapes: ShapeTable = None, motions: collections.abc.Sequence[ElongationTrajectory] = []) -> BatchResult:
        """
        Runs every model along the trajectory on `threads` C++ threads (0: one per hardware thread), the GIL released, and keeps of each run the channels (SimulationResult's output columns, by name) at the sample indices `rows` (increasing; None: none) and their largest and smallest values over every sample: a BatchResult, each run's numbers Simulator.run's bit for bit whatever the threads. A run that fails keeps its message and NaN; the others run. shapes: a ShapeTable for every run it applies to; motions: run i follows motions[i] (on the trajectory's times). ValueError for an unknown channel, rows that do not increase or pass the end, or motions that are neither empty nor one per model.
        """
    @typing.overload
    def run_batch(self, sets: ParameterSets, trajectory: ElongationTrajectory, channels: collections.abc.Sequence[str] = ['force_N', 'gauge_pressure_Pa', 'temperature_K'], rows: collections.abc.Sequence[typing.SupportsInt | typing.SupportsIndex] | None = None, threads: typing.SupportsInt | typing.SupportsIndex = 0) -> BatchResult:
        """
        run_batch over the runs of a ParameterSets, each run's muscle made on the C++ thread that runs it (ParameterSets.at): a design sweep with no Python per run. A run whose parameters are refused is marked in BatchResult.failures as RunFailure.parameters.
        """
    def run_sensitivities(self, model: MuscleModel, moved: collections.abc.Sequence[MuscleModel], steps: collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex], trajectory: ElongationTrajectory, shapes: ShapeTable = None, moved_motions: collections.abc.Sequence[ElongationTrajectory] = [], rows: collections.abc.Sequence[typing.SupportsInt | typing.SupportsIndex] = []) -> SensitivityResult:
        """
        run, with the forward sensitivities of every output column to parameters integrated by CVODES beside the state (BDF, staggered corrector, on the state's own steps: outside the error test, so the run is the plain run's to rounding). Parameter i is given as moved[i], the model with it moved by steps[i] (signed; its own initial state follows); each sensitivity's right-hand side and output derivative is the directional difference quotient (f_i(y + h_i s_i) - f(y)) / h_i. Parameters should be of order one (the sensitivities share the state's absolute tolerances); steps near 1e-6 give derivatives to ~1e-6 relative. moved_motions: where a parameter moves the muscle's motion (a fixture's slack), moved model i's elongation on the trajectory's times (its derivative's elongation_m is the motion's); empty: every moved model follows the trajectory. rows: the samples (increasing indices) whose derivatives are read, NaN at the others, which cost nothing (empty: every sample). Returns a SensitivityResult; releases the GIL. ValueError for mismatched sizes, a zero step, a moved motion on other times, a moved model whose motion leaves its braid's range, or rows that do not increase or pass the end.
        """
    @property
    def config(self) -> SimulatorConfig:
        ...
class GasMode:
    """
    How the muscle's gas is held during a test.
    
    Members:
    
      sealed
    
      supplied
    """
    __members__: typing.ClassVar[dict[str, GasMode]]
    sealed: typing.ClassVar[GasMode]
    supplied: typing.ClassVar[GasMode]
    @typing.overload
    def __eq__(self, other: GasMode) -> bool:
        ...
    @typing.overload
    def __eq__(self, other: typing.Any) -> bool:
        ...
    def __getstate__(self) -> int:
        ...
    def __hash__(self) -> int:
        ...
    def __index__(self) -> int:
        ...
    def __init__(self, value: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    def __int__(self) -> int:
        ...
    @typing.overload
    def __ne__(self, other: GasMode) -> bool:
        ...
    @typing.overload
    def __ne__(self, other: typing.Any) -> bool:
        ...
    def __repr__(self) -> str:
        ...
    def __setstate__(self, state: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    def __str__(self) -> str:
        ...
    @property
    def name(self) -> str:
        ...
    @property
    def value(self) -> int:
        ...
class Measurement:
    """
    Channels of a bench test on one time base (numpy arrays, copied in and out).
    """
    def __init__(self) -> None:
        ...
    @property
    def elongation_m(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        the crosshead's elongation [m]
        """
    @elongation_m.setter
    def elongation_m(self, arg1: typing.Annotated[numpy.typing.ArrayLike, numpy.float64]) -> None:
        ...
    @property
    def force_N(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        load cell [N]
        """
    @force_N.setter
    def force_N(self, arg1: typing.Annotated[numpy.typing.ArrayLike, numpy.float64]) -> None:
        ...
    @property
    def gauge_pressure_Pa(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        pressure transducer: above the atmosphere [Pa]
        """
    @gauge_pressure_Pa.setter
    def gauge_pressure_Pa(self, arg1: typing.Annotated[numpy.typing.ArrayLike, numpy.float64]) -> None:
        ...
    @property
    def statistics(self) -> SolverStatistics:
        """
        CVODES counters of the run behind a sealed test; all zero for a supplied test (no ODE)
        """
    @property
    def temperature_K(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        gas temperature sensor [K]
        """
    @temperature_K.setter
    def temperature_K(self, arg1: typing.Annotated[numpy.typing.ArrayLike, numpy.float64]) -> None:
        ...
    @property
    def time_s(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        sample times [s]
        """
    @time_s.setter
    def time_s(self, arg1: typing.Annotated[numpy.typing.ArrayLike, numpy.float64]) -> None:
        ...
class EffectStage:
    """
    Where an effect acts in a simulated measurement.
    
    Members:
    
      physics : the model's parameters and states
    
      motion : the motion between crosshead and muscle
    
      measurement : what the instruments read
    """
    __members__: typing.ClassVar[dict[str, EffectStage]]
    measurement: typing.ClassVar[EffectStage]
    motion: typing.ClassVar[EffectStage]
    physics: typing.ClassVar[EffectStage]
    @typing.overload
    def __eq__(self, other: EffectStage) -> bool:
        ...
    @typing.overload
    def __eq__(self, other: typing.Any) -> bool:
        ...
    def __getstate__(self) -> int:
        ...
    def __hash__(self) -> int:
        ...
    def __index__(self) -> int:
        ...
    def __init__(self, value: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    def __int__(self) -> int:
        ...
    @typing.overload
    def __ne__(self, other: EffectStage) -> bool:
        ...
    @typing.overload
    def __ne__(self, other: typing.Any) -> bool:
        ...
    def __repr__(self) -> str:
        ...
    def __setstate__(self, state: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    def __str__(self) -> str:
        ...
    @property
    def name(self) -> str:
        ...
    @property
    def value(self) -> int:
        ...
class FitScale:
    """
    The scale on which a diagnosis moves a parameter.
    
    Members:
    
      linear
    
      log : time constants and stiffnesses that span decades
    
      reciprocal : 'infinity means off' constants, fitted as a rate
    """
    __members__: typing.ClassVar[dict[str, FitScale]]
    linear: typing.ClassVar[FitScale]
    log: typing.ClassVar[FitScale]
    reciprocal: typing.ClassVar[FitScale]
    @typing.overload
    def __eq__(self, other: FitScale) -> bool:
        ...
    @typing.overload
    def __eq__(self, other: typing.Any) -> bool:
        ...
    def __getstate__(self) -> int:
        ...
    def __hash__(self) -> int:
        ...
    def __index__(self) -> int:
        ...
    def __init__(self, value: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    def __int__(self) -> int:
        ...
    @typing.overload
    def __ne__(self, other: FitScale) -> bool:
        ...
    @typing.overload
    def __ne__(self, other: typing.Any) -> bool:
        ...
    def __repr__(self) -> str:
        ...
    def __setstate__(self, state: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    def __str__(self) -> str:
        ...
    @property
    def name(self) -> str:
        ...
    @property
    def value(self) -> int:
        ...
class Resolution:
    """
    What a record must resolve for a fitted value to mean something.
    
    Members:
    
      any
    
      sample_interval : |value| [s] at least the sample interval
    
      travel_per_sample : value [m] at least the travel between samples
    """
    __members__: typing.ClassVar[dict[str, Resolution]]
    any: typing.ClassVar[Resolution]
    sample_interval: typing.ClassVar[Resolution]
    travel_per_sample: typing.ClassVar[Resolution]
    @typing.overload
    def __eq__(self, other: Resolution) -> bool:
        ...
    @typing.overload
    def __eq__(self, other: typing.Any) -> bool:
        ...
    def __getstate__(self) -> int:
        ...
    def __hash__(self) -> int:
        ...
    def __index__(self) -> int:
        ...
    def __init__(self, value: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    def __int__(self) -> int:
        ...
    @typing.overload
    def __ne__(self, other: Resolution) -> bool:
        ...
    @typing.overload
    def __ne__(self, other: typing.Any) -> bool:
        ...
    def __repr__(self) -> str:
        ...
    def __setstate__(self, state: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    def __str__(self) -> str:
        ...
    @property
    def name(self) -> str:
        ...
    @property
    def value(self) -> int:
        ...
class EffectParameter:
    """
    One parameter of an effect.
    
    A Python effect declares at least name, value, unit, the allowed range (min, max) and the
    realistic range synthetic benches draw from. It may also declare the physically plausible range
    with its source (a fitted value outside it is reported, never named as a cause) and the
    diagnosis's search (fit_scale, fit_min, fit_max, fit_start); left out, plausible is the allowed
    range and the search is linear over the realistic range widened by its width on each side.
    """
    def __init__(self, name: str, value: typing.SupportsFloat | typing.SupportsIndex, unit: str, min: typing.SupportsFloat | typing.SupportsIndex, max: typing.SupportsFloat | typing.SupportsIndex, realistic_min: typing.SupportsFloat | typing.SupportsIndex, realistic_max: typing.SupportsFloat | typing.SupportsIndex, description: str = '', *, either_sign: bool = False, plausible_min: typing.SupportsFloat | typing.SupportsIndex | None = None, plausible_max: typing.SupportsFloat | typing.SupportsIndex | None = None, plausible_source: str = '', fit_scale: FitScale | None = None, fit_min: typing.SupportsFloat | typing.SupportsIndex | None = None, fit_max: typing.SupportsFloat | typing.SupportsIndex | None = None, fit_start: typing.SupportsFloat | typing.SupportsIndex | None = None, resolution: Resolution = Resolution.any) -> None:
        ...
    def __repr__(self) -> str:
        ...
    @property
    def description(self) -> str:
        ...
    @property
    def either_sign(self) -> bool:
        """
        the realistic range bounds |value|
        """
    @property
    def fit_max(self) -> float:
        """
        the search's upper end
        """
    @property
    def fit_min(self) -> float:
        """
        the search's lower end (a fit ending here is at a bound)
        """
    @property
    def fit_scale(self) -> FitScale:
        """
        the diagnosis's search scale
        """
    @property
    def fit_start(self) -> float:
        """
        where the search starts
        """
    @property
    def max(self) -> float:
        """
        largest allowed value
        """
    @property
    def min(self) -> float:
        """
        smallest allowed value
        """
    @property
    def name(self) -> str:
        ...
    @property
    def neutral(self) -> float:
        """
        the value at which the parameter adds nothing (a zero offset, a unit gain); NaN where none does
        """
    @property
    def plausible_max(self) -> float:
        """
        largest physically plausible value
        """
    @property
    def plausible_min(self) -> float:
        """
        smallest physically plausible value
        """
    @property
    def plausible_source(self) -> str:
        """
        why that range
        """
    @property
    def realistic_max(self) -> float:
        """
        largest value synthetic benches draw
        """
    @property
    def realistic_min(self) -> float:
        """
        smallest value synthetic benches draw
        """
    @property
    def resolution(self) -> Resolution:
        """
        what one sample must resolve
        """
    @property
    def unit(self) -> str:
        ...
    @property
    def value(self) -> float:
        ...
class Effect:
    """
    A model extension with physical parameters.
    
    Subclass it in Python to add an effect: define name(), description(), parameters() (a list of
    EffectParameter), set(key, value), and any of apply_to_params(params) -> params,
    apply_to_elongation(time_s, crosshead_m) -> elongation_m, apply_to_measurement(measurement) -> measurement,
    why_not(mode) -> None or a reason it cannot act in "sealed"/"supplied" tests.
    """
    def __init__(self) -> None:
        ...
    def __repr__(self) -> str:
        ...
    def acts_in(self, mode: GasMode) -> tuple[bool, typing.Any]:
        """
        (True, None) or (False, reason)
        """
    def apply_to_elongation(self, time_s: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], crosshead_m: typing.Annotated[numpy.typing.ArrayLike, numpy.float64]) -> numpy.typing.NDArray[numpy.float64]:
        """
        the muscle's elongation [m] along the crosshead's, at time_s [s]
        """
    def apply_to_measurement(self, arg0: Measurement) -> Measurement:
        ...
    def apply_to_params(self, arg0: MuscleParams) -> MuscleParams:
        ...
    def apply_to_supplied_pressure(self, time_s: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], gauge_pressure_Pa: typing.Annotated[numpy.typing.ArrayLike, numpy.float64]) -> numpy.typing.NDArray[numpy.float64]:
        """
        the gauge pressure [Pa] that drives a supplied test, from the reading (time_s empty: settled rows)
        """
    def channels_changed(self) -> list[str]:
        """
        the measured channels it changes ([]: all)
        """
    def description(self) -> str:
        ...
    def name(self) -> str:
        ...
    def options(self) -> dict[str, str]:
        ...
    def parameters(self) -> list[EffectParameter]:
        ...
    def reads_samples_alone(self) -> bool:
        """
        whether what the instruments read at a sample depends on that sample alone (an offset, a gain), not on its neighbours (a lag, a skew)
        """
    def reads_supplied_pressure(self) -> bool:
        """
        whether it is an error of the transducer whose reading drives a supplied test
        """
    @typing.overload
    def set(self, key: str, value: typing.SupportsFloat | typing.SupportsIndex) -> None:
        """
        sets a numeric parameter
        """
    @typing.overload
    def set(self, key: str, value: str) -> None:
        """
        sets a parameter or option from text
        """
    def shows_between_branches(self) -> bool:
        """
        whether it shows only between the pressurising and venting branches of a supplied pressure
        """
    def signature(self) -> str:
        """
        a short phrase for a verdict (may name {channel})
        """
    def stage(self) -> EffectStage:
        """
        where the effect acts: physics, motion or measurement
        """
class EffectCatalog:
    """
    Effect names mapped to factories.
    """
    @staticmethod
    def builtin() -> EffectCatalog:
        """
        the nine effects of the catalog
        """
    @staticmethod
    def split(spec: str) -> tuple[str, list[tuple[str, str]]]:
        """
        the name and the (key, value) settings of a spec, as parse reads them, without making the effect
        """
    def __init__(self) -> None:
        ...
    def add(self, name: str, factory: collections.abc.Callable) -> None:
        """
        adds a factory (e.g. a pamkit.Effect subclass) called with no arguments for each new effect
        """
    def make(self, name: str) -> Effect:
        ...
    def names(self) -> list[str]:
        ...
    def parse(self, spec: str) -> Effect:
        """
        'NAME' or 'NAME:key=value,...'
        """
class IsotonicLengths:
    """
    Where an isotonic test's muscle settles at each row.
    """
    @property
    def at_limit(self) -> list[bool]:
        """
        whether each row's equilibrium lay beyond the range searched
        """
    @property
    def length_m(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        length at each row [m]
        """
class IsotonicMotionConfig:
    """
    CVODES settings of isotonic_motion.
    """
    @staticmethod
    def fields() -> dict:
        """
        Field names mapped to their unit, allowed range and meaning.
        """
    def __init__(self, **kwargs) -> None:
        """
        Keyword construction; fields not given keep their documented defaults.
        """
    def __repr__(self) -> str:
        ...
    def to_dict(self) -> dict:
        ...
    def validate(self) -> None:
        """
        Raises ValueError naming the first field out of range.
        """
    @property
    def absolute_tolerance_m(self) -> float:
        """
        absolute tolerance on the length [m], allowed [0.000000, 0.010000]
        """
    @absolute_tolerance_m.setter
    def absolute_tolerance_m(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def absolute_tolerance_m_per_s(self) -> float:
        """
        absolute tolerance on the velocity [m/s], allowed [0.000000, 1.000000]
        """
    @absolute_tolerance_m_per_s.setter
    def absolute_tolerance_m_per_s(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def max_step_s(self) -> float:
        """
        largest step (0: no limit) [s], allowed [0.000000, 1000000000.000000]
        """
    @max_step_s.setter
    def max_step_s(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def max_steps(self) -> float:
        """
        most steps between samples [1], allowed [10.000000, 1000000000.000000]
        """
    @max_steps.setter
    def max_steps(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def relative_tolerance(self) -> float:
        """
        relative tolerance [1], allowed [0.000000, 0.010000]
        """
    @relative_tolerance.setter
    def relative_tolerance(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
class IsotonicMotion:
    """
    A mass on the muscle over time, one entry per pressure sample.
    """
    @property
    def force_N(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        the muscle's tension, friction included [N]
        """
    @property
    def gauge_pressure_Pa(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        gauge pressure that drove the model, effects applied [Pa]
        """
    @property
    def length_m(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        muscle length [m]
        """
    @property
    def statistics(self) -> SolverStatistics:
        ...
    @property
    def time_s(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        sample times [s]
        """
    @property
    def velocity_m_per_s(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        lengthening rate [m/s], > 0 while the load wins
        """
class GaitData:
    """
    Winter's gait data as printed in appendix G.3: one row per frame.
    """
    def __init__(self, frame: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], hip_deg: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], leg_deg: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], foot_deg: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], ankle_moment_Nm: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], subject_mass_kg: typing.SupportsFloat | typing.SupportsIndex = 56.7) -> None:
        """
        Columns of equal length (angles [deg], moment [N m] with Winter's sign: plantarflexor < 0).
        """
    def __len__(self) -> int:
        ...
    def ankle_angle_deg(self, row: typing.SupportsInt | typing.SupportsIndex) -> float:
        """
        shank strut to foot arm at a row (G.3 testangle) [deg]
        """
    @property
    def ankle_moment_Nm(self) -> numpy.typing.NDArray[numpy.float64]:
        ...
    @property
    def foot_deg(self) -> numpy.typing.NDArray[numpy.float64]:
        ...
    @property
    def frame(self) -> numpy.typing.NDArray[numpy.float64]:
        ...
    @property
    def hip_deg(self) -> numpy.typing.NDArray[numpy.float64]:
        ...
    @property
    def leg_deg(self) -> numpy.typing.NDArray[numpy.float64]:
        ...
    @property
    def subject_mass_kg(self) -> float:
        ...
class GaitEvents:
    """
    Gait events found in the data (frame numbers as printed).
    """
    @property
    def heel_strike_frame(self) -> float:
        ...
    @property
    def stance_percent(self) -> float:
        """
        stance over stride [%]
        """
    @property
    def stride_frames(self) -> float:
        ...
    @property
    def toe_off_frame(self) -> float:
        ...
class GaitCycle:
    """
    One stride at evenly spaced percent of the gait cycle, 0 % at heel strike.
    """
    def __len__(self) -> int:
        ...
    @property
    def ankle_angle_deg(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        shank strut to foot arm (G.3 testangle) [deg]
        """
    @property
    def body_mass_kg(self) -> float:
        ...
    @property
    def foot_deg(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        foot segment angle [deg]
        """
    @property
    def hip_deg(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        thigh segment angle [deg]
        """
    @property
    def leg_deg(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        shank segment angle [deg]
        """
    @property
    def moment_Nm(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        biological ankle moment, plantarflexor > 0, scaled to body_mass_kg [N m]
        """
    @property
    def percent(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        percent of the gait cycle [%]
        """
    @property
    def toe_off_percent(self) -> float:
        ...
class LinkageParams:
    """
    Dimensions of the device (appendix G.3's as defaults).
    """
    @staticmethod
    def fields() -> dict:
        """
        Field names mapped to their unit, allowed range and meaning.
        """
    def __init__(self, **kwargs) -> None:
        """
        Keyword construction; fields not given keep their documented defaults.
        """
    def __repr__(self) -> str:
        ...
    def to_dict(self) -> dict:
        ...
    def validate(self) -> None:
        """
        Raises ValueError naming the first field out of range.
        """
    @property
    def block_angle_deg(self) -> float:
        """
        heel bar to shank strut on the stopper block (G.3 blockangle) [deg], allowed [1.000000, 179.000000]
        """
    @block_angle_deg.setter
    def block_angle_deg(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def heel_offset_m(self) -> float:
        """
        ankle to heel anchor (G.3 heeloffset) [m], allowed [0.010000, 0.500000]
        """
    @heel_offset_m.setter
    def heel_offset_m(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def shank_offset_m(self) -> float:
        """
        upright to shank anchor, posterior (G.3 shankoffset) [m], allowed [0.000000, 0.500000]
        """
    @shank_offset_m.setter
    def shank_offset_m(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def upright_length_m(self) -> float:
        """
        ankle to the upright's end along the shank (G.3 uprightlength) [m], allowed [0.020000, 1.000000]
        """
    @upright_length_m.setter
    def upright_length_m(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
class LinkagePose:
    """
    The linkage at one heel-bar angle (shank frame: x up the shank, y to the heel).
    """
    @property
    def heel_anchor_x_m(self) -> float:
        ...
    @property
    def heel_anchor_y_m(self) -> float:
        ...
    @property
    def heel_bar_angle_deg(self) -> float:
        ...
    @property
    def moment_arm_m(self) -> float:
        ...
    @property
    def shank_anchor_x_m(self) -> float:
        ...
    @property
    def shank_anchor_y_m(self) -> float:
        ...
    @property
    def spring_length_m(self) -> float:
        ...
class Linkage:
    """
    The device's geometry. Immutable.
    """
    def __init__(self, params: LinkageParams = ...) -> None:
        ...
    def elongation(self, heel_bar_angle_deg: typing.SupportsFloat | typing.SupportsIndex) -> float:
        """
        beyond the block length [m]
        """
    def horizontal_lever_m(self, heel_bar_angle_deg: typing.SupportsFloat | typing.SupportsIndex, leg_deg: typing.SupportsFloat | typing.SupportsIndex) -> float:
        """
        G.3's momentarm(1,:): horizontal distance ankle to heel anchor [m]
        """
    def pose(self, heel_bar_angle_deg: typing.SupportsFloat | typing.SupportsIndex) -> LinkagePose:
        ...
    @property
    def min_spring_length(self) -> float:
        """
        spring length at the block [m]
        """
    @property
    def params(self) -> LinkageParams:
        ...
class LinearSpring:
    """
    F = k e (G.3's coil spring).
    """
    @staticmethod
    def fields() -> dict:
        """
        Field names mapped to their unit, allowed range and meaning.
        """
    def __call__(self, elongation_m: typing.SupportsFloat | typing.SupportsIndex) -> float:
        ...
    def __init__(self, **kwargs) -> None:
        """
        Keyword construction; fields not given keep their documented defaults.
        """
    def __repr__(self) -> str:
        ...
    def to_dict(self) -> dict:
        ...
    def validate(self) -> None:
        """
        Raises ValueError naming the first field out of range.
        """
    @property
    def stiffness_N_per_m(self) -> float:
        """
        spring rate k (G.3 linearspringstiffness) [N/m], allowed [0.000000, 100000000.000000]
        """
    @stiffness_N_per_m.setter
    def stiffness_N_per_m(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
class ThesisPolynomialSpring:
    """
    G.3's pamequation: 0.1687 (1000e)^2 + 0.127 (1000e) + 16.9 [N].
    """
    def __call__(self, elongation_m: typing.SupportsFloat | typing.SupportsIndex) -> float:
        ...
    def __init__(self) -> None:
        ...
class PamStaticSpring:
    """
    The muscle as a static, sealed, polytropic spring (pamkit's force model).
    """
    def __call__(self, elongation_m: typing.SupportsFloat | typing.SupportsIndex) -> float:
        """
        force [N] at spring elongation [m]
        """
    def __init__(self, build: MuscleBuild, bladder: BladderLaw, gas: GasParams, free_length_m: typing.SupportsFloat | typing.SupportsIndex, gauge_pressure_Pa: typing.SupportsFloat | typing.SupportsIndex, pretension_m: typing.SupportsFloat | typing.SupportsIndex = 0.0, polytropic_index: typing.SupportsFloat | typing.SupportsIndex = 1.0) -> None:
        ...
    def gauge_pressure(self, elongation_m: typing.SupportsFloat | typing.SupportsIndex) -> float:
        """
        [Pa]
        """
    def muscle_length(self, elongation_m: typing.SupportsFloat | typing.SupportsIndex) -> float:
        """
        [m]
        """
class ClutchMode:
    """
    Mode of the ratchet-and-pawl timing mechanism (section 4.4).
    
    Members:
    
      disengaged
    
      engaging
    
      engaged
    
      releasing
    """
    __members__: typing.ClassVar[dict[str, ClutchMode]]
    disengaged: typing.ClassVar[ClutchMode]
    engaged: typing.ClassVar[ClutchMode]
    engaging: typing.ClassVar[ClutchMode]
    releasing: typing.ClassVar[ClutchMode]
    @typing.overload
    def __eq__(self, other: ClutchMode) -> bool:
        ...
    @typing.overload
    def __eq__(self, other: typing.Any) -> bool:
        ...
    def __getstate__(self) -> int:
        ...
    def __hash__(self) -> int:
        ...
    def __index__(self) -> int:
        ...
    def __init__(self, value: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    def __int__(self) -> int:
        ...
    @typing.overload
    def __ne__(self, other: ClutchMode) -> bool:
        ...
    @typing.overload
    def __ne__(self, other: typing.Any) -> bool:
        ...
    def __repr__(self) -> str:
        ...
    def __setstate__(self, state: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    def __str__(self) -> str:
        ...
    @property
    def name(self) -> str:
        ...
    @property
    def value(self) -> int:
        ...
class ClutchParams:
    """
    Screw angles and switching travel of the timing mechanism.
    """
    @staticmethod
    def fields() -> dict:
        """
        Field names mapped to their unit, allowed range and meaning.
        """
    def __init__(self, **kwargs) -> None:
        """
        Keyword construction; fields not given keep their documented defaults.
        """
    def __repr__(self) -> str:
        ...
    def to_dict(self) -> dict:
        ...
    def validate(self) -> None:
        """
        Raises ValueError naming the first field out of range.
        """
    @property
    def engage_angle_deg(self) -> float:
        """
        engage screw: dorsiflexion past it engages (G.3 engageangle) [deg], allowed [30.000000, 180.000000]
        """
    @engage_angle_deg.setter
    def engage_angle_deg(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def release_angle_deg(self) -> float:
        """
        release screw: plantarflexion past it releases (G.3 disengageangle) [deg], allowed [30.000000, 180.000000]
        """
    @release_angle_deg.setter
    def release_angle_deg(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def switching_travel_deg(self) -> float:
        """
        travel to switch state (7 deg, section 4.4) [deg], allowed [0.000000, 45.000000]
        """
    @switching_travel_deg.setter
    def switching_travel_deg(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
class PlayParams:
    """
    Play between leg and device: dead zone and compliance.
    """
    @staticmethod
    def fields() -> dict:
        """
        Field names mapped to their unit, allowed range and meaning.
        """
    def __init__(self, **kwargs) -> None:
        """
        Keyword construction; fields not given keep their documented defaults.
        """
    def __repr__(self) -> str:
        ...
    def to_dict(self) -> dict:
        ...
    def validate(self) -> None:
        """
        Raises ValueError naming the first field out of range.
        """
    @property
    def compliance_deg_per_Nm(self) -> float:
        """
        strap and shoe compliance [deg/(N m)], allowed [0.000000, 10.000000]
        """
    @compliance_deg_per_Nm.setter
    def compliance_deg_per_Nm(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def dead_zone_deg(self) -> float:
        """
        free play between leg and device [deg], allowed [0.000000, 90.000000]
        """
    @dead_zone_deg.setter
    def dead_zone_deg(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
class Clutch:
    """
    The timing mechanism as a hybrid state machine.
    """
    def __init__(self, params: ClutchParams, initial: ClutchMode = ClutchMode.engaged) -> None:
        ...
    def step(self, device_angle_deg: typing.SupportsFloat | typing.SupportsIndex) -> ClutchMode:
        ...
    def stretch_deg(self, device_angle_deg: typing.SupportsFloat | typing.SupportsIndex) -> float:
        ...
    @property
    def mode(self) -> ClutchMode:
        ...
    @property
    def reference_deg(self) -> float:
        ...
class DeviceRun:
    """
    One stride of the device, per gait-cycle sample.
    """
    @property
    def ankle_angle_deg(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        leg's shank-to-foot angle [deg]
        """
    @property
    def biological_torque_Nm(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        biological ankle moment [N m]
        """
    @property
    def device_angle_deg(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        device's shank-to-foot angle after play [deg]
        """
    @property
    def elongation_m(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        beyond the block length [m]
        """
    @property
    def engage_percent(self) -> float | None:
        """
        where the pawl meshed [%], or None
        """
    @property
    def force_N(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        spring force [N]
        """
    @property
    def heel_bar_angle_deg(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        heel bar to shank strut [deg]
        """
    @property
    def horizontal_lever_m(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        G.3 momentarm(1,:) [m]
        """
    @property
    def mode(self) -> numpy.typing.NDArray[numpy.int32]:
        """
        ClutchMode value per sample
        """
    @property
    def moment_arm_m(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        perpendicular moment arm [m]
        """
    @property
    def percent(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        percent of the gait cycle [%]
        """
    @property
    def release_percent(self) -> float | None:
        """
        where the pawl lifted [%], or None
        """
    @property
    def spring_length_m(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        anchor to anchor [m]
        """
    @property
    def torque_Nm(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        plantarflexor torque of the device [N m]
        """
class IdealSpring:
    """
    The force that would give a share of the biological moment (figure 4.7).
    """
    def force_at(self, elongation_m: typing.SupportsFloat | typing.SupportsIndex) -> float | None:
        """
        force on the stretching branch [N], or None if never reached
        """
    @property
    def elongation_at_peak_m(self) -> float:
        ...
    @property
    def elongation_m(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        [m]
        """
    @property
    def force_N(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        [N]
        """
    @property
    def loading_samples(self) -> int:
        ...
    @property
    def max_elongation_m(self) -> float:
        ...
    @property
    def peak_force_N(self) -> float:
        ...
    @property
    def percent(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        stance samples with the spring stretched [%]
        """
class ScriptKinematics:
    """
    Appendix G.3's script as printed, rows 2..83.
    """
    @property
    def elongation_m(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        elongation [m]
        """
    @property
    def horizontal_lever_m(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        momentarm(1,:) [m]
        """
    @property
    def ideal_force_N(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        idealforce [N]
        """
    @property
    def moment_Nm(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        anklemoment, scaled [N m]
        """
    @property
    def moment_arm_m(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        perpendicular moment arm [m]
        """
    @property
    def row(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        1-based data row
        """
    @property
    def spring_length_m(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        springlength [m]
        """
class JigParams:
    """
    Set-up of the exoskeleton in the Instron (appendix G.4).
    """
    @staticmethod
    def fields() -> dict:
        """
        Field names mapped to their unit, allowed range and meaning.
        """
    def __init__(self, **kwargs) -> None:
        """
        Keyword construction; fields not given keep their documented defaults.
        """
    def __repr__(self) -> str:
        ...
    def to_dict(self) -> dict:
        ...
    def validate(self) -> None:
        """
        Raises ValueError naming the first field out of range.
        """
    @property
    def heel_bar_tilt_deg(self) -> float:
        """
        heel bar from vertical (G.4 alpha) [deg], allowed [-45.000000, 45.000000]
        """
    @heel_bar_tilt_deg.setter
    def heel_bar_tilt_deg(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def initial_angle_deg(self) -> float:
        """
        shank strut to heel bar at the start (G.4 thetao) [deg], allowed [1.000000, 179.000000]
        """
    @initial_angle_deg.setter
    def initial_angle_deg(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
class JigSample:
    """
    One converted crosshead sample.
    """
    @property
    def ankle_moment_Nm(self) -> float:
        ...
    @property
    def heel_bar_angle_deg(self) -> float:
        ...
    @property
    def muscle_force_N(self) -> float:
        ...
    @property
    def muscle_length_m(self) -> float:
        ...
    @property
    def rotation_deg(self) -> float:
        ...
class Jig:
    """
    Crosshead displacement and force to muscle length, force and ankle moment.
    """
    def __init__(self, linkage: LinkageParams = ..., jig: JigParams = ...) -> None:
        ...
    def convert(self, displacement_m: typing.SupportsFloat | typing.SupportsIndex, force_N: typing.SupportsFloat | typing.SupportsIndex) -> JigSample:
        ...
    @property
    def linkage(self) -> LinkageParams:
        ...
    @property
    def params(self) -> JigParams:
        ...
class Table42Row:
    """
    A row of table 4.2.
    """
    @property
    def angle_deg(self) -> float:
        ...
    @property
    def gauge_pressure_Pa(self) -> float:
        ...
    @property
    def muscle_length_m(self) -> float:
        ...
    @property
    def vertical_displacement_m(self) -> float:
        ...
class MuscleParamsFile:
    """
    What a muscle-parameters file holds.
    """
    @property
    def initial(self) -> InitialState | None:
        """
        [initial]: the state at zero elongation of the sealed test the parameters were calibrated on, or None
        """
    @property
    def params(self) -> MuscleParams:
        """
        the muscle: [build], [bladder], [friction], [gas], [extensions]
        """
    @property
    def rig_effects(self) -> list[str]:
        """
        [rig] effects: what a diagnosis found in the test's fixture and instruments, as effect specs ("NAME:key=value,..."); empty if the file has none
        """
def braid_cylinder_length(fiber_length_m: typing.SupportsFloat | typing.SupportsIndex, braid_angle_rad: typing.SupportsFloat | typing.SupportsIndex) -> float:
    """
    Eq. 3.1.10: Lm = Lym cos(theta) [m].
    """
def braid_diameter(fiber_length_m: typing.SupportsFloat | typing.SupportsIndex, revolutions: typing.SupportsFloat | typing.SupportsIndex, braid_angle_rad: typing.SupportsFloat | typing.SupportsIndex) -> float:
    """
    Eq. 3.1.9: D = Lym sin(theta) / (pi n) [m].
    """
def braid_fiber_length(cylinder_length_m: typing.SupportsFloat | typing.SupportsIndex, diameter_m: typing.SupportsFloat | typing.SupportsIndex, revolutions: typing.SupportsFloat | typing.SupportsIndex) -> float:
    """
    Eq. 3.1.11 solved for Lym [m].
    """
def braid_tension(force_N: typing.SupportsFloat | typing.SupportsIndex, band_N: typing.SupportsFloat | typing.SupportsIndex) -> float:
    """
    What a braid transmits of a gas-and-bladder force [N]: it cannot push (smooth over band_N).
    """
def deflated_braid_angle_deg(build: MuscleBuild) -> float:
    """
    Braid angle of the deflated build's cylinder [deg]: tan(theta) = pi n D / Lm.
    """
def detect_gait_events(data: GaitData) -> GaitEvents:
    """
    Stride, heel strike and toe-off from the data alone.
    """
def estimate_stiffness(model: MuscleModel, trajectory: ElongationTrajectory, config: SimulatorConfig = ...) -> StiffnessEstimate:
    """
    The stiffness test SimulatorConfig(method=IntegrationMethod.auto) makes before a run.
    """
def fiber_revolutions_for_braid_angle(build: MuscleBuild, braid_angle_deg: typing.SupportsFloat | typing.SupportsIndex) -> float:
    """
    The fiber revolutions n that give the deflated build this braid angle [deg].
    """
def fit_clutch(cycle: GaitCycle, travel_deg: typing.SupportsFloat | typing.SupportsIndex = 7.0, margin_deg: typing.SupportsFloat | typing.SupportsIndex = 0.5) -> ClutchParams:
    """
    Screw angles that engage before heel strike and release at push-off for this gait on a well-fitted device.
    """
def free_inflation(geometry: BraidGeometry, bladder: BladderLaw, atmospheric_pressure_Pa: typing.SupportsFloat | typing.SupportsIndex, gauge_pressure_Pa: typing.SupportsFloat | typing.SupportsIndex) -> FreeInflation:
    """
    Length and diameter of the unloaded muscle inflated to a gauge pressure.
    """
def ideal_spring(run: DeviceRun, toe_off_percent: typing.SupportsFloat | typing.SupportsIndex, share: typing.SupportsFloat | typing.SupportsIndex) -> IdealSpring:
    ...
def inflated_and_sealed(params: MuscleParams, gauge_pressure_Pa: typing.SupportsFloat | typing.SupportsIndex) -> InitialState:
    """
    The start of a sealed test: inflated freely to gauge_pressure_Pa [Pa], sealed at the free length it gives.
    """
def isotonic_lengths(params: MuscleParams, gauge_pressures_Pa: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], load_N: typing.SupportsFloat | typing.SupportsIndex, start_length_m: typing.SupportsFloat | typing.SupportsIndex, effects: collections.abc.Sequence[Effect] = []) -> IsotonicLengths:
    """
    The length [m] at which the muscle carries load_N at each supplied gauge pressure [Pa], rows in the order measured, following the quasi-static path from start_length_m. Releases the GIL.
    """
def isotonic_motion(params: MuscleParams, time_s: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], gauge_pressures_Pa: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], load_N: typing.SupportsFloat | typing.SupportsIndex, mass_kg: typing.SupportsFloat | typing.SupportsIndex, start_length_m: typing.SupportsFloat | typing.SupportsIndex | None = None, effects: collections.abc.Sequence[Effect] = [], config: IsotonicMotionConfig = ...) -> IsotonicMotion:
    """
    Integrates a mass mass_kg [kg] under a constant load load_N [N] hanging on the muscle while the supplied gauge pressure [Pa] moves through its samples at time_s [s] (linear between them): m dv/dt = load - F(L, p, v), friction and effects included, starting at rest at start_length_m [m] (None: the quasi-static equilibrium of the first sample). Length and velocity at each sample. Releases the GIL.
    """
def measured_channels() -> list[str]:
    """
    names of the channels effects may act on
    """
def muscle_forces(geometry: BraidGeometry, shape: MuscleShape, bladder: BladderLaw, friction: FrictionParams, absolute_pressure_Pa: typing.SupportsFloat | typing.SupportsIndex, atmospheric_pressure_Pa: typing.SupportsFloat | typing.SupportsIndex, velocity_m_per_s: typing.SupportsFloat | typing.SupportsIndex) -> MuscleForces:
    """
    Virtual-work force of gas and bladder plus friction at one shape.
    """
def newtonian_fiber_tensions(geometry: BraidGeometry, shape: MuscleShape, bladder: BladderLaw, gauge_pressure_Pa: typing.SupportsFloat | typing.SupportsIndex) -> FiberTensions:
    """
    The thesis's Newtonian fiber tensions and force (eqs. 3.1.4-3.1.8).
    """
def polytropic_pressure(p0_abs_Pa: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], v0_m3: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], v_m3: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], n: typing.Annotated[numpy.typing.ArrayLike, numpy.float64]) -> typing.Any:
    """
    Eq. 3.1.16: absolute pressure after a polytropic change [Pa].
    """
def polytropic_temperature(t0_K: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], v0_m3: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], v_m3: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], n: typing.Annotated[numpy.typing.ArrayLike, numpy.float64]) -> typing.Any:
    """
    Eq. 3.1.18: temperature after a polytropic change [K].
    """
def pressure_branches(gauge_pressure_Pa: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], play_Pa: typing.SupportsFloat | typing.SupportsIndex = 2000.0) -> numpy.typing.NDArray[numpy.float64]:
    """
    +1 where a supplied gauge pressure [Pa] is being raised, -1 where lowered (a play operator of half-width play_Pa [Pa]).
    """
def read_muscle_params(path: os.PathLike | str | bytes) -> MuscleParams:
    """
    The MuscleParams of a muscle-parameters TOML file (read_muscle_params_file(path).params).
    """
def read_muscle_params_file(path: os.PathLike | str | bytes) -> MuscleParamsFile:
    """
    Reads and validates a muscle-parameters TOML file: its MuscleParams and its optional [initial] state. Raises ValueError naming the file, line, column and key (unknown or missing section or key, wrong type, a value outside its field's range).
    """
def reproduce_g3_script(data: GaitData, linkage: Linkage, body_mass_kg: typing.SupportsFloat | typing.SupportsIndex, begin_row: typing.SupportsInt | typing.SupportsIndex = 12, end_row: typing.SupportsInt | typing.SupportsIndex = 43, ideal_rows: typing.SupportsInt | typing.SupportsIndex = 45) -> ScriptKinematics:
    ...
def resample_cycle(data: GaitData, events: GaitEvents, points: typing.SupportsInt | typing.SupportsIndex, body_mass_kg: typing.SupportsFloat | typing.SupportsIndex) -> GaitCycle:
    """
    One stride resampled at `points` percents, the moment scaled to body_mass_kg.
    """
@typing.overload
def run_device(cycle: GaitCycle, linkage: Linkage, clutch: ClutchParams, play: PlayParams, spring: LinearSpring, strides: typing.SupportsInt | typing.SupportsIndex = 3, initial: ClutchMode = ClutchMode.engaged) -> DeviceRun:
    """
    The device over `strides` repeats of the gait cycle; returns the last stride (DeviceRun). `spring` is a LinearSpring, ThesisPolynomialSpring, PamStaticSpring or any callable force_N(elongation_m).
    """
@typing.overload
def run_device(cycle: GaitCycle, linkage: Linkage, clutch: ClutchParams, play: PlayParams, spring: ThesisPolynomialSpring, strides: typing.SupportsInt | typing.SupportsIndex = 3, initial: ClutchMode = ClutchMode.engaged) -> DeviceRun:
    """
    The device over `strides` repeats of the gait cycle; returns the last stride (DeviceRun). `spring` is a LinearSpring, ThesisPolynomialSpring, PamStaticSpring or any callable force_N(elongation_m).
    """
@typing.overload
def run_device(cycle: GaitCycle, linkage: Linkage, clutch: ClutchParams, play: PlayParams, spring: PamStaticSpring, strides: typing.SupportsInt | typing.SupportsIndex = 3, initial: ClutchMode = ClutchMode.engaged) -> DeviceRun:
    """
    The device over `strides` repeats of the gait cycle; returns the last stride (DeviceRun). `spring` is a LinearSpring, ThesisPolynomialSpring, PamStaticSpring or any callable force_N(elongation_m).
    """
@typing.overload
def run_device(cycle: GaitCycle, linkage: Linkage, clutch: ClutchParams, play: PlayParams, spring: collections.abc.Callable[[float], typing.SupportsFloat | typing.SupportsIndex], strides: typing.SupportsInt | typing.SupportsIndex = 3, initial: ClutchMode = ClutchMode.engaged) -> DeviceRun:
    """
    The device over `strides` repeats of the gait cycle; returns the last stride (DeviceRun). `spring` is a LinearSpring, ThesisPolynomialSpring, PamStaticSpring or any callable force_N(elongation_m).
    """
def simulate_measurement(params: MuscleParams, initial: InitialState, crosshead: ElongationTrajectory, effects: collections.abc.Sequence[Effect], simulator: Simulator = ..., shapes: ShapeTable = None) -> Measurement:
    """
    Simulates a sealed test as its instruments read it, with the effects applied at every stage. Releases the GIL: diagnosis fits run in parallel threads (a Python effect takes the GIL for its own calls). shapes: a ShapeTable of the build along the muscle's motion (ShapeTable(params, initial.length_m, crosshead) when no effect moves the muscle), read where it applies to the run (the effects leave the build, the motion and the fibres' stiffness as it has them), with the same result bit for bit; ignored otherwise (statistics.tabulated_shapes says which).
    """
def simulate_measurement_blocks(params: MuscleParams, initial: InitialState, crosshead: ElongationTrajectory, effects: collections.abc.Sequence[Effect], simulator: Simulator, block_rows: typing.SupportsInt | typing.SupportsIndex, sink: collections.abc.Callable, shapes: ShapeTable = None) -> SolverStatistics:
    """
    simulate_measurement, its samples handed to sink(first, channels) as they are integrated, block_rows at a time: first is the index of the block's first sample, channels a dict of numpy arrays (time_s [s], elongation_m [m], force_N [N], gauge_pressure_Pa [Pa], temperature_K [K]). The samples equal simulate_measurement's bit for bit; only one block is held. Effects on the measured channels read the whole series and are refused (ValueError). Returns the SolverStatistics. Releases the GIL but for the sink's calls. shapes: as for simulate_measurement.
    """
def simulate_supplied_measurement(params: MuscleParams, length_m: typing.SupportsFloat | typing.SupportsIndex, crosshead: ElongationTrajectory, gauge_pressure_Pa: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], effects: collections.abc.Sequence[Effect]) -> Measurement:
    """
    Simulates a supplied-pressure test: the measured gauge pressure [Pa] drives the static model at each sample of crosshead (lengths from length_m [m]), the gas at params.gas.ambient_temperature_K; force is predicted. Releases the GIL.
    """
def static_forces(params: MuscleParams, lengths_m: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], gauge_pressures_Pa: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], effects: collections.abc.Sequence[Effect] = []) -> numpy.typing.NDArray[numpy.float64]:
    """
    The muscle's force at rest [N] at each row of a static table (length [m], supplied gauge pressure [Pa]), with physical effects applied. Releases the GIL.
    """
def table_4_2() -> list[Table42Row]:
    """
    Table 4.2 as printed.
    """
def thesis_protocol(max_elongation_m: typing.SupportsFloat | typing.SupportsIndex, speed_m_per_s: typing.SupportsFloat | typing.SupportsIndex = 0.0025, cycles: typing.SupportsInt | typing.SupportsIndex = 10, sample_period_s: typing.SupportsFloat | typing.SupportsIndex = 0.1, hold_s: typing.SupportsFloat | typing.SupportsIndex = 0.0) -> ElongationTrajectory:
    """
    The bench protocol of section 3.2.1: triangular stretch cycles at constant speed.
    """
def walking_trajectory(run: DeviceRun, stride_period_s: typing.SupportsFloat | typing.SupportsIndex, strides: typing.SupportsInt | typing.SupportsIndex, pretension_m: typing.SupportsFloat | typing.SupportsIndex = 0.0) -> ElongationTrajectory:
    """
    The muscle's elongation over repeated strides, for the Simulator.
    """
def winter_appendix_g3() -> GaitData:
    """
    Winter's walking data as appendix G.3 prints it (56.7 kg subject).
    """
def with_ankle_range(cycle: GaitCycle, range_deg: typing.SupportsFloat | typing.SupportsIndex) -> GaitCycle:
    """
    The cycle with its ankle angle's excursion scaled to range_deg about the middle of its range.
    """
def write_muscle_params(path: os.PathLike | str | bytes, params: MuscleParams, initial: InitialState | None = None, comment: str = '', rig_effects: collections.abc.Sequence[str] = []) -> None:
    """
    Writes params (validated first) and, if given, the initial state as a muscle-parameters TOML file under the C++ field names, each key with its unit and meaning; `comment` goes at the top as TOML comments; `rig_effects` (effect specs of the test's fixture and instruments) as [rig] effects. read_muscle_params gives back the same doubles.
    """
PRESSURE_BRANCH_PLAY_PA: float = 2000.0
WINTER_SUBJECT_MASS_KG: float = 56.7
__version__: str
