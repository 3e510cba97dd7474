"""A true muscle that is not its declared build: the base-model mismatch every real rig has.

A diagnosis calibrates the model the experiment file declares. A real muscle differs from any
declared build in ways no catalog effect describes and the baseline's three calibrated numbers
(inflation pressure, friction scale, bladder scale) absorb only in part. :func:`draw_mismatch`
draws one or two such differences, each at a size a careful builder would not notice:

- the braid's wind, 2-5 % more or fewer turns than counted (5 % of PAM 2's two turns is 1.3
  degrees of its deflated braid angle, within what a sleeve settles to on its end fittings);
- the bladder wall 10-25 % thicker or thinner than measured (a latex tube's wall varies by
  that much along its length), which moves the rubber's volume and the membrane's stiffness;
- the end cones' slant 5-15 % longer or shorter (the sleeve's fold at the end fittings);
- a friction closer to Coulomb's: the tanh's sharpness 30-300 s/m instead of the thesis's 1 s/m,
  at the same force at the test's speed (the friction scale the baseline calibrates keeps the
  level; what differs is the shape at each reversal).

Used by ``synthesize(true_muscle=...)`` and ``bench/bench_diagnose.py --mismatch``; what was
drawn goes to the manifest.
"""

from __future__ import annotations

import math

import numpy as np

from pamkit._core import MuscleParams

WIND_RATIO = (0.02, 0.05)
BLADDER_THICKNESS_RATIO = (0.10, 0.25)
CONE_GENERATOR_RATIO = (0.05, 0.15)
FRICTION_SHARPNESS_S_PER_M = (30.0, 300.0)  # log-uniform
KINDS = ("wind", "bladder_thickness", "cone_generator", "friction_sharpness")


def _signed(rng: np.random.Generator, span: tuple[float, float]) -> float:
    return float(rng.choice((-1.0, 1.0)) * rng.uniform(*span))


def draw_mismatch(rng: np.random.Generator, kinds=KINDS, count: tuple[int, int] = (1, 2)):
    """A ``true_muscle`` for :func:`pamkit.synth.dataset.synthesize`: one or two of `kinds`
    drawn with their sizes (module docstring). A sharper friction is scaled to the thesis's force
    at the test's crosshead speed."""
    chosen = sorted(rng.choice(len(kinds), size=int(rng.integers(count[0], count[1] + 1)), replace=False))
    drawn: dict[str, float] = {}
    for index in chosen:
        kind = kinds[index]
        if kind == "wind":
            drawn["fiber_revolutions_ratio"] = 1.0 + _signed(rng, WIND_RATIO)
        elif kind == "bladder_thickness":
            drawn["bladder_thickness_ratio"] = 1.0 + _signed(rng, BLADDER_THICKNESS_RATIO)
        elif kind == "cone_generator":
            drawn["cone_generator_ratio"] = 1.0 + _signed(rng, CONE_GENERATOR_RATIO)
        elif kind == "friction_sharpness":
            low, high = FRICTION_SHARPNESS_S_PER_M
            drawn["friction_sharpness_s_per_m"] = math.exp(rng.uniform(math.log(low), math.log(high)))
        else:
            raise ValueError(f"unknown mismatch kind '{kind}' (known: {', '.join(KINDS)})")

    def true_muscle(declared: MuscleParams, protocol) -> tuple[MuscleParams, dict]:
        params = MuscleParams(
            build=declared.build, bladder=declared.bladder, friction=declared.friction, gas=declared.gas
        )
        build, friction = params.build, params.friction
        build.fiber_revolutions *= drawn.get("fiber_revolutions_ratio", 1.0)
        build.bladder_thickness_m *= drawn.get("bladder_thickness_ratio", 1.0)
        build.cone_generator_m *= drawn.get("cone_generator_ratio", 1.0)
        if "friction_sharpness_s_per_m" in drawn:
            sharpness = drawn["friction_sharpness_s_per_m"]
            speed = protocol.speed_m_per_s
            level = math.tanh(friction.sharpness_s_per_m * speed) / math.tanh(sharpness * speed)
            friction.sharpness_s_per_m = sharpness
            friction.fiber_fiber_coefficient *= level
            friction.fiber_bladder_coefficient *= level
        params.build, params.friction = build, friction
        return params, dict(drawn)

    return true_muscle
