"""The thesis's own muscle model (chapter 3), written afresh from its text, with the ways a real
muscle departs from it as dials: the base of the near-model world (:mod:`.near_families`).

Never imports pamkit. Where the printed text is wrong, the physical resolution is derived here:
the force is the virtual work of the gas and the bladder (not eqs. 3.1.4-3.1.8, whose cones carry
load without doing work), the ε⁴ term of eq. 3.1.13 is +19462, the wall is table C.4's 0.254 mm,
and a wall of incompressible rubber keeps its deflated volume (eq. 3.1.3 evaluated once).
SI units throughout; tension and elongation positive; pressures gauge unless named absolute.

Braid (eqs. 3.1.1, 3.1.9-3.1.11). A cylinder of inextensible fibres, each of length b over the
cylinder with n turns, between two end cones of fixed slant length g joining the cylinder's
diameter D to the end caps' d. With c = (D − d)/2 the cone's axial length is h(D) = √(g² − c²),
the cylinder's length L_m = L − 2 h(D), and the braid closes by

    G(D; L, b) = (π n D)² + (L − 2 h(D))² − b² = 0,

solved for D by safeguarded Newton iteration (G rises with D while L_m > 0). Implicitly,
∂D/∂L = −2 L_m / G_D and ∂D/∂b = 2 b / G_D with G_D = 2 (π n)² D + 2 L_m c / h. The fibre length
is fixed by the deflated build: b² = L_m0² + (π n D₀)².

Volumes. Inside the braid, eq. 3.1.1: V_t = (2/3) π h (D² + d² + d D)/4 + π D² L_m / 4. The gas
fills V = V_t − V_w. The wall's rubber V_w is incompressible, so it keeps its deflated volume
V_w0 = π L₀ (D₀ t_b − t_b²) (eq. 3.1.3 on the build); a wall that keeps its *thickness* instead
(eq. 3.1.3 at every length, as the thesis evaluates it) is the dial `wall_held`:
V_w = V_w0 + w (π L (D t_b − t_b²) − V_w0).

Bladder (eqs. 3.1.12-3.1.13, engineering stresses of the strains ε_l = L_m/L_m0 − 1 and
ε_h = D/D_b0 − 1, table 3.1's definitions, on the deflated cylinder's rubber V_r = π D_b0 t_b L_m0).
Its stored energy E_b has dE_b = V_r (σ_l dε_l + σ_h dε_h). The dial `membrane_share` blends in
another membrane law, an incompressible Mooney-Rivlin (or neo-Hookean) membrane whose two
constants are least-squares matched to the polynomials along the muscle's own strain path, so
that the two laws agree in stiffness and differ in shape only.

Force (virtual work, massless braid and bladder). With the gas at gauge pressure p doing work
p dV on the walls (the atmosphere fills whatever the gas does not),

    F = ∂E_b/∂L − p ∂V/∂L + F_friction.

Fibres of axial stiffness EA (fibre compliance) stretch to b' = b (1 + T/EA), where the tension
T of one fibre is the force conjugate to its length: N T = p ∂V/∂b − ∂E_b/∂b (a fibre cannot be
compressed: T ≥ 0); the force is then ∂/∂L of the same potential at that b' (envelope theorem).

Friction (eqs. 3.1.19-3.1.24): fibre-fibre, q = 2 n (N/2)² − N/2 crossings each 2 p μ_d w z, and
fibre-bladder 2 p μ_fb w (b N − z q / 2), μ_d = μ_fb = 0.2 (table C.4), w = z = the fibre
thickness (the thesis prints neither), times tanh(K_f v) with K_f = 1 s/m (eq. 3.1.21). The dial
`friction_share` moves a share of it to another law, at the thesis law's level at 11 mm/s: a
smooth Coulomb law tanh(v / v_s), or Dahl's law, whose normalised state z = F / F_c follows the
elongation, dz/dx = (1 − z sgn v) / x_d (x_d: the pre-sliding length), so that at a reversal the
friction turns over x_d of travel instead of at once, and in a hold it stays where it was.

Gas: n moles at temperature T in V + V_dead, p_abs = n R T / (V + V_dead). Isothermal unless a
heat-exchange time constant τ_h is given: n c_v dT/dt = −p_abs dV/dt − R T ṅ_out + n c_v (T_a − T)/τ_h.
A laminar leak ṅ_out = (V₀ + V_dead) p / (R T_a τ_L) (the gauge pressure decays with τ_L at
fixed volume). Viscoelastic bladder: a Maxwell branch beside each direction's elastic law,
dq_i/dt = k E_i(ε_i) dε_i/dt − q_i/τ_v (E_i the law's tangent modulus, k its strength), adding
V_r (q_l ∂ε_l/∂L + q_h ∂ε_h/∂L) to the force. Integrated with scipy.integrate.solve_ivp segment
by segment between the corners of the muscle's piecewise-linear motion.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

from .physics import ATMOSPHERE_PA, CV_AIR, GAS_CONSTANT, KELVIN, Build, Motion

FRICTION_SHARPNESS_S_PER_M = 1.0  # K_f of eq. 3.1.21, the thesis's value
FRICTION_COEFFICIENT = 0.2  # μ_d and μ_fb of table C.4
# The other friction laws' level equals the thesis law's at this speed, the middle (log scale) of
# the bench's 2.5-50 mm/s: a muscle's Coulomb level does not depend on the test's speed, and at
# either end of the range it is within 4x of the thesis law's, which a calibrated friction
# scale follows.
FRICTION_MATCHED_AT_M_PER_S = 0.011
HOOP_POLYNOMIAL_PA = (-81e3, 2046e3, -1415e3, -4759e3, 19462e3, -24717e3, 11166e3)  # eq. 3.1.13, c0..c6
LONGITUDINAL_POLYNOMIAL_PA = (0.0, 0.0, -3700e3, -52700e3, -438900e3, -1553000e3, -2018400e3)  # eq. 3.1.12
MEMBRANES = ("polynomial", "mooney_rivlin", "neo_hookean")
FRICTION_LAWS = ("tanh", "coulomb", "dahl")


@dataclass(frozen=True)
class Departures:
    """How this muscle differs from the thesis's model of the build its file declares; every
    dial at its default is the thesis's model (the declared build, pamkit's resolutions)."""

    wall_held: float = 0.0
    """share of the wall that keeps its thickness (eq. 3.1.3 at every length) rather than its
    volume [1]: 0 incompressible rubber, 1 the thesis's constant thickness"""
    wind: float = 0.0
    """relative error of the declared fibre revolutions: the braid has n (1 + wind) turns [1]"""
    end_flattening: float = 0.0
    """the end cones' slant is the declared one times (1 − this) [1]: 1 is flat ends"""
    membrane: str = "polynomial"
    """the other membrane law blended in: "mooney_rivlin" or "neo_hookean" (matched stiffness)"""
    membrane_share: float = 0.0
    """share of the bladder's stresses following that law instead of eqs. 3.1.12-13 [1]"""
    friction_law: str = "tanh"
    """the other friction law: "coulomb" (smooth, v_s = coulomb_velocity) or "dahl" """
    friction_share: float = 0.0
    """share of the friction following that law, at the thesis law's level at 11 mm/s [1]"""
    dahl_length_m: float = 0.5e-3
    """Dahl's pre-sliding length x_d [m]"""
    coulomb_velocity_m_per_s: float = 0.5e-3
    """v_s of the smooth Coulomb law [m/s]"""
    friction_scale: float = 1.0
    """this muscle's friction over the thesis coefficients' [1] (a baseline calibrates it)"""
    bladder_scale: float = 1.0
    """this bladder's stiffness over the butyl sample's [1] (a baseline calibrates it)"""


