"""A sealed (or supplied) braided muscle on a tensile machine, derived from first principles.

Independent of pamkit by construction: its own end geometry, bladder energy, friction laws and
gas law; only the build's numbers (thesis PAM 2) are shared, because a test must describe the
same muscle. Equations (SI units, tension positive, elongation rate v positive when stretching):

Braid (ideal cylinder, Chou & Hannaford 1996). Each fibre has length b and winds n turns over
the braided length L_a; the braid's diameter follows from b² = L_a² + (n π D)²:

    D(L_a) = sqrt(b² − L_a²) / (n π),   dD/dL_a = −L_a / ((n π)² D).

End effects (this model's own choice): the two end caps are rigid cones, frozen in their
deflated shape (axial height h = sqrt(g² − ((D₀ − d_e)/2)²) from the cone's generator g), so
L_a = L − 2h and the cones add a constant gas volume. Gas volume inside the bladder:

    V(L) = π/4 (D − δ)² L_a + V_cones,   δ = 2 (t_fibre + t_bladder).

Bladder: an incompressible neo-Hookean tube of shear modulus μ, reference mid-diameter
d_m = d_bladder − t_bladder and length L_a0, stretched λθ = (D − 2 t_fibre − t_bladder) / d_m
round and λz = L_a / L_a0 along; stored energy E = μ/2 (λθ² + λz² + λθ⁻²λz⁻² − 3) · V_rubber.
Mullins-like softening scales μ by (1 − η m(t)/m_max), m the largest elongation reached so far.

Virtual work on the massless braid and bladder: F dL + p_g dV = dE, hence the static tension

    F_static = dE/dL − p_g dV/dL,

and a braid carries no compression: the load cell reads max(F, 0) of the muscle itself.

Friction between fibres and bladder, proportional to the gauge pressure that presses them
together: smooth Coulomb F_f = c_f p_g tanh(v / v_s), or Dahl's law
dF_f/dt = (c_f p_g / x_d) v (1 − F_f / (c_f p_g) sgn v) (a pre-sliding length x_d).

Gas: a closed mass of air (n moles) at temperature T in V + V_dead (hose, transducer):
p_abs = n R T / (V + V_dead). Heat exchange with the wall at ambient, time constant τ_h
(None: isothermal); a laminar leak ṅ = −(V₀ / (R T_a τ_L)) p_g (gauge pressure decays with τ_L
at fixed volume). First law per mole: n c_v dT/dt = −p_abs dV/dt − R T ṅ_out + n c_v (T_a − T)/τ_h.
Integrated with scipy.integrate.solve_ivp segment by segment between the crosshead's corners.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

GAS_CONSTANT = 8.314462618  # J/(mol K), CODATA 2018
CV_AIR = 2.5 * GAS_CONSTANT  # diatomic ideal gas [J/(mol K)]
ATMOSPHERE_PA = 101325.0
KELVIN = 273.15


@dataclass(frozen=True)
class Build:
    """Thesis PAM 2 as built and deflated (tables 3.4 and C.4), in the TOML's [muscle] keys."""

    length_m: float = 0.225
    diameter_m: float = 0.020
    bladder_diameter_m: float = 0.01545
    bladder_thickness_m: float = 0.000254
    fiber_count: int = 216
    fiber_revolutions: float = 2.0
    fiber_thickness_m: float = 0.000254
    end_diameter_m: float = 0.013
    cone_generator_m: float = 0.0095


@dataclass(frozen=True)
class Physics:
    """The model's material and gas parameters (calibrated once against the bench's range:
    see tests/independent/calibrate.py) and the switches of the hidden causes."""

    shear_modulus_Pa: float = 0.6e6
    """bladder rubber μ: natural latex is 0.3-0.6 MPa; 0.6, its top, brings the force nearest
    pamkit's while the pressure stays within 2.3 kPa (calibrate.py --grid)"""
    friction_m2: float = 2.6e-5
    """c_f: friction force per gauge pressure [N/Pa]; least squares against pamkit at 2.5 and 25 mm/s"""
    friction_velocity_m_per_s: float = 1.0e-3
    """v_s of the smooth Coulomb sign [m/s]"""
    dahl_length_m: float | None = None
    """pre-sliding length x_d of Dahl's law; None: smooth Coulomb"""
    heat_time_constant_s: float | None = None
    """τ_h; None: isothermal gas"""
    dead_volume_fraction: float = 0.0
    """V_dead / V at the length the muscle was sealed at (its free length unless given)"""
    leak_time_constant_s: float | None = None
    """τ_L; None: sealed"""
    mullins_softening: float = 0.0
    """η: fraction of μ lost once the largest elongation of the test is reached"""


