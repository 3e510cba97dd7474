"""An independent NumPy/SciPy implementation of pamkit's muscle model, to check and time pamkit.

It re-implements, from the thesis (chapter 3) and pamkit's header comments but sharing no code
with pamkit (this file does not import it), the same equations:

* braid with end cones: the closure (pi n D)^2 + (L - 2 LL(D))^2 = Lym^2 solved for the braid
  diameter D by ``scipy.optimize.brentq`` (eqs. 3.1.9-3.1.11 plus cones of fixed slant Lz);
* volumes, eqs. 3.1.1-3.1.3 (the bladder's rubber conserved), and their derivatives with respect to L;
* force by virtual work: -p_abs dV_gas/dL + p_atm dV_total/dL, plus the bladder
  V_ref (sigma_l deps_l/dL + sigma_h deps_h/dL) with the polynomials of eqs. 3.1.12-3.1.13,
  plus friction (eqs. 3.1.19-3.1.24 as in pamkit/muscle/friction.hpp);
* the gas temperature ODE, polytropic (d/dt of T V^(n-1) = 0) or heat exchange with the wall
  (m cv dT/dt = -p dV/dt - m cv (T - T_ambient) / tau), and ideal gas p = m R T / V;
* three energy integrals (work F dL, heat lost, friction work) carried as extra ODE states.

Derivatives come from a different route than pamkit's: pamkit differentiates the closure
implicitly at fixed L; here the constrained braid is parametrised by D itself (Lm(D) from the
fibre, L(D) = Lm(D) + 2 LL(D)) and every d/dL is (d/dD) / (dL/dD).

Integration is ``scipy.integrate.solve_ivp`` piece by piece between the corners of the
piecewise-linear elongation (where the rate jumps), as pamkit's simulator restarts CVODES
there. The default method is LSODA: the temperature ODE is not stiff here (its fastest rate
is 1/tau ~ 0.2 1/s against steps of ~0.1-1 s), so LSODA runs its Adams methods at up to order
12, which is what rtol ~ 1e-11 wants, and it steps in compiled ODEPACK code. 'Radau' and 'BDF'
are pure-Python steppers of order <= 5 with finite-difference Jacobians: several times slower
at these tolerances for no gain (``method=`` selects them for comparison).

The hot path (one right-hand side) uses the ``math`` module on scalars, which is several
times faster than NumPy on 1-element data; the timing against pamkit is meant to be fair.

Usage::

    ref = ReferenceMuscle(build=dict(...), initial_length_m=0.167, initial_gauge_pressure_Pa=236.63e3,
                          gas=dict(process="heat_transfer", heat_transfer_time_constant_s=5.0))
    out = ref.simulate(time_s, elongation_m, rtol=1e-11, atol_K=1e-11, atol_J=1e-11)
    out["force_N"], out["gauge_pressure_Pa"], out["temperature_K"], ...
"""

from __future__ import annotations

import math

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

#: PAM 2 of table 3.4 / table C.4, SI units (the keys of pamkit.MuscleBuild).
DEFAULT_BUILD = {
    "length_m": 0.225,
    "diameter_m": 0.020,
    "bladder_diameter_m": 0.01545,
    "bladder_thickness_m": 0.254e-3,
    "fiber_count": 216.0,
    "fiber_revolutions": 2.0,
    "fiber_thickness_m": 0.254e-3,
    "end_diameter_m": 0.013,
    "cone_generator_m": 0.0095,
    "end_zone_m": 0.0,
    "series_compliance_m_per_N": 0.0,
}

#: Table C.4 friction; sharpness Kf of eq. 3.1.21 (keys of pamkit.FrictionParams).
DEFAULT_FRICTION = {
    "fiber_fiber_coefficient": 0.2,
    "fiber_bladder_coefficient": 0.2,
    "sharpness_s_per_m": 1.0,
    "fiber_width_m": 0.254e-3,
    "contact_length_m": 0.254e-3,
}