@dataclass(frozen=True)
class Effects:
    """Physical causes of the catalog, switched on in the muscle (None or 0: off)."""

    heat_time_constant_s: float | None = None  # τ_h; None: isothermal gas
    dead_volume_fraction: float = 0.0  # V_dead over the gas volume at the initial length
    leak_time_constant_s: float | None = None  # τ_L; None: sealed
    viscoelastic_time_constant_s: float = 2.0  # τ_v of the Maxwell branch [s]
    viscoelastic_strength: float = 0.0  # k: branch modulus over the tangent modulus; 0: none
    fiber_stiffness_N: float | None = None  # EA of one fibre; None: inextensible


@dataclass
class Shape:
    """The braid at lengths L (arrays): what the force and the gas need."""

    diameter: np.ndarray
    cylinder_length: np.ndarray
    gas_volume: np.ndarray
    dV_dL: np.ndarray  # at a fixed fibre length [m²]
    dV_db: np.ndarray  # ∂V/∂b at a fixed length [m²]
    strain_l: np.ndarray
    strain_h: np.ndarray
    de_l_dL: np.ndarray
    de_h_dL: np.ndarray
    de_l_db: np.ndarray
    de_h_db: np.ndarray


class Braid:
    """The braid, cones and wall of one muscle as built (the true one, departures applied)."""

    def __init__(self, build: Build, departures: Departures = Departures()):
        self.build = build
        self.departures = departures
        self.turns = math.pi * build.fiber_revolutions * (1.0 + departures.wind)  # π n
        self.slant = build.cone_generator_m * (1.0 - departures.end_flattening)
        self.end = build.end_diameter_m
        self.cylinder0 = build.length_m - 2.0 * self._cone_height(build.diameter_m)
        self.fiber_length = math.hypot(self.cylinder0, self.turns * build.diameter_m)
        tb = build.bladder_thickness_m
        self.wall0 = math.pi * build.length_m * (build.diameter_m * tb - tb * tb)
        self.rubber = math.pi * build.bladder_diameter_m * tb * self.cylinder0
        self.widest = self.end + 2.0 * self.slant if self.slant > 0 else math.inf

    def _cone_height(self, diameter):
        if self.slant <= 0:
            return 0.0 * diameter
        c = 0.5 * (np.asarray(diameter, dtype=float) - self.end)
        return np.sqrt(np.maximum(self.slant**2 - c * c, 0.0))

    @property
    def shortest_m(self) -> float:
        """Where the cones lie flat (or the braid reaches 90°) [m]."""
        if self.slant <= 0 or self.turns * self.widest >= self.fiber_length:
            return 0.0
        return math.sqrt(self.fiber_length**2 - (self.turns * self.widest) ** 2)

    def diameter(self, length, fiber_length=None) -> np.ndarray:
        """D solving the closure at each length (fibre length b, by default the build's)."""
        length = np.asarray(length, dtype=float)
        b = np.broadcast_to(np.asarray(self.fiber_length if fiber_length is None else fiber_length), length.shape)
        if self.slant <= 0:
            return np.sqrt(np.maximum(b * b - length * length, 0.0)) / self.turns
        k2 = self.turns**2
        low = np.full(length.shape, self.end)
        high = np.full(length.shape, self.widest)
        d = np.clip(np.sqrt(np.maximum(b * b - length * length, 0.0)) / self.turns, low + 1e-12, high - 1e-12)
        for _ in range(100):
            c = 0.5 * (d - self.end)
            h = np.sqrt(np.maximum(self.slant**2 - c * c, 1e-300))
            lm = length - 2.0 * h
            g = k2 * d * d + lm * lm - b * b
            slope = 2.0 * k2 * d + 2.0 * lm * c / h
            low = np.where(g < 0, d, low)
            high = np.where(g > 0, d, high)
            step = g / slope
            trial = d - step
            outside = ~((trial > low) & (trial < high))
            trial = np.where(outside, 0.5 * (low + high), trial)
            done = np.abs(trial - d) <= 1e-15 * d
            d = trial
            if done.all():
                break
        return d

    def shape(self, length, fiber_length=None) -> Shape:
        """The braid at each length, with its derivatives in length and in fibre length."""
        length = np.asarray(length, dtype=float)
        b = np.broadcast_to(np.asarray(self.fiber_length if fiber_length is None else fiber_length), length.shape)
        d = self.diameter(length, b)
        e, tb, w = self.end, self.build.bladder_thickness_m, self.departures.wall_held
        if self.slant > 0:
            c = 0.5 * (d - e)
            h = np.sqrt(np.maximum(self.slant**2 - c * c, 1e-300))
            c_over_h = c / h
        else:
            h = np.zeros_like(d)
            c_over_h = np.zeros_like(d)
        lm = length - 2.0 * h
        g_d = 2.0 * self.turns**2 * d + 2.0 * lm * c_over_h
        dd_dl = -2.0 * lm / g_d
        dd_db = 2.0 * b / g_d
        frustum = (d * d + e * e + e * d) / 4.0
        # V_t(D, L): partial derivatives at fixed L and at fixed D (h depends on D only)
        dh_dd = -0.5 * c_over_h
        vt_d = (2.0 / 3.0) * math.pi * (dh_dd * frustum + h * (2.0 * d + e) / 4.0) + math.pi / 4.0 * (
            2.0 * d * lm - 2.0 * d * d * dh_dd
        )
        vt_l = math.pi / 4.0 * d * d
        total = (2.0 / 3.0) * math.pi * h * frustum + math.pi / 4.0 * d * d * lm
        held = math.pi * length * (d * tb - tb * tb)
        wall = self.wall0 + w * (held - self.wall0)
        vw_d = w * math.pi * length * tb
        vw_l = w * math.pi * (d * tb - tb * tb)
        v_d, v_l = vt_d - vw_d, vt_l - vw_l
        de_l_dd = c_over_h / self.cylinder0  # ∂ε_l/∂D at fixed L: L_m = L − 2 h(D)
        db0 = self.build.bladder_diameter_m
        return Shape(
            diameter=d,
            cylinder_length=lm,
            gas_volume=total - wall,
            dV_dL=v_l + v_d * dd_dl,
            dV_db=v_d * dd_db,
            strain_l=lm / self.cylinder0 - 1.0,
            strain_h=d / db0 - 1.0,
            de_l_dL=1.0 / self.cylinder0 + de_l_dd * dd_dl,
            de_h_dL=dd_dl / db0,
            de_l_db=de_l_dd * dd_db,
            de_h_db=dd_db / db0,
        )

    def friction_coefficient_m2(self) -> float:
        """Eqs. 3.1.22-3.1.24: friction force per gauge pressure at full sliding [m²]."""
        n, fibers = self.turns / math.pi, self.build.fiber_count
        w = z = self.build.fiber_thickness_m
        crossings = 2.0 * n * (fibers / 2.0) ** 2 - fibers / 2.0
        fiber_fiber = crossings * 2.0 * w * z * FRICTION_COEFFICIENT
        fiber_bladder = 2.0 * FRICTION_COEFFICIENT * w * (self.fiber_length * fibers - z * crossings / 2.0)
        return fiber_fiber + fiber_bladder


