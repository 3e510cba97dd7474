"""An isometric force map of a braided muscle from physics derived afresh, for the static-table
diagnosis. Nothing here imports pamkit.

Gaylord's cylinder of inextensible fibres (length b, n turns, flat ends): D = b sin(theta) / (pi n),
L = b cos(theta), V = pi D^2 L / 4, so the gas force is -p dV/dL = p (pi D0^2 / (4 sin^2 theta0))
(3 cos^2 theta - 1). The wall is a thin incompressible neo-Hookean membrane of modulus mu and
thickness t on the braid, moulded at diameter D0 / prestretch: its energy per deflated area is
mu t / 2 (l_h^2 + l_l^2 + 1/(l_h l_l)^2 - 3) and its force the derivative of the energy over
the muscle's length (by complex-step differentiation here, not the closed form pamkit uses). A
braid cannot push: the force is max(F, 0), sharply. The load cell adds white noise and
quantisation.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np


def gaylord_membrane_force(
    length_m, gauge_Pa, *, rest_length_m, diameter_m, braid_angle_deg, shear_modulus_Pa, thickness_m, prestretch
):
    """Force [N] of the muscle held at `length_m` with supplied gauge pressure (tension > 0)."""
    theta0 = math.radians(braid_angle_deg)
    fiber = rest_length_m / math.cos(theta0)
    radius_per_sine = diameter_m / math.sin(theta0)  # D = (D0 / sin theta0) sin theta

    def energy(length):  # membrane energy [J]; works on complex lengths for the complex step
        cos = length / fiber
        diameter = radius_per_sine * np.sqrt(1 - cos * cos)
        hoop = prestretch * diameter / diameter_m
        axial = length / rest_length_m
        area = math.pi * (diameter_m / prestretch) * rest_length_m
        return 0.5 * shear_modulus_Pa * thickness_m * area * (hoop**2 + axial**2 + 1 / (hoop * axial) ** 2 - 3)

    length = np.asarray(length_m, dtype=float)
    cos = length / fiber
    gas = gauge_Pa * math.pi * diameter_m**2 / (4 * math.sin(theta0) ** 2) * (3 * cos**2 - 1)
    step = 1e-20
    membrane = np.imag(energy(length + 1j * step)) / step  # dU/dL: resists contraction
    return np.maximum(gas + membrane, 0.0)


def write_map(
    folder: Path,
    *,
    lengths_m,
    pressures_kPa,
    seed: int,
    noise_N: float = 1.0,
    step_N: float = 0.1,
    calibrate: bool = True,
    cell_quadratic_per_N: float = 0.0,
    **truth,
) -> Path:
    """Writes an isometric map (TOML + CSV) of a muscle with `truth` (gaylord_membrane_force's
    keywords) and returns the TOML's path. The TOML declares the build as a datasheet would and,
    with `calibrate`, the braid angle, modulus and membrane diameter unknown. A nonlinear load
    cell reads F + `cell_quadratic_per_N` F^2 (a cause no catalog effect has)."""
    rng = np.random.default_rng(seed)
    folder.mkdir(parents=True, exist_ok=True)
    rows = []
    for length in lengths_m:
        for pressure in pressures_kPa:
            force = float(gaylord_membrane_force(length, pressure * 1e3, **truth))
            force += cell_quadratic_per_N * force**2
            if force > 0:
                force += rng.normal(0, noise_N)
            rows.append((length, pressure, max(round(force / step_N) * step_N, 0.0)))
    with (folder / "map.csv").open("w") as handle:
        handle.write("length_m,pressure_kPa,force_N\n")
        handle.writelines(f"{length:.4f},{pressure:.1f},{force:.1f}\n" for length, pressure, force in rows)
    diameter = truth["diameter_m"]
    unknowns = (
        f"[calibrate]\nbraid_angle_deg = [10.0, 45.0]\nbladder_diameter_m = [{0.8 * diameter}, {diameter}]\n"
        "bladder.shear_modulus_Pa = [1.0e4, 2.0e7]\n"
        if calibrate
        else ""
    )
    (folder / "map.toml").write_text(
        f"""[muscle]
