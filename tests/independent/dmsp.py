"""A Festo-type fluidic muscle (fibres embedded in the membrane, press-fitted flat flanges) and
the two settled characterisations a lab runs on it, from physics derived afresh. Nothing here
imports pamkit.

The braid: between two end zones of length e that keep their deflated shape, a cylinder of
inextensible fibres of length b = (L0 - 2e) / cos(theta0): cos(theta) = (L - 2e) / b,
D = D0 sin(theta) / sin(theta0). The gas force is -p dV/dL of V = pi D^2 (L - 2e) / 4, here by
complex-step differentiation of the volume (not the closed form). The braid cannot push: the
force is max(F, 0), sharply.

Friction with memory: a Prandtl-Ishlinskii operator of uniform density, in 400 elastic-perfectly
plastic elements whose break-away displacements sit at the midpoints of (0, delta] (pamkit's
16: the discretisations differ). Each follows the braid's length with stiffness
(f / n) / delta_i until it holds f / n.

The rig: an isometric test holds the muscle's ends at a length; below its rest length it is slack
at low pressure, and its free braid contracts as the pressure rises (zero force: elastic force and
friction balance) until it pulls taut, and lengthens again once it goes slack on venting. An
isotonic test hangs a load on it; each settled step moves the length to where the force carries
the load, from the last one. The load cell reads 1 N of noise in 0.1 N steps; the laser, 0.1 mm
in 0.01 mm steps.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from scipy.optimize import brentq

PA_PER_KPA = 1e3  # the files' pressures are in kPa, the physics' in Pa


@dataclass
class DmspTruth:
    rest_length_m: float = 0.25
    diameter_m: float = 0.01
    braid_angle_deg: float = 22.0
    end_zone_m: float = 0.008
    slip_force_N: float = 150.0
    slip_distance_m: float = 0.02


class Muscle:
    """The elastic force of the muscle at a braid length and gauge pressure."""

    def __init__(self, t: DmspTruth):
        self.t = t
        self.theta0 = math.radians(t.braid_angle_deg)
        self.fiber = (t.rest_length_m - 2 * t.end_zone_m) / math.cos(self.theta0)
        self.longest = self.fiber + 2 * t.end_zone_m

    def volume(self, length):
        active = length - 2 * self.t.end_zone_m
        cos = active / self.fiber
        diameter = self.t.diameter_m * np.sqrt(1 - cos * cos) / math.sin(self.theta0)
        return math.pi * diameter**2 * active / 4

    def force(self, length, gauge_Pa):
        """Tension [N] of the gas (no friction, before the slack) at `length` [m]."""
        step = 1e-20
        return -gauge_Pa * float(np.imag(self.volume(length + 1j * step)) / step)


class Slip:
    """Maxwell-slip elements: a Prandtl-Ishlinskii operator of uniform density."""

    def __init__(self, force_N: float, distance_m: float, elements: int = 400):
        self.limit = force_N / elements
        breakaway = distance_m * (np.arange(elements) + 0.5) / elements
        self.stiffness = self.limit / breakaway
        self.held = np.zeros(elements)

    def after(self, displacement_m: float) -> float:
        return float(np.sum(np.clip(self.held + self.stiffness * displacement_m, -self.limit, self.limit)))

    def move(self, displacement_m: float) -> None:
        self.held = np.clip(self.held + self.stiffness * displacement_m, -self.limit, self.limit)


def _first_root(function, start: float, end: float, steps: int = 400) -> float | None:
    """The first zero of `function` from `start` towards `end`, by stepping and brentq."""
    previous, value = start, function(start)
    if value == 0:
        return start
    for x in np.linspace(start, end, steps + 1)[1:]:
        here = function(x)
        if (here > 0) != (value > 0) or here == 0:
            return brentq(function, min(previous, x), max(previous, x), xtol=1e-12)
        previous, value = x, here
    return None


def isometric_forces(truth: DmspTruth, lengths_m, gauge_pressures_Pa) -> np.ndarray:
    """The force [N] at each (held length [m], gauge pressure [Pa]) row in the order measured, from rest."""
    muscle, slip = Muscle(truth), Slip(truth.slip_force_N, truth.slip_distance_m)
    braid = truth.rest_length_m
    out = []
    for held, gauge in zip(lengths_m, gauge_pressures_Pa):

        def carried(x, gauge=gauge, start=braid):
            return muscle.force(x, gauge) + slip.after(x - start)

        taut = carried(held)
        if taut >= 0:
            slip.move(held - braid)
            braid = held
            out.append(taut)
            continue
        top = muscle.longest * (1 - 1e-9)
        free = _first_root(carried, held, top)
        free = top if free is None else free
        slip.move(free - braid)
        braid = free
        out.append(0.0)
    return np.array(out)


def isotonic_lengths(truth: DmspTruth, gauge_pressures_Pa, load_N: float) -> np.ndarray:
    """The settled length [m] at each gauge pressure [Pa] under `load_N`, from rest, in the order measured."""
    muscle, slip = Muscle(truth), Slip(truth.slip_force_N, truth.slip_distance_m)
    length = truth.rest_length_m
    shortest, longest = 0.5 * truth.rest_length_m, muscle.longest * (1 - 1e-9)
    out = []
    for gauge in gauge_pressures_Pa:

        def imbalance(x, gauge=gauge, start=length):
            return max(muscle.force(x, gauge) + slip.after(x - start), 0.0) - load_N

        here = imbalance(length)
        target = shortest if here > 0 else longest
        found = _first_root(imbalance, length, target, steps=2000)
        new = target if found is None else found
        slip.move(new - length)
        length = new
        out.append(length)
    return np.array(out)


def _muscle_section(truth: DmspTruth, calibrate: str) -> str:
    d = truth.diameter_m
    return f"""[muscle]