#: Air and surroundings (keys of pamkit.GasParams; process is "polytropic" or "heat_transfer").
DEFAULT_GAS = {
    "gas_constant_J_per_kgK": 287.0,
    "heat_capacity_ratio": 1.4,
    "atmospheric_pressure_Pa": 101e3,
    "ambient_temperature_K": 296.0,
    "polytropic_index": 1.0,
    "heat_transfer_time_constant_s": 10.0,
    "process": "polytropic",
}

# Eqs. 3.1.12-3.1.13 as printed, in kPa, highest power first (eps^6 ... eps^0). The operator
# lost before 19462 eps^4 in eq. 3.1.13 is taken as "+".
_SIGMA_LONG_KPA = (-2018400.0, -1553000.0, -438900.0, -52700.0, -3700.0, 0.0, 0.0)
_SIGMA_HOOP_KPA = (11166.0, -24717.0, 19462.0, -4759.0, -1415.0, 2046.0, -81.0)

#: Bladder law in Pa, highest power first.
THESIS_BLADDER = {
    "longitudinal_Pa": tuple(1e3 * c for c in _SIGMA_LONG_KPA),
    "hoop_Pa": tuple(1e3 * c for c in _SIGMA_HOOP_KPA),
}


def _horner(coefficients_high_first, x):
    value = 0.0
    for c in coefficients_high_first:
        value = value * x + c
    return value


def _merge(defaults, given, what):
    out = dict(defaults)
    for key, value in (given or {}).items():
        if key not in defaults:
            raise KeyError(f"{what} has no field {key!r}")
        out[key] = value
    return out


def _corner(previous_rate, rate):
    """True where the elongation rate changes by more than rounding (as pamkit decides)."""
    return abs(rate - previous_rate) > 1e-9 * max(abs(rate), abs(previous_rate))