def _polynomial(coefficients, x):
    x = np.asarray(x, dtype=float)
    return sum(c * x**k for k, c in enumerate(coefficients))


def _polynomial_slope(coefficients, x):
    x = np.asarray(x, dtype=float)
    return sum(k * c * x ** (k - 1) for k, c in enumerate(coefficients) if k)


def _mooney_rivlin_basis(strain_l, strain_h):
    """Engineering stresses of an incompressible membrane per unit C₁ and C₂ of
    W = C₁ (I₁ − 3) + C₂ (I₂ − 3), λ₃ = 1/(λ_l λ_h) eliminated: σ_i = ∂W/∂λ_i."""
    ll, lh = 1.0 + np.asarray(strain_l), 1.0 + np.asarray(strain_h)
    c1 = (2.0 * (ll - ll**-3 * lh**-2), 2.0 * (lh - lh**-3 * ll**-2))
    c2 = (2.0 * (ll * lh * lh - ll**-3), 2.0 * (lh * ll * ll - lh**-3))
    return c1, c2


class Membrane:
    """The bladder's stress law: eqs. 3.1.12-13, blended with a matched hyperelastic law."""

    def __init__(self, braid: Braid, departures: Departures):
        self.share = departures.membrane_share
        self.scale = departures.bladder_scale
        self.constants = (0.0, 0.0)
        if self.share > 0:
            if departures.membrane not in MEMBRANES[1:]:
                raise ValueError(f"membrane = {departures.membrane!r}: one of {MEMBRANES[1:]}")
            self.constants = matched_constants(braid, departures.membrane)

    def stresses(self, strain_l, strain_h):
        sl = _polynomial(LONGITUDINAL_POLYNOMIAL_PA, strain_l)
        sh = _polynomial(HOOP_POLYNOMIAL_PA, strain_h)
        if self.share > 0:
            (al, ah), (bl, bh) = _mooney_rivlin_basis(strain_l, strain_h)
            c1, c2 = self.constants
            sl = (1 - self.share) * sl + self.share * (c1 * al + c2 * bl)
            sh = (1 - self.share) * sh + self.share * (c1 * ah + c2 * bh)
        return self.scale * sl, self.scale * sh

    def tangents(self, strain_l, strain_h):
        """dσ_l/dε_l and dσ_h/dε_h (by a central difference for the blended law) [Pa]."""
        if self.share == 0:
            return (
                self.scale * _polynomial_slope(LONGITUDINAL_POLYNOMIAL_PA, strain_l),
                self.scale * _polynomial_slope(HOOP_POLYNOMIAL_PA, strain_h),
            )
        step = 1e-6
        plus_l, _ = self.stresses(np.asarray(strain_l) + step, strain_h)
        minus_l, _ = self.stresses(np.asarray(strain_l) - step, strain_h)
        _, plus_h = self.stresses(strain_l, np.asarray(strain_h) + step)
        _, minus_h = self.stresses(strain_l, np.asarray(strain_h) - step)
        return (plus_l - minus_l) / (2 * step), (plus_h - minus_h) / (2 * step)