construction = "embedded"
length_m = {truth.rest_length_m}
diameter_m = {d}
bladder_diameter_m = {d}
bladder_thickness_m = {0.05 * d}
fiber_count = 100
braid_angle_deg = 20.0
fiber_thickness_m = 0.0
end_diameter_m = {d / 2}
cone_generator_m = 0.0
end_zone_m = {0.5 * d}

[bladder]
law = "none"

[calibrate]
braid_angle_deg = [10.0, 45.0]
end_zone_m = [0.0, {2 * d}]
{calibrate}"""


def write_dmsp_isometric(
    folder: Path, truth: DmspTruth, *, lengths_m, top_kPa: float, seed: int, noise_N: float = 1.0
) -> Path:
    """An isometric test (TOML + CSV, kind isometric_map): at each held length, the muscle from
    rest, the pressure stepped up to `top_kPa` and down to 0 twice, in 25 kPa steps. The TOML
    declares the build as a datasheet does, the braid angle and end zones unknown."""
    rng = np.random.default_rng(seed)
    folder.mkdir(parents=True, exist_ok=True)
    up = list(np.arange(0.0, top_kPa + 1e-9, 25.0))
    sweep = up + up[::-1][1:]
    rows = []
    for length in lengths_m:
        pressures = sweep + sweep[1:]
        forces = isometric_forces(truth, [length] * len(pressures), [PA_PER_KPA * p for p in pressures])
        for pressure, force in zip(pressures, forces):
            reading = force + rng.normal(0, noise_N) if force > 0 else 0.0
            rows.append((length, pressure, max(round(reading / 0.1) * 0.1, 0.0)))
    with (folder / "isometric.csv").open("w") as handle:
        handle.write("length_m,pressure_kPa,force_N\n")
        handle.writelines(f"{length:.4f},{pressure:.1f},{force:.1f}\n" for length, pressure, force in rows)
    (folder / "isometric.toml").write_text(
        _muscle_section(truth, "") + '\n[test]\nkind = "isometric_map"\ndata = "isometric.csv"\n'
    )
    return folder / "isometric.toml"


def write_dmsp_isotonic(
    folder: Path,
    truth: DmspTruth,
    *,
    load_N: float,
    top_kPa: float,
    sweeps: int,
    seed: int,
    bottom_kPa: float = 150.0,
    noise_m: float = 0.1e-3,
) -> Path:
    """An isotonic test (TOML + CSV): `sweeps` sweeps of settled steps from `bottom_kPa` to
    `top_kPa` and back in 25 kPa steps under `load_N` (hung on at the first step), the length by
    laser. Vented, a muscle with no membrane holds a load by its friction alone: the sweeps stay
    above `bottom_kPa`. The load is weighed: with it unknown, the force's scale, the load and the
    friction trade (the lengths tell W + f from W - f, not their scale)."""
    rng = np.random.default_rng(seed)
    folder.mkdir(parents=True, exist_ok=True)
    up = list(np.arange(bottom_kPa, top_kPa + 1e-9, 25.0))
    sweep = up + up[::-1][1:]
    pressures = sweep + sum((sweep[1:] for _ in range(sweeps - 1)), [])
    lengths = isotonic_lengths(truth, [PA_PER_KPA * p for p in pressures], load_N)
    with (folder / "isotonic.csv").open("w") as handle:
        handle.write("pressure_kPa,length_m\n")
        for pressure, length in zip(pressures, lengths):
            handle.write(f"{pressure:.1f},{round((length + rng.normal(0, noise_m)) * 1e5) / 1e5:.5f}\n")
    (folder / "isotonic.toml").write_text(
        _muscle_section(truth, "") + f'\n[test]\nkind = "isotonic"\ndata = "isotonic.csv"\nload_N = {load_N}\n'
    )
    return folder / "isotonic.toml"
