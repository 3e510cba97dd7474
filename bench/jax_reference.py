"""The sealed muscle in JAX + diffrax, for the sweep bench's side-by-side (bench/bench_sweep.py --jax).

The same physics as bench/scipy_reference.py (read its docstring for the equations and their
sources), written again with jax.numpy so that diffrax's Tsit5 can integrate it jit-compiled and
vectorised (jax.vmap) over many runs at once. Like scipy_reference.py it shares no code with
pamkit and does not import it; only the bladder law is fixed to the thesis's polynomials.

What differs from scipy_reference.py, each for the sake of jit and vmap:

* the braid closure (pi n D)^2 + (L - 2 LL(D))^2 = Lym^2 is solved by a fixed number of Newton
  iterations instead of brentq. The closure is increasing and convex in D, and the start
  D_a = sqrt(Lym^2 - (L - 2 Lz)^2) / (pi n) (the cones at their longest) lies on its positive
  side, so Newton converges monotonically from there; NEWTON_ITERATIONS iterations reach
  rounding on the bench's lengths (checked against pamkit by the bench);
* one diffeqsolve spans the whole trajectory: the corners (rate jumps above a share of the
  largest rate, pamkit's SimulatorConfig.corner_threshold) are diffrax's ``jump_ts``, where it
  ends a step and restarts, as pamkit and scipy_reference.py restart their integrators there.

Runs differ by their per-run parameters (``gauge_pressure_Pa`` and ``fiber_revolutions``, the
two a pamkit sweep over inflation pressure and braid angle changes); everything else is shared.
Needs jax, jaxlib and diffrax (bench/requirements-jax.txt), 64-bit floats switched on.
"""

from __future__ import annotations

import diffrax
import jax
import jax.numpy as jnp
import numpy as np

jax.config.update("jax_enable_x64", True)

NEWTON_ITERATIONS = 12

# Eqs. 3.1.12-3.1.13 in Pa, highest power first (scipy_reference.THESIS_BLADDER, "+" before 19462 eps^4).
SIGMA_LONG_PA = tuple(1e3 * c for c in (-2018400.0, -1553000.0, -438900.0, -52700.0, -3700.0, 0.0, 0.0))
SIGMA_HOOP_PA = tuple(1e3 * c for c in (11166.0, -24717.0, 19462.0, -4759.0, -1415.0, 2046.0, -81.0))


def _horner(coefficients_high_first, x):
    value = jnp.zeros_like(x)
    for c in coefficients_high_first:
        value = value * x + c
    return value


def corner_times(time_s, elongation_m, threshold=0.2):
    """Times where the elongation rate jumps by more than `threshold` of its largest value."""
    rate = np.diff(elongation_m) / np.diff(time_s)
    jump = np.abs(np.diff(rate)) > threshold * np.max(np.abs(rate))
    return np.asarray(time_s)[1:-1][jump]