def matched_constants(braid: Braid, law: str) -> tuple[float, float]:
    """C₁, C₂ of the hyperelastic membrane closest (least squares, both directions) to the
    thesis polynomials along the braid's own strains from 80 % of its stroke to its deflated length."""
    lengths = np.linspace(braid.shortest_m + 0.2 * (braid.build.length_m - braid.shortest_m), braid.build.length_m, 60)
    s = braid.shape(lengths)
    (al, ah), (bl, bh) = _mooney_rivlin_basis(s.strain_l, s.strain_h)
    target = np.concatenate(
        [_polynomial(LONGITUDINAL_POLYNOMIAL_PA, s.strain_l), _polynomial(HOOP_POLYNOMIAL_PA, s.strain_h)]
    )
    if law == "neo_hookean":
        basis = np.concatenate([al, ah])[:, None]
        (c1,), *_ = np.linalg.lstsq(basis, target, rcond=None)
        return float(c1), 0.0
    basis = np.column_stack([np.concatenate([al, ah]), np.concatenate([bl, bh])])
    (c1, c2), *_ = np.linalg.lstsq(basis, target, rcond=None)
    return float(c1), float(c2)


@dataclass
class Forces:
    """The muscle at lengths L with its gas at gauge pressure p (arrays)."""

    static: np.ndarray  # ∂E_b/∂L − p ∂V/∂L, no friction [N]
    shape: Shape  # the braid, at the fibres' stretched length
    fiber_strain: np.ndarray  # the fibres' stretch T/EA [1] (0: inextensible)