class ReferenceMuscle:
    """The muscle model of pamkit re-derived in Python. SI units throughout.

    :param build: dict of pamkit.MuscleBuild fields (missing ones take the table C.4 defaults)
    :param initial_length_m: muscle length at zero elongation [m]
    :param initial_gauge_pressure_Pa: gauge pressure there [Pa]; the gas starts at ambient temperature
    :param friction: dict of pamkit.FrictionParams fields
    :param gas: dict of pamkit.GasParams fields, ``process`` a string
    :param bladder: dict with ``longitudinal_Pa`` and ``hoop_Pa``, polynomial coefficients in Pa,
        highest power first; None for the thesis law, ``"none"`` for no bladder stress
    """

    def __init__(
        self,
        build=None,
        initial_length_m=0.167,
        initial_gauge_pressure_Pa=236.63e3,
        friction=None,
        gas=None,
        bladder=None,
    ):
        b = _merge(DEFAULT_BUILD, build, "build")
        if b["end_zone_m"] != 0.0:
            raise ValueError("the reference is the thesis's muscle, its ends cones: it has no flat flanges' end zones")
        if b["series_compliance_m_per_N"] != 0.0:
            raise ValueError(
                "the reference is a sealed test's ODE, its muscle held at the crosshead: nothing in series"
            )
        f = _merge(DEFAULT_FRICTION, friction, "friction")
        g = _merge(DEFAULT_GAS, gas, "gas")
        if g["process"] not in ("polytropic", "heat_transfer"):
            raise ValueError(f"gas process must be 'polytropic' or 'heat_transfer', got {g['process']!r}")
        if bladder is None:
            bladder = THESIS_BLADDER
        elif bladder == "none":
            bladder = {"longitudinal_Pa": (0.0,), "hoop_Pa": (0.0,)}
        self.build, self.friction, self.gas = b, f, g
        self.sigma_long = tuple(float(c) for c in bladder["longitudinal_Pa"])
        self.sigma_hoop = tuple(float(c) for c in bladder["hoop_Pa"])

        self.n = float(b["fiber_revolutions"])
        self.k = math.pi * self.n  # pi n: D = Lym sin(theta) / (pi n)
        self.d = float(b["end_diameter_m"])
        self.lz = float(b["cone_generator_m"])
        self.tb = float(b["bladder_thickness_m"])
        self.dbo = float(b["bladder_diameter_m"])
        d0 = float(b["diameter_m"])
        # Deflated build: cones at D0, the cylinder the rest; fibre length from eq. 3.1.11.
        self.lm0 = float(b["length_m"]) - 2.0 * self._cone_length(d0)
        self.lym = math.sqrt(self.lm0**2 + (self.k * d0) ** 2)
        self.v_rubber = math.pi * self.dbo * self.tb * self.lm0  # reference volume of the stress laws
        deflated_ring = (d0 / 2.0) ** 2 - (d0 / 2.0 - self.tb) ** 2
        self.v_wall = float(b["length_m"]) * math.pi * deflated_ring  # the bladder's rubber, conserved

        # Friction magnitude per pascal of gauge pressure (eqs. 3.1.19-3.1.24), times tanh(Kf v).
        N = float(b["fiber_count"])
        q = 2.0 * self.n * (N / 2.0) ** 2 - N / 2.0  # eq. 3.1.22, crossings
        w, z = f["fiber_width_m"], f["contact_length_m"]
        fiber_fiber = q * 2.0 * (w * z) * f["fiber_fiber_coefficient"]  # eqs. 3.1.19, 3.1.24
        fiber_bladder = 2.0 * f["fiber_bladder_coefficient"] * w * (self.lym * N - z * q / 2.0)  # eq. 3.1.23
        self.friction_per_Pa = fiber_fiber + fiber_bladder
        self.kf = float(f["sharpness_s_per_m"])

        self.R = float(g["gas_constant_J_per_kgK"])
        self.cv = self.R / (float(g["heat_capacity_ratio"]) - 1.0)
        self.p_atm = float(g["atmospheric_pressure_Pa"])
        self.t_amb = float(g["ambient_temperature_K"])
        self.n_poly = float(g["polytropic_index"])
        self.tau = float(g["heat_transfer_time_constant_s"])
        self.heat_transfer = g["process"] == "heat_transfer"

        self.length0 = float(initial_length_m)
        shape0 = self.shape(self.length0)
        self.v_gas0 = shape0["gas_volume"]
        self.mass = (self.p_atm + float(initial_gauge_pressure_Pa)) * self.v_gas0 / (self.R * self.t_amb)  # eq. 3.1.17

    # --- geometry ---------------------------------------------------------------------------
    def _cone_length(self, D):
        """Axial length LL of a cone of slant Lz joining diameters D and d."""
        if self.lz <= 0.0:
            return 0.0
        half = 0.5 * (D - self.d)
        return math.sqrt(max(self.lz * self.lz - half * half, 0.0))

    def diameter(self, L):
        """Braid diameter D [m] at length L: the root of the cone closure, by brentq."""
        k2, lym2 = self.k * self.k, self.lym * self.lym
        if self.lz <= 0.0:
            return math.sqrt((lym2 - L * L) / k2)
        d, lz = self.d, self.lz

        def closure(D):
            half = 0.5 * (D - d)
            lm = L - 2.0 * math.sqrt(max(lz * lz - half * half, 0.0))
            return k2 * D * D + lm * lm - lym2

        return brentq(closure, d, d + 2.0 * lz, xtol=1e-18, rtol=4 * np.finfo(float).eps, maxiter=200)

    def shape(self, L):
        """Shape and its L-derivatives at length L, as a dict (names of pamkit.MuscleShape)."""
        D = self.diameter(L)
        d, k2, pi = self.d, self.k * self.k, math.pi
        ll = self._cone_length(D)
        lm = L - 2.0 * ll
        # Along the braid's constraint, with D as the parameter:
        #   Lm(D) = sqrt(Lym^2 - (pi n D)^2)  ->  dLm/dD = -(pi n)^2 D / Lm
        #   LL(D) = sqrt(Lz^2 - ((D - d)/2)^2) -> dLL/dD = -(D - d) / (4 LL)
        #   L(D)  = Lm + 2 LL                  ->  dL/dD = dLm/dD + 2 dLL/dD,  d/dL = (d/dD) / (dL/dD)
        dlm_dD = -k2 * D / lm
        dll_dD = -(D - d) / (4.0 * ll) if self.lz > 0.0 else 0.0
        dL_dD = dlm_dD + 2.0 * dll_dD
        dD_dL = 1.0 / dL_dD
        # Eq. 3.1.1: two frusta of height LL and the cylinder.
        frustum = (D * D + d * d + d * D) / 4.0
        v_total = (2.0 / 3.0) * pi * ll * frustum + pi * D * D / 4.0 * lm
        dvt_dD = (
            (2.0 / 3.0) * pi * (dll_dD * frustum + ll * (2.0 * D + d) / 4.0)
            + pi * D / 2.0 * lm
            + pi * D * D / 4.0 * dlm_dD
        )
        # The rubber is incompressible: its volume is eq. 3.1.3's tube (length L, outer diameter
        # D, wall tb) on the deflated build, at every length.
        v_bladder = self.v_wall
        dvb_dL = 0.0
        dvt_dL = dvt_dD * dD_dL
        return {
            "length": L,
            "diameter": D,
            "cylinder_length": lm,
            "cone_length": ll,
            "braid_angle": math.atan2(self.k * D, lm),
            "total_volume": v_total,
            "bladder_volume": v_bladder,
            "gas_volume": v_total - v_bladder,
            "d_diameter": dD_dL,
            "d_cylinder_length": dlm_dD * dD_dL,
            "d_total_volume": dvt_dL,
            "d_bladder_volume": dvb_dL,
            "d_gas_volume": dvt_dL - dvb_dL,
        }

    # --- the model at one instant -------------------------------------------------------------
    def evaluate(self, L, velocity, T):
        """Forces, pressure and rates at length L [m], rate dL/dt [m/s], gas temperature T [K]."""
        s = self.shape(L)
        V, dV = s["gas_volume"], s["d_gas_volume"]
        v_rate = dV * velocity  # dV_gas/dt
        p = self.mass * self.R * T / V  # eq. 3.1.17
        mcv = self.mass * self.cv
        if self.heat_transfer:
            q_loss = mcv * (T - self.t_amb) / self.tau
            T_rate = -(p * v_rate + q_loss) / mcv
        else:
            T_rate = -(self.n_poly - 1.0) * T * v_rate / V  # T V^(n-1) constant, eq. 3.1.18
            q_loss = -(mcv * T_rate + p * v_rate)  # first law: what the wall must take
        f_pressure = -p * dV + self.p_atm * s["d_total_volume"]
        eps_l = s["cylinder_length"] / self.lm0 - 1.0
        eps_h = s["diameter"] / self.dbo - 1.0
        f_bladder = self.v_rubber * (
            _horner(self.sigma_long, eps_l) * s["d_cylinder_length"] / self.lm0
            + _horner(self.sigma_hoop, eps_h) * s["d_diameter"] / self.dbo
        )
        f_friction = self.friction_per_Pa * max(p - self.p_atm, 0.0) * math.tanh(self.kf * velocity)
        return {
            "shape": s,
            "absolute_pressure_Pa": p,
            "gauge_pressure_Pa": p - self.p_atm,
            "temperature_K": T,
            "temperature_rate_K_per_s": T_rate,
            "heat_loss_rate_W": q_loss,
            "force_pressure_N": f_pressure,
            "force_bladder_N": f_bladder,
            "friction_force_N": f_friction,
            "force_N": f_pressure + f_bladder + f_friction,
        }

    # --- simulation -------------------------------------------------------------------------
    def simulate(self, time_s, elongation_m, rtol=1e-11, atol_K=1e-11, atol_J=1e-11, method="LSODA"):
        """Integrates along a piecewise-linear elongation history; outputs at its samples.

        The friction at a sample uses the rate of the segment that ends there (of the first one
        at t0), as pamkit does. Returns a dict of arrays (the names of pamkit.SimulationResult)
        and ``nfev``, the right-hand-side evaluations solve_ivp made.
        """
        t = np.asarray(time_s, dtype=float)
        e = np.asarray(elongation_m, dtype=float)
        if t.ndim != 1 or t.shape != e.shape or t.size < 2 or not np.all(np.diff(t) > 0):
            raise ValueError("time_s and elongation_m must be 1-D, the same size (>= 2), time increasing")
        rates = np.diff(e) / np.diff(t)
        atol = [atol_K, atol_J, atol_J, atol_J]
        columns = {
            name: np.empty(t.size)
            for name in (
                "length_m",
                "force_N",
                "friction_force_N",
                "gauge_pressure_Pa",
                "temperature_K",
                "gas_volume_m3",
                "braid_angle_rad",
                "diameter_m",
                "work_J",
                "heat_lost_J",
                "friction_dissipated_J",
            )
        }

        def record(i, rate, y):
            L = self.length0 + e[i]
            out = self.evaluate(L, rate, y[0])
            columns["length_m"][i] = L
            columns["force_N"][i] = out["force_N"]
            columns["friction_force_N"][i] = out["friction_force_N"]
            columns["gauge_pressure_Pa"][i] = out["gauge_pressure_Pa"]
            columns["temperature_K"][i] = y[0]
            columns["gas_volume_m3"][i] = out["shape"]["gas_volume"]
            columns["braid_angle_rad"][i] = out["shape"]["braid_angle"]
            columns["diameter_m"][i] = out["shape"]["diameter"]
            columns["work_J"][i], columns["heat_lost_J"][i], columns["friction_dissipated_J"][i] = y[1], y[2], y[3]

        y = np.array([self.t_amb, 0.0, 0.0, 0.0])
        record(0, rates[0], y)
        nfev = 0
        k = 0
        while k + 1 < t.size:
            end = k + 1
            while end + 1 < t.size and not _corner(rates[k], rates[end]):
                end += 1
            rate, t_start, L_start = rates[k], t[k], self.length0 + e[k]

            def rhs(time, state, rate=rate, t_start=t_start, L_start=L_start):
                out = self.evaluate(L_start + rate * (time - t_start), rate, state[0])
                return (
                    out["temperature_rate_K_per_s"],
                    out["force_N"] * rate,
                    out["heat_loss_rate_W"],
                    out["friction_force_N"] * rate,
                )

            sol = solve_ivp(rhs, (t[k], t[end]), y, method=method, t_eval=t[k + 1 : end + 1], rtol=rtol, atol=atol)
            if not sol.success:
                raise RuntimeError(f"solve_ivp ({method}) failed on [{t[k]}, {t[end]}] s: {sol.message}")
            nfev += sol.nfev
            for j, i in enumerate(range(k + 1, end + 1)):
                record(i, rate, sol.y[:, j])
            y = sol.y[:, -1].copy()
            k = end
        result = {"time_s": t.copy(), "elongation_m": e.copy(), **columns}
        result["nfev"] = nfev
        return result


def thesis_protocol(max_elongation_m, speed_m_per_s=2.5e-3, cycles=10, sample_period_s=0.1):
    """Triangular stretch cycles at constant speed, sampled every period (section 3.2.1);
    the same samples as pamkit.thesis_protocol without holds."""
    t, e = [0.0], [0.0]
    ramp = max_elongation_m / speed_m_per_s

    def segment(duration, target):
        t0, e0 = t[-1], e[-1]
        steps = math.ceil(duration / sample_period_s - 1e-9)
        for i in range(1, steps + 1):
            f = 1.0 if i == steps else i * sample_period_s / duration
            t.append(t0 + f * duration)
            e.append(e0 + f * (target - e0))

    for _ in range(cycles):
        segment(ramp, max_elongation_m)
        segment(ramp, 0.0)
    return np.array(t), np.array(e)