@dataclass(frozen=True)
class Geometry:
    build: Build = field(default_factory=Build)

    @property
    def cone_height_m(self) -> float:
        b = self.build
        return math.sqrt(b.cone_generator_m**2 - ((b.diameter_m - b.end_diameter_m) / 2) ** 2)

    @property
    def cone_volume_m3(self) -> float:
        b = self.build
        d, e = b.diameter_m, b.end_diameter_m
        return 2 * math.pi * self.cone_height_m / 12 * (d * d + d * e + e * e)

    @property
    def braided_length0_m(self) -> float:
        return self.build.length_m - 2 * self.cone_height_m

    @property
    def fiber_length_m(self) -> float:
        b = self.build
        return math.hypot(self.braided_length0_m, b.fiber_revolutions * math.pi * b.diameter_m)

    def diameter(self, length):
        braided = np.asarray(length) - 2 * self.cone_height_m
        return np.sqrt(self.fiber_length_m**2 - braided**2) / (self.build.fiber_revolutions * math.pi)

    def volume_and_slope(self, length):
        """Gas volume inside the muscle [m³] and its derivative with length [m²]."""
        b = self.build
        braided = np.asarray(length) - 2 * self.cone_height_m
        d = self.diameter(length)
        dd = -braided / ((b.fiber_revolutions * math.pi) ** 2 * d)
        inner = d - 2 * (b.fiber_thickness_m + b.bladder_thickness_m)
        volume = math.pi / 4 * inner**2 * braided + self.cone_volume_m3
        slope = math.pi / 4 * (2 * inner * dd * braided + inner**2)
        return volume, slope

    def bladder_slope(self, length, shear_modulus_Pa):
        """dE/dL of the neo-Hookean bladder [N]."""
        b = self.build
        braided = np.asarray(length) - 2 * self.cone_height_m
        d = self.diameter(length)
        dd = -braided / ((b.fiber_revolutions * math.pi) ** 2 * d)
        mid = b.bladder_diameter_m - b.bladder_thickness_m
        hoop = (d - 2 * b.fiber_thickness_m - b.bladder_thickness_m) / mid
        axial = braided / self.braided_length0_m
        rubber = math.pi * mid * b.bladder_thickness_m * self.braided_length0_m
        d_hoop = (hoop - hoop**-3 * axial**-2) * dd / mid
        d_axial = (axial - hoop**-2 * axial**-3) / self.braided_length0_m
        return shear_modulus_Pa * rubber * (d_hoop + d_axial)

    def static_tension(self, length, gauge_Pa, shear_modulus_Pa):
        _, slope = self.volume_and_slope(length)
        return self.bladder_slope(length, shear_modulus_Pa) - gauge_Pa * slope

    def free_length(self, gauge_Pa: float, shear_modulus_Pa: float) -> float:
        """Length at which the inflated muscle pulls nothing [m]."""
        shortest = 2 * self.cone_height_m + self.fiber_length_m / math.sqrt(3)
        return brentq(
            lambda x: float(self.static_tension(x, gauge_Pa, shear_modulus_Pa)),
            shortest,
            self.build.length_m,
            xtol=1e-10,
        )


@dataclass
class Motion:
    """The muscle's true length history: piecewise linear through corners (times, elongations)."""

    corner_t: np.ndarray
    corner_x: np.ndarray

    def elongation(self, t):
        return np.interp(t, self.corner_t, self.corner_x)

    def velocity(self, t):
        """Right-continuous: at a corner, the velocity of the segment that starts there."""
        t = np.asarray(t, dtype=float)
        slopes = np.diff(self.corner_x) / np.diff(self.corner_t)
        index = np.clip(np.searchsorted(self.corner_t, t, side="right") - 1, 0, slopes.size - 1)
        return slopes[index]

    def running_max(self, t):
        x = self.elongation(t)
        before = np.maximum.accumulate(self.corner_x)
        index = np.clip(np.searchsorted(self.corner_t, t, side="right") - 1, 0, before.size - 1)
        return np.maximum(before[index], x)


@dataclass
class SealedRun:
    """A sealed test: the truth at requested instants."""

    time_s: np.ndarray
    elongation_m: np.ndarray
    force_N: np.ndarray
    gauge_kPa: np.ndarray
    temperature_C: np.ndarray