length_m = {truth["rest_length_m"]}
diameter_m = {diameter}
bladder_diameter_m = {diameter / truth["prestretch"] if not calibrate else 0.97 * diameter}
bladder_thickness_m = {truth["thickness_m"]}
fiber_count = 100
braid_angle_deg = {truth["braid_angle_deg"] if not calibrate else 20.0}
fiber_thickness_m = 0.0
end_diameter_m = {diameter / 2}
cone_generator_m = 0.0

[bladder]
law = "neo_hookean"
shear_modulus_Pa = {truth["shear_modulus_Pa"] if not calibrate else 1.0e6}

{unknowns}
[test]
kind = "isometric_map"
data = "map.csv"
"""
    )
    return folder / "map.toml"


def isotonic_length(gauge_Pa, load_N, branch, *, hysteresis, **truth):
    """The length at which the muscle carries `load_N` [m]: Gaylord's force less a friction of
    `hysteresis` x p pi D^2 / 4 that resists the motion the pressure drives (branch +1 while the
    pressure rises). The force falls monotonically as the muscle shortens here, so the root is
    unique; SciPy's brentq finds it."""
    from scipy.optimize import brentq

    theta0 = math.radians(truth["braid_angle_deg"])
    fiber = truth["rest_length_m"] / math.cos(theta0)
    radius_per_sine = truth["diameter_m"] / math.sin(theta0)

    def imbalance(length):
        diameter = radius_per_sine * math.sqrt(1 - (length / fiber) ** 2)
        friction = hysteresis * gauge_Pa * math.pi * diameter**2 / 4
        return float(gaylord_membrane_force(length, gauge_Pa, **truth)) - branch * friction - load_N

    return brentq(imbalance, 0.6 * truth["rest_length_m"], 0.999 * fiber, xtol=1e-9)


def write_isotonic(
    folder: Path,
    *,
    sweeps,
    load_N: float,
    hysteresis: float,
    seed: int,
    noise_m: float = 0.1e-3,
    pressure_offset_kPa: float = 0.0,
    **truth,
) -> Path:
    """Writes an isotonic test (TOML + CSV): `sweeps` lists of settled pressures [kPa] (each up,
    then down), the length measured with `noise_m` of noise in 0.01 mm steps. The transducer
    reads the pressure plus `pressure_offset_kPa`, and nothing below 0 kPa (its display clips, as
    a lab rig's may); the TOML then declares that range. The TOML
    leaves the braid angle, the membrane and the load unknown."""
    rng = np.random.default_rng(seed)
    folder.mkdir(parents=True, exist_ok=True)
    rows, previous = [], None
    branch = 1.0
    for sweep in sweeps:
        for pressure in sweep:
            if previous is not None and pressure != previous:
                branch = 1.0 if pressure > previous else -1.0
            previous = pressure
            length = isotonic_length(pressure * 1e3, load_N, branch, hysteresis=hysteresis, **truth)
            reading = max(pressure + pressure_offset_kPa, 0.0)
            rows.append((reading, round((length + rng.normal(0, noise_m)) * 1e5) / 1e5))
    with (folder / "isotonic.csv").open("w") as handle:
        handle.write("pressure_kPa,length_m\n")
        handle.writelines(f"{pressure:.1f},{length:.5f}\n" for pressure, length in rows)
    diameter = truth["diameter_m"]
    (folder / "isotonic.toml").write_text(
        f"""[muscle]
length_m = {truth["rest_length_m"]}
diameter_m = {diameter}
bladder_diameter_m = {0.97 * diameter}
bladder_thickness_m = {truth["thickness_m"]}
fiber_count = 100
braid_angle_deg = 20.0
fiber_thickness_m = 0.0
end_diameter_m = {diameter / 2}
cone_generator_m = 0.0

[bladder]
law = "neo_hookean"
shear_modulus_Pa = 1.0e6

[calibrate]
braid_angle_deg = [10.0, 45.0]
bladder_diameter_m = [{0.8 * diameter}, {diameter}]
bladder.shear_modulus_Pa = [1.0e4, 2.0e7]
load_N = [1.0, 500.0]

[test]
kind = "isotonic"
data = "isotonic.csv"
{"pressure_range_kPa = [0.0, 1000.0]" if pressure_offset_kPa else ""}
"""
    )
    return folder / "isotonic.toml"
