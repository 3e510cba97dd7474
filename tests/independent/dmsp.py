"""A Festo-type fluidic muscle (fibres embedded in the membrane, press-fitted flat flanges) and
the two settled characterisations a lab runs on it, from physics derived afresh. Nothing here
imports pamkit.

The braid: between two end zones of length e that keep their deflated shape, a cylinder of
inextensible fibres of length b = (L0 - 2e) / cos(theta0): cos(theta) = (L - 2e) / b,
D = D0 sin(theta) / sin(theta0). The gas force is -p dV/dL of V = pi D^2 (L - 2e) / 4, here by
complex-step differentiation of the volume (not the closed form). The braid cannot push: the
force is max(F, 0), sharply.

Friction with memory: Iwan's distributed-element model, springs of one stiffness whose sliders
break away at displacements spread evenly over (0, delta], so that from rest the friction follows
f (2 x / delta - (x / delta)^2) up to f: here 400 elastic-perfectly plastic elements, each
following the braid's length with stiffness 2 f / delta until it holds its share of f in
proportion to its break-away displacement (pamkit's 16 elements: the discretisations differ).

The rig: an isometric test holds the muscle's ends at a length; below its rest length it is slack
at low pressure, and its free braid contracts as the pressure rises (zero force: elastic force and
friction balance) until it pulls taut, and lengthens again once it goes slack on venting. An
isotonic test hangs a load on it; each settled step moves the length to where the force carries
the load, from the last one. What stretches in series with the braid (fittings, load cell, frame:
c per newton) puts a held muscle's braid where its force F(x) equals (held - x) / c, found by
brentq, and a loaded one c W longer. The load cell reads 1 N of noise in 0.1 N steps; the laser, 0.1 mm
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
    series_compliance_m_per_N: float = 0.0  # fittings, load cell and frame in series with the braid


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
    """Maxwell-slip elements: Iwan's model, one stiffness, break-away displacements spread evenly."""

    def __init__(self, force_N: float, distance_m: float, elements: int = 400):
        breakaway = distance_m * (np.arange(elements) + 0.5) / elements
        # Each element's share of the whole stiffness 2 f / delta, holding until it has moved its break-away.
        self.stiffness = np.full(elements, 2.0 * force_N / distance_m / elements)
        self.limit = self.stiffness * breakaway
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


def _series_place(carried, held: float, taut: float, compliance: float) -> float:
    """The braid's length x at which its force equals the series parts' (held - x) / c."""
    return brentq(lambda x: carried(x) - (held - x) / compliance, held - compliance * taut, held, xtol=1e-13)


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
            # Pulling, it stretches what is in series with it by c F: the braid lies that much short.
            c = truth.series_compliance_m_per_N
            place = held if c == 0 or taut == 0 else _series_place(carried, held, taut, c)
            out.append(carried(place))
            slip.move(place - braid)
            braid = place
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
    # The parts in series with the braid stretch under the load: the muscle is that much longer.
    return np.array(out) + truth.series_compliance_m_per_N * load_N


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
    folder: Path,
    truth: DmspTruth,
    *,
    lengths_m,
    top_kPa: float,
    seed: int,
    noise_N: float = 1.0,
    sweeps: int = 2,
    pressure_offset_kPa: float = 0.0,
    calibrate: str = "",
) -> Path:
    """An isometric test (TOML + CSV, kind isometric_map): at each held length, the muscle from
    rest, the pressure stepped up to `top_kPa` and down to 0 `sweeps` times, in 25 kPa steps. The
    transducer reads the pressure plus `pressure_offset_kPa`. The TOML declares the build as a
    datasheet does, the braid angle and end zones unknown, and the lines `calibrate` unknown too."""
    rng = np.random.default_rng(seed)
    folder.mkdir(parents=True, exist_ok=True)
    up = list(np.arange(0.0, top_kPa + 1e-9, 25.0))
    sweep = up + up[::-1][1:]
    rows = []
    for length in lengths_m:
        pressures = sweep + sum((sweep[1:] for _ in range(sweeps - 1)), [])
        forces = isometric_forces(truth, [length] * len(pressures), [PA_PER_KPA * p for p in pressures])
        for pressure, force in zip(pressures, forces):
            reading = force + rng.normal(0, noise_N) if force > 0 else 0.0
            rows.append((length, pressure + pressure_offset_kPa, max(round(reading / 0.1) * 0.1, 0.0)))
    with (folder / "isometric.csv").open("w") as handle:
        handle.write("length_m,pressure_kPa,force_N\n")
        handle.writelines(f"{length:.4f},{pressure:.1f},{force:.1f}\n" for length, pressure, force in rows)
    (folder / "isometric.toml").write_text(
        _muscle_section(truth, calibrate) + '\n[test]\nkind = "isometric_map"\ndata = "isometric.csv"\n'
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


def write_dmsp_cyclic(
    folder: Path,
    truth: DmspTruth,
    *,
    gauge_kPa: float,
    stroke_m: float,
    cycles: int,
    seed: int,
    step_m: float = 0.5e-3,
    speed_m_per_s: float = 2e-3,
    noise_N: float = 1.0,
) -> Path:
    """A cyclic test on a tensile machine (TOML + CSV, a supplied time series): the muscle mounted
    at its rest length, pressurised there to `gauge_kPa` by a regulator in 50 kPa steps, then
    shortened by `stroke_m` and returned `cycles` times by the crosshead at `speed_m_per_s`, a
    sample every `step_m` of travel. What the muscle does depends on its path, not its rate
    (friction with memory, a slack braid): each sample is a held length at the regulated pressure,
    in the order measured. The TOML declares the build as the other writers do; its [friction] is
    none, the thesis's sliding sleeve (this muscle's fibres lie in its membrane)."""
    rng = np.random.default_rng(seed)
    folder.mkdir(parents=True, exist_ok=True)
    pressures = list(np.arange(0.0, gauge_kPa, 50.0)) + [gauge_kPa]
    elongation = [0.0] * len(pressures)
    steps = int(round(stroke_m / step_m))
    down = [-step_m * k for k in range(1, steps + 1)]
    cycle = down + down[::-1][1:] + [0.0]
    for _ in range(cycles):
        elongation += cycle
        pressures += [gauge_kPa] * len(cycle)
    forces = isometric_forces(truth, [truth.rest_length_m + e for e in elongation], [PA_PER_KPA * p for p in pressures])
    dt = step_m / speed_m_per_s
    with (folder / "cyclic.csv").open("w") as handle:
        handle.write("time_s,elongation_m,force_N,pressure_kPa\n")
        for k, (e, p, f) in enumerate(zip(elongation, pressures, forces)):
            reading = max(round((f + rng.normal(0, noise_N)) / 0.1) * 0.1, 0.0) if f > 0 else 0.0
            handle.write(f"{k * dt:.3f},{e:.5f},{reading:.1f},{p:.1f}\n")
    friction = "[friction]\nfiber_fiber_coefficient = 0.0\nfiber_bladder_coefficient = 0.0\n"
    test = '[test]\ngas = "supplied"\ninflation_pressure_kPa = 0\nambient_temperature_C = 20.0\ndata = "cyclic.csv"\n'
    (folder / "cyclic.toml").write_text(_muscle_section(truth, "") + "\n" + friction + "\n" + test)
    return folder / "cyclic.toml"