class ThesisMuscle:
    """One muscle: its braid and membrane as built (departures applied) and its physics effects.
    `forces` is the model's static force; `SealedTest` and `supplied_force` run tests on it."""

    def __init__(self, build: Build, departures: Departures = Departures(), effects: Effects = Effects()):
        self.build = build
        self.departures = departures
        self.effects = effects
        self.braid = Braid(build, departures)
        self.membrane = Membrane(self.braid, departures)
        self.friction_m2 = self.braid.friction_coefficient_m2() * departures.friction_scale

    def _static(self, shape: Shape, gauge_Pa, fiber=False):
        sl, sh = self.membrane.stresses(shape.strain_l, shape.strain_h)
        if fiber:
            return self.braid.rubber * (sl * shape.de_l_db + sh * shape.de_h_db) - gauge_Pa * shape.dV_db
        return self.braid.rubber * (sl * shape.de_l_dL + sh * shape.de_h_dL) - gauge_Pa * shape.dV_dL

    def forces(self, length, gauge_Pa, absolute_of=None) -> Forces:
        """Static force at lengths and gauge pressures. With fibre compliance the fibres stretch
        to the length where their tension balances; `absolute_of(volume)` then gives the gas's
        absolute pressure at a gas volume (a sealed gas), else the pressure is held."""
        length = np.asarray(length, dtype=float)
        gauge = np.broadcast_to(np.asarray(gauge_Pa, dtype=float), length.shape)
        stiffness = self.effects.fiber_stiffness_N
        strain = np.zeros_like(length)
        if stiffness is None:
            shape = self.braid.shape(length)
            return Forces(self._static(shape, gauge), shape, strain)
        fibers = self.build.fiber_count

        def imbalance(eps):
            s = self.braid.shape(length, self.braid.fiber_length * (1.0 + eps))
            p = gauge if absolute_of is None else absolute_of(s.gas_volume) - ATMOSPHERE_PA
            tension = -self._static(s, p, fiber=True) / fibers
            return stiffness * eps - np.maximum(tension, 0.0), s, p

        # Newton on EA ε − T(ε) = 0 (rising in ε: a stable fibre), slope by a small difference
        for _ in range(30):
            r, _, _ = imbalance(strain)
            r2, _, _ = imbalance(strain + 1e-9)
            slope = np.maximum((r2 - r) / 1e-9, 1e-3 * stiffness)
            step = r / slope
            strain = np.maximum(strain - step, 0.0)
            if np.all(np.abs(step) < 1e-13):
                break
        _, shape, p = imbalance(strain)
        return Forces(self._static(shape, p), shape, strain)

    def free_length(self, gauge_Pa: float) -> float:
        """Length at which the muscle, inflated to `gauge_Pa` and held there, pulls nothing [m]."""
        shortest = max(self.braid.shortest_m, 0.3 * self.build.length_m) + 1e-6
        return brentq(
            lambda x: float(self.forces(np.array([x]), gauge_Pa).static[0]),
            shortest,
            self.build.length_m,
            xtol=1e-12,
        )