class JaxMuscle:
    """Sealed-muscle runs along one prescribed elongation, vectorised over per-run parameters.

    :param build: dict of pamkit.MuscleBuild fields (all nine)
    :param friction: dict of pamkit.FrictionParams fields
    :param gas: dict of pamkit.GasParams fields, ``process`` "polytropic" or "heat_transfer"
    :param initial_length_m: muscle length at zero elongation [m] (the same for every run)
    :param time_s, elongation_m: the prescribed elongation, linear between samples
    """

    def __init__(self, build, friction, gas, initial_length_m, time_s, elongation_m):
        self.build, self.friction, self.gas = dict(build), dict(friction), dict(gas)
        if self.gas["process"] not in ("polytropic", "heat_transfer"):
            raise ValueError(f"gas process must be 'polytropic' or 'heat_transfer', got {self.gas['process']!r}")
        self.length0 = float(initial_length_m)
        self.time_s = jnp.asarray(time_s, dtype=float)
        self.elongation_m = jnp.asarray(elongation_m, dtype=float)
        self.rates = jnp.diff(self.elongation_m) / jnp.diff(self.time_s)
        self.jump_ts = jnp.asarray(corner_times(np.asarray(time_s), np.asarray(elongation_m)))

    # --- per-run constants -------------------------------------------------------------------
    def constants(self, gauge_pressure_Pa, fiber_revolutions):
        """What one run needs, from its inflation pressure and braid revolutions (jnp scalars)."""
        b, f, g = self.build, self.friction, self.gas
        c = {"k": jnp.pi * fiber_revolutions, "d": b["end_diameter_m"], "lz": b["cone_generator_m"]}
        d0 = b["diameter_m"]
        c["lm0"] = b["length_m"] - 2.0 * self._cone_length(c, d0)
        c["lym"] = jnp.sqrt(c["lm0"] ** 2 + (c["k"] * d0) ** 2)
        c["v_rubber"] = jnp.pi * b["bladder_diameter_m"] * b["bladder_thickness_m"] * c["lm0"]
        ring = (d0 / 2.0) ** 2 - (d0 / 2.0 - b["bladder_thickness_m"]) ** 2
        c["v_wall"] = b["length_m"] * jnp.pi * ring
        N = b["fiber_count"]
        q = 2.0 * fiber_revolutions * (N / 2.0) ** 2 - N / 2.0  # eq. 3.1.22
        w, z = f["fiber_width_m"], f["contact_length_m"]
        fiber_fiber = q * 2.0 * (w * z) * f["fiber_fiber_coefficient"]
        fiber_bladder = 2.0 * f["fiber_bladder_coefficient"] * w * (c["lym"] * N - z * q / 2.0)
        c["friction_per_Pa"] = fiber_fiber + fiber_bladder
        v_gas0 = self.shape(c, jnp.asarray(self.length0))["gas_volume"]
        c["mass"] = (
            (g["atmospheric_pressure_Pa"] + gauge_pressure_Pa)
            * v_gas0
            / (g["gas_constant_J_per_kgK"] * g["ambient_temperature_K"])
        )
        return c

    # --- geometry -------------------------------------------------------------------------------
    @staticmethod
    def _cone_length(c, D):
        half = 0.5 * (D - c["d"])
        return jnp.sqrt(jnp.maximum(c["lz"] ** 2 - half * half, 0.0))

    def diameter(self, c, L):
        k2, lym2, d, lz = c["k"] ** 2, c["lym"] ** 2, c["d"], c["lz"]
        upper = d + 2.0 * lz
        start = jnp.sqrt(jnp.maximum(lym2 - (L - 2.0 * lz) ** 2, 0.0) / k2)
        D = jnp.minimum(start, upper * (1.0 - 1e-12))

        def newton(_, D):
            half = 0.5 * (D - d)
            ll = jnp.sqrt(jnp.maximum(lz * lz - half * half, 1e-300))
            lm = L - 2.0 * ll
            closure = k2 * D * D + lm * lm - lym2
            slope = 2.0 * k2 * D + 2.0 * lm * (half / ll)  # d/dD: dLL/dD = -half / (2 LL)
            return D - closure / slope

        return jax.lax.fori_loop(0, NEWTON_ITERATIONS, newton, D)

    def shape(self, c, L):
        D = self.diameter(c, L)
        d, k2 = c["d"], c["k"] ** 2
        ll = self._cone_length(c, D)
        lm = L - 2.0 * ll
        dlm_dD = -k2 * D / lm
        dll_dD = -(D - d) / (4.0 * ll)
        dD_dL = 1.0 / (dlm_dD + 2.0 * dll_dD)
        frustum = (D * D + d * d + d * D) / 4.0
        v_total = (2.0 / 3.0) * jnp.pi * ll * frustum + jnp.pi * D * D / 4.0 * lm
        dvt_dD = (
            (2.0 / 3.0) * jnp.pi * (dll_dD * frustum + ll * (2.0 * D + d) / 4.0)
            + jnp.pi * D / 2.0 * lm
            + jnp.pi * D * D / 4.0 * dlm_dD
        )
        dvt_dL = dvt_dD * dD_dL
        return {
            "diameter": D,
            "cylinder_length": lm,
            "gas_volume": v_total - c["v_wall"],
            "d_diameter": dD_dL,
            "d_cylinder_length": dlm_dD * dD_dL,
            "d_total_volume": dvt_dL,
            "d_gas_volume": dvt_dL,  # the rubber's volume is conserved
        }

    # --- the model at one instant -------------------------------------------------------------
    def evaluate(self, c, L, velocity, T):
        """(force [N], gauge pressure [Pa], dT/dt, heat loss rate [W], friction force [N])."""
        g, b = self.gas, self.build
        R = g["gas_constant_J_per_kgK"]
        cv = R / (g["heat_capacity_ratio"] - 1.0)
        s = self.shape(c, L)
        V, dV = s["gas_volume"], s["d_gas_volume"]
        v_rate = dV * velocity
        p = c["mass"] * R * T / V
        mcv = c["mass"] * cv
        if g["process"] == "heat_transfer":
            q_loss = mcv * (T - g["ambient_temperature_K"]) / g["heat_transfer_time_constant_s"]
            T_rate = -(p * v_rate + q_loss) / mcv
        else:
            T_rate = -(g["polytropic_index"] - 1.0) * T * v_rate / V
            q_loss = -(mcv * T_rate + p * v_rate)
        f_pressure = -p * dV + g["atmospheric_pressure_Pa"] * s["d_total_volume"]
        lm0, dbo = c["lm0"], b["bladder_diameter_m"]
        eps_l = s["cylinder_length"] / lm0 - 1.0
        eps_h = s["diameter"] / dbo - 1.0
        f_bladder = c["v_rubber"] * (
            _horner(SIGMA_LONG_PA, eps_l) * s["d_cylinder_length"] / lm0
            + _horner(SIGMA_HOOP_PA, eps_h) * s["d_diameter"] / dbo
        )
        gauge = p - g["atmospheric_pressure_Pa"]
        f_friction = (
            c["friction_per_Pa"] * jnp.maximum(gauge, 0.0) * jnp.tanh(self.friction["sharpness_s_per_m"] * velocity)
        )
        return f_pressure + f_bladder + f_friction, gauge, T_rate, q_loss, f_friction

    # --- one run -------------------------------------------------------------------------------
    def segment(self, t):
        """The segment [t_k, t_k+1] that holds time t."""
        k = jnp.searchsorted(self.time_s, t, side="right") - 1
        return jnp.clip(k, 0, self.rates.size - 1)

    def run(self, gauge_pressure_Pa, fiber_revolutions, rtol, atol_K, atol_J):
        """Force [N] and gauge pressure [Pa] at every sample of one run (jit- and vmap-able)."""
        c = self.constants(gauge_pressure_Pa, fiber_revolutions)

        def rhs(t, y, _):
            k = self.segment(t)
            rate = self.rates[k]
            L = self.length0 + self.elongation_m[k] + rate * (t - self.time_s[k])
            force, _, T_rate, q_loss, friction = self.evaluate(c, L, rate, y[0])
            return jnp.stack([T_rate, force * rate, q_loss, friction * rate])

        y0 = jnp.array([self.gas["ambient_temperature_K"], 0.0, 0.0, 0.0])
        controller = diffrax.PIDController(
            rtol=rtol, atol=jnp.array([atol_K, atol_J, atol_J, atol_J]), jump_ts=self.jump_ts
        )
        solution = diffrax.diffeqsolve(
            diffrax.ODETerm(rhs),
            diffrax.Tsit5(),
            t0=self.time_s[0],
            t1=self.time_s[-1],
            dt0=None,
            y0=y0,
            saveat=diffrax.SaveAt(ts=self.time_s),
            stepsize_controller=controller,
            max_steps=100_000,
        )
        # Sample k's friction uses the rate of the segment that ends there (segment 0 at t0), as pamkit's.
        sample_rates = jnp.concatenate([self.rates[:1], self.rates])
        lengths = self.length0 + self.elongation_m
        force, gauge, *_ = jax.vmap(lambda L, v, T: self.evaluate(c, L, v, T))(lengths, sample_rates, solution.ys[:, 0])
        return force, gauge

    def batch(self, rtol=1e-8, atol_K=1e-8, atol_J=1e6):
        """A jit-compiled function of (gauge pressures, fiber revolutions), one entry per run,
        returning (force, gauge pressure), one row per run. atol_J's default leaves the energy
        integrals out of the error test, as pamkit's SimulatorConfig does."""
        return jax.jit(jax.vmap(lambda p, n: self.run(p, n, rtol, atol_K, atol_J)))