class SealedMuscle:
    """A sealed muscle inflated at `gauge_kPa` and released to its free length at ambient; or,
    given `sealed_length_m`, inflated and sealed while held at that length (a test that declares
    its initial length: held longer than its free length it pulls before it moves, shorter its
    braid is slack). Elongations in `run` are from the length it was sealed at."""

    def __init__(
        self, build: Build, physics: Physics, gauge_kPa: float, ambient_C: float, sealed_length_m: float | None = None
    ):
        self.geometry = Geometry(build)
        self.physics = physics
        self.ambient_K = ambient_C + KELVIN
        self.free_length_m = self.geometry.free_length(gauge_kPa * 1e3, physics.shear_modulus_Pa)
        self.sealed_length_m = self.free_length_m if sealed_length_m is None else sealed_length_m
        volume, _ = self.geometry.volume_and_slope(self.sealed_length_m)
        self.dead_volume_m3 = physics.dead_volume_fraction * float(volume)
        self.moles0 = (
            (gauge_kPa * 1e3 + ATMOSPHERE_PA) * (float(volume) + self.dead_volume_m3) / (GAS_CONSTANT * self.ambient_K)
        )
        tau = physics.leak_time_constant_s
        self.leak_conductance = 0.0 if tau is None else float(volume) / (GAS_CONSTANT * self.ambient_K * tau)

    def _gauge(self, moles, temperature, length):
        volume, _ = self.geometry.volume_and_slope(length)
        return moles * GAS_CONSTANT * temperature / (volume + self.dead_volume_m3) - ATMOSPHERE_PA

    def _friction_limit(self, gauge_Pa):
        return self.physics.friction_m2 * np.maximum(gauge_Pa, 0.0)

    def run(self, motion: Motion, times: np.ndarray) -> SealedRun:
        """Integrates over the motion's segments; returns the truth at `times` (sorted)."""
        p = self.physics
        times = np.asarray(times, dtype=float)
        state = np.array([self.moles0, self.ambient_K, 0.0])
        out = np.zeros((3, times.size))
        corners = motion.corner_t
        for k in range(corners.size - 1):
            t0, t1 = corners[k], corners[k + 1]
            speed = (motion.corner_x[k + 1] - motion.corner_x[k]) / (t1 - t0)
            x0 = motion.corner_x[k]

            def rhs(t, y, speed=speed, x0=x0, t0=t0):
                moles, temperature, dahl = y
                length = self.sealed_length_m + x0 + speed * (t - t0)
                volume, slope = self.geometry.volume_and_slope(length)
                gauge = moles * GAS_CONSTANT * temperature / (volume + self.dead_volume_m3) - ATMOSPHERE_PA
                outflow = self.leak_conductance * gauge
                heat = (
                    0.0
                    if p.heat_time_constant_s is None
                    else moles * CV_AIR * (self.ambient_K - temperature) / p.heat_time_constant_s
                )
                if p.heat_time_constant_s is None:
                    d_temperature = 0.0
                else:
                    d_temperature = (
                        -(gauge + ATMOSPHERE_PA) * slope * speed - GAS_CONSTANT * temperature * outflow + heat
                    ) / (moles * CV_AIR)
                d_dahl = 0.0
                if p.dahl_length_m is not None:
                    limit = max(p.friction_m2 * max(gauge, 0.0), 1e-9)
                    d_dahl = (
                        limit / p.dahl_length_m * speed * (1.0 - dahl / limit * math.copysign(1.0, speed))
                        if speed
                        else 0.0
                    )
                return [-outflow, d_temperature, d_dahl]

            inside = (times >= t0) & ((times < t1) | ((k == corners.size - 2) & (times <= t1)))
            solution = solve_ivp(
                rhs,
                (t0, t1),
                state,
                method="LSODA",
                rtol=1e-9,
                atol=[self.moles0 * 1e-12, 1e-9, 1e-9],
                dense_output=True,
            )
            if not solution.success:
                raise RuntimeError(f"independent model: integration failed on segment {k}: {solution.message}")
            if inside.any():
                out[:, inside] = solution.sol(times[inside])
            state = solution.y[:, -1]
        moles, temperature, dahl = out
        x = motion.elongation(times)
        length = self.sealed_length_m + x
        gauge = self._gauge(moles, temperature, length)
        mu = p.shear_modulus_Pa * (
            1.0 - p.mullins_softening * motion.running_max(times) / max(motion.corner_x.max(), 1e-12)
        )
        static = self.geometry.static_tension(length, gauge, mu)
        if p.dahl_length_m is None:
            friction = self._friction_limit(gauge) * np.tanh(motion.velocity(times) / p.friction_velocity_m_per_s)
        else:
            friction = dahl
        force = np.maximum(static + friction, 0.0)
        return SealedRun(times, x, force, gauge / 1e3, temperature - KELVIN)


def supplied_tension(build: Build, physics: Physics, length_m: float, gauge_kPa: np.ndarray) -> np.ndarray:
    """Isometric tension at a held length for a supplied pressure: no motion, so no friction;
    a braid carries no compression."""
    geometry = Geometry(build)
    return np.maximum(geometry.static_tension(length_m, np.asarray(gauge_kPa) * 1e3, physics.shear_modulus_Pa), 0.0)


def with_changes(physics: Physics, **changes) -> Physics:
    return replace(physics, **changes)