# ----------------------------------------------------------------------------------------------
# bench tests of the muscle


def fixture_play(motion: Motion, slack_m: float) -> Motion:
    """The muscle's motion behind a crosshead with `slack_m` of play (a play operator): a stretch
    first takes up the play, a return leaves the muscle where it is until the crosshead comes
    back to it. Exact corners for a piecewise-linear crosshead."""
    if slack_m <= 0:
        return motion
    t_out, x_out = [motion.corner_t[0]], [0.0]
    muscle = 0.0
    for k in range(motion.corner_t.size - 1):
        t0, t1 = motion.corner_t[k], motion.corner_t[k + 1]
        x0, x1 = motion.corner_x[k], motion.corner_x[k + 1]
        if x1 != x0:
            # the crosshead meets the muscle at `engage`: the play's far end when stretching
            engage = muscle + slack_m if x1 > x0 else muscle
            if (x1 - engage) * (x1 - x0) > 0:
                if (engage - x0) * (x1 - x0) > 0:
                    t_out.append(t0 + (engage - x0) / (x1 - x0) * (t1 - t0))
                    x_out.append(muscle)
                muscle = x1 - slack_m if x1 > x0 else x1
        t_out.append(t1)
        x_out.append(muscle)
    return Motion(np.asarray(t_out), np.asarray(x_out))


def arriving_velocity(motion: Motion, times) -> np.ndarray:
    """The velocity of the segment that ends at each instant (left-continuous): a sample taken at
    a reversal reads the friction of the ramp it closes, as a load cell sampling at the end of
    each interval does."""
    t = np.asarray(times, dtype=float)
    slopes = np.diff(motion.corner_x) / np.diff(motion.corner_t)
    index = np.clip(np.searchsorted(motion.corner_t, t - 1e-9, side="left") - 1, 0, slopes.size - 1)
    return slopes[index]


def dahl_state(motion: Motion, times: np.ndarray, length_m: float) -> np.ndarray:
    """Dahl's normalised friction z(t) ∈ [−1, 1] along the motion, from z = 0 at rest:
    dz/dx = (1 − z sgn v)/x_d, exact on each linear segment."""
    t, x = motion.corner_t, motion.corner_x
    z_corner = np.zeros(t.size)
    for k in range(t.size - 1):
        z_corner[k + 1] = _dahl_step(z_corner[k], x[k + 1] - x[k], length_m)
    index = np.clip(np.searchsorted(t, times, side="right") - 1, 0, t.size - 2)
    return _dahl_step(z_corner[index], motion.elongation(times) - x[index], length_m)


def _dahl_step(z0, dx, length_m):
    sign = np.sign(dx)
    return np.where(sign == 0, z0, sign - (sign - z0) * np.exp(-np.abs(dx) / length_m))


@dataclass
class SealedRun:
    """The truth of a sealed test at the requested instants."""

    time_s: np.ndarray
    elongation_m: np.ndarray  # the muscle's, from its initial length
    force_N: np.ndarray
    gauge_kPa: np.ndarray
    temperature_C: np.ndarray
    fiber_strain: np.ndarray  # the fibres' stretch (fibre compliance) [1]


class SealedTest:
    """A muscle inflated to `gauge_kPa` at `initial_length_m`, sealed, and moved from there."""

    def __init__(self, muscle: ThesisMuscle, gauge_kPa: float, ambient_C: float, initial_length_m: float):
        self.muscle = muscle
        self.ambient_K = ambient_C + KELVIN
        self.initial_length_m = initial_length_m
        effects = muscle.effects
        if effects.fiber_stiffness_N is not None and (
            effects.heat_time_constant_s is not None
            or effects.leak_time_constant_s is not None
            or effects.viscoelastic_strength > 0
        ):
            raise ValueError("fibre compliance is modelled with a sealed isothermal gas and an elastic bladder only")
        gauge0 = gauge_kPa * 1e3
        if effects.fiber_stiffness_N is None:
            volume0 = float(muscle.braid.shape(np.array([initial_length_m])).gas_volume[0])
        else:
            volume0 = float(muscle.forces(np.array([initial_length_m]), gauge0).shape.gas_volume[0])
        self.dead_m3 = effects.dead_volume_fraction * volume0
        self.moles0 = (gauge0 + ATMOSPHERE_PA) * (volume0 + self.dead_m3) / (GAS_CONSTANT * self.ambient_K)
        tau = effects.leak_time_constant_s
        self.leak_conductance = 0.0 if tau is None else (volume0 + self.dead_m3) / (GAS_CONSTANT * self.ambient_K * tau)

    def _absolute(self, moles, temperature):
        return lambda volume: moles * GAS_CONSTANT * temperature / (volume + self.dead_m3)

    def _states(self, motion: Motion, times: np.ndarray):
        """(moles, temperature, q_l, q_h) at `times` by integrating the motion's segments."""
        e = self.muscle.effects
        ode = e.heat_time_constant_s is not None or e.leak_time_constant_s is not None or e.viscoelastic_strength > 0
        out = np.zeros((4, times.size))
        out[0], out[1] = self.moles0, self.ambient_K
        if not ode:
            return out
        braid, membrane = self.muscle.braid, self.muscle.membrane
        state = np.array([self.moles0, self.ambient_K, 0.0, 0.0])
        corners = motion.corner_t
        for k in range(corners.size - 1):
            t0, t1 = corners[k], corners[k + 1]
            speed = (motion.corner_x[k + 1] - motion.corner_x[k]) / (t1 - t0)
            x0 = motion.corner_x[k]

            def rhs(t, y, speed=speed, x0=x0, t0=t0):
                moles, temperature, q_l, q_h = y
                length = np.array([self.initial_length_m + x0 + speed * (t - t0)])
                s = braid.shape(length)
                volume = s.gas_volume[0] + self.dead_m3
                gauge = moles * GAS_CONSTANT * temperature / volume - ATMOSPHERE_PA
                outflow = self.leak_conductance * gauge
                if e.heat_time_constant_s is None:
                    d_temperature = 0.0
                else:
                    d_temperature = (
                        -(gauge + ATMOSPHERE_PA) * s.dV_dL[0] * speed
                        - GAS_CONSTANT * temperature * outflow
                        + moles * CV_AIR * (self.ambient_K - temperature) / e.heat_time_constant_s
                    ) / (moles * CV_AIR)
                d_q = [0.0, 0.0]
                if e.viscoelastic_strength > 0:
                    el, eh = membrane.tangents(s.strain_l, s.strain_h)
                    tau_v = e.viscoelastic_time_constant_s
                    d_q = [
                        e.viscoelastic_strength * el[0] * s.de_l_dL[0] * speed - q_l / tau_v,
                        e.viscoelastic_strength * eh[0] * s.de_h_dL[0] * speed - q_h / tau_v,
                    ]
                return [-outflow, d_temperature, *d_q]

            inside = (times >= t0) & ((times < t1) | ((k == corners.size - 2) & (times <= t1)))
            solution = solve_ivp(
                rhs,
                (t0, t1),
                state,
                method="LSODA",
                rtol=1e-10,
                atol=[self.moles0 * 1e-13, 1e-10, 1e-4, 1e-4],
                dense_output=True,
            )
            if not solution.success:
                raise RuntimeError(f"thesis muscle: integration failed on segment {k}: {solution.message}")
            if inside.any():
                out[:, inside] = solution.sol(times[inside])
            state = solution.y[:, -1]
        return out

    def run(self, motion: Motion, times) -> SealedRun:
        """The truth at `times` (sorted) for the muscle's motion (elongation from the initial length)."""
        times = np.asarray(times, dtype=float)
        moles, temperature, q_l, q_h = self._states(motion, times)
        x = motion.elongation(times)
        length = self.initial_length_m + x
        sealed = self._absolute(moles, temperature)
        if self.muscle.effects.fiber_stiffness_N is None:
            f = self.muscle.forces(length, sealed(self.muscle.braid.shape(length).gas_volume) - ATMOSPHERE_PA)
        else:
            f = self.muscle.forces(length, 0.0, absolute_of=sealed)
        shape = f.shape
        gauge = sealed(shape.gas_volume) - ATMOSPHERE_PA
        force = f.static + self.muscle.braid.rubber * (q_l * shape.de_l_dL + q_h * shape.de_h_dL)
        force = force + self.friction(motion, times, gauge)
        return SealedRun(times, x, force, gauge / 1e3, temperature - KELVIN, f.fiber_strain)

    def friction(self, motion: Motion, times, gauge_Pa) -> np.ndarray:
        """Friction along the motion at the gas's gauge pressure [N] (eqs. 3.1.19-3.1.24, with the
        other law's share)."""
        d = self.muscle.departures
        level = self.muscle.friction_m2 * np.maximum(gauge_Pa, 0.0)
        velocity = arriving_velocity(motion, times)
        thesis = np.tanh(FRICTION_SHARPNESS_S_PER_M * velocity)
        share = d.friction_share
        if share == 0:
            return level * thesis
        at_speed = math.tanh(FRICTION_SHARPNESS_S_PER_M * FRICTION_MATCHED_AT_M_PER_S)
        if d.friction_law == "coulomb":
            other = at_speed * np.tanh(velocity / d.coulomb_velocity_m_per_s)
        elif d.friction_law == "dahl":
            other = at_speed * dahl_state(motion, times, d.dahl_length_m)
        else:
            raise ValueError(f"friction_law = {d.friction_law!r}: one of {FRICTION_LAWS[1:]}")
        return level * ((1 - share) * thesis + share * other)


def supplied_force(
    muscle: ThesisMuscle,
    length_m: float,
    gauge_kPa,
    *,
    hysteresis: float = 0.0,
    hysteresis_width_kPa: float = 2.0,
    braid_pushes: bool = False,
) -> np.ndarray:
    """Force of a muscle held at `length_m` while its supplied pressure runs through `gauge_kPa`
    (in time order) [N]. The bladder-braid friction of a pressure raised and lowered is a share
    `hysteresis` of the pressure force p π D²/4 against the pressure's direction, turning over
    `hysteresis_width_kPa` of pressure (Dahl's law in pressure): the force on venting lies above the
    force on pressurising. A braid carries no compression: the load cell reads max(F, 0) unless
    `braid_pushes` (the thesis's braid)."""
    gauge = np.asarray(gauge_kPa, dtype=float) * 1e3
    lengths = np.full(gauge.shape, length_m)
    f = muscle.forces(lengths, gauge)
    force = f.static
    if hysteresis > 0:
        z = np.zeros_like(gauge)
        for i in range(1, gauge.size):
            z[i] = _dahl_step(z[i - 1], gauge[i] - gauge[i - 1], hysteresis_width_kPa * 1e3)
        force = force - hysteresis * np.maximum(gauge, 0.0) * math.pi * f.shape.diameter**2 / 4.0 * z
    return force if braid_pushes else np.maximum(force, 0.0)
