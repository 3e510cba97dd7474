"""The near-model world's generators (tests/independent/thesis_muscle.py, near_families.py):
the thesis's muscle written afresh, checked against virtual work, energy balances and gas-law
closed forms; its departures acting as intended; each hidden cause's signature visible in the
data written; and the generator deterministic and blind to pamkit. No diagnosis verdicts here:
bench/bench_near_model.py scores those."""

import math
import os
import subprocess
import sys
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
from numpy.polynomial import polynomial as P
from scipy.optimize import minimize_scalar

SOURCE_DIR = Path(os.environ.get("PAMKIT_SOURCE_DIR", Path(__file__).resolve().parents[3]))
sys.path.insert(0, str(SOURCE_DIR / "tests"))  # tests/independent: a folder, not an installed package

from independent.near_families import FAMILIES, QUICK, STRENGTHS, draw_departures, first_order_lag  # noqa: E402
from independent.physics import ATMOSPHERE_PA, CV_AIR, GAS_CONSTANT, Build, Motion  # noqa: E402
from independent.thesis_muscle import (  # noqa: E402
    HOOP_POLYNOMIAL_PA,
    LONGITUDINAL_POLYNOMIAL_PA,
    Departures,
    Effects,
    SealedTest,
    ThesisMuscle,
    _mooney_rivlin_basis,
    dahl_state,
    fixture_play,
    matched_constants,
    supplied_force,
)

GAMMA_AIR = (CV_AIR + GAS_CONSTANT) / CV_AIR


def read_csv(toml: Path) -> dict:
    data = np.genfromtxt(toml.with_suffix(".csv"), delimiter=",", names=True)
    return {name: data[name] for name in data.dtype.names}


def bladder_energy(muscle: ThesisMuscle, strain_l, strain_h):
    """E_b from its definition dE_b = V_r (σ_l dε_l + σ_h dε_h): the polynomials integrated term by
    term, the hyperelastic share as its strain energy W = C₁ (I₁ − 3) + C₂ (I₂ − 3) per unit volume."""
    d = muscle.departures
    energy = P.polyval(strain_l, P.polyint(LONGITUDINAL_POLYNOMIAL_PA)) + P.polyval(
        strain_h, P.polyint(HOOP_POLYNOMIAL_PA)
    )
    if d.membrane_share:
        c1, c2 = muscle.membrane.constants
        ll, lh = 1 + strain_l, 1 + strain_h
        i1 = ll**2 + lh**2 + (ll * lh) ** -2
        i2 = ll**-2 + lh**-2 + (ll * lh) ** 2
        energy = (1 - d.membrane_share) * energy + d.membrane_share * (c1 * (i1 - 3) + c2 * (i2 - 3))
    return d.bladder_scale * muscle.braid.rubber * energy


def potential(muscle: ThesisMuscle, length, gauge_Pa, fiber_length=None):
    """E_b − p V at a held gauge pressure, from the volume and the strains alone."""
    s = muscle.braid.shape(np.atleast_1d(length), fiber_length)
    return bladder_energy(muscle, s.strain_l, s.strain_h) - gauge_Pa * s.gas_volume


# ----------------------------------------------------------------------------------------------
# the muscle: virtual work and closed forms


@pytest.mark.parametrize(
    "departures",
    [
        Departures(),
        Departures(wall_held=1.0),
        Departures(wind=0.02, end_flattening=-0.08),
        Departures(end_flattening=1.0),  # flat ends
        Departures(membrane="mooney_rivlin", membrane_share=0.7, bladder_scale=1.2),
        Departures(membrane="neo_hookean", membrane_share=1.0),
    ],
    ids=["thesis", "wall_held", "wind_and_cones", "flat_ends", "mooney_rivlin", "neo_hookean"],
)
def test_the_static_force_is_the_virtual_work_of_gas_and_bladder(departures):
    """F = d(E_b − p V)/dL at a held pressure (virtual work), against a central difference of the
    potential computed from the volume and the bladder's strain energy only; with the bladder off
    it is −p dV/dL. Tolerance: the difference's truncation error, ~1e-8 relative at h = 1 µm."""
    muscle = ThesisMuscle(Build(), departures)
    no_bladder = ThesisMuscle(Build(), replace(departures, bladder_scale=0.0))
    h = 1e-6
    for gauge in (0.0, 60e3, 250e3):
        for length in (0.165, 0.19, 0.215):
            numeric = (potential(muscle, length + h, gauge) - potential(muscle, length - h, gauge)) / (2 * h)
            force = muscle.forces(np.array([length]), gauge).static
            assert force == pytest.approx(numeric, rel=1e-6, abs=1e-6)
            volume_slope = (
                no_bladder.braid.shape(np.array([length + h])).gas_volume
                - no_bladder.braid.shape(np.array([length - h])).gas_volume
            ) / (2 * h)
            assert no_bladder.forces(np.array([length]), gauge).static == pytest.approx(
                -gauge * volume_slope, rel=1e-6, abs=1e-9
            )


@pytest.mark.parametrize("wind", [0.0, 0.03, -0.05])
def test_flat_thin_braid_without_bladder_is_gaylords_closed_form(wind):
    """Flat ends, a wall and fibres of no thickness, no bladder: V = π D² L / 4 with
    π n D = √(b² − L²), so F = −p dV/dL = p (3 L² − b²) / (4 π n²) (Gaylord's formula), with the
    braid's n = (1 + wind) times the declared turns and b fixed by the deflated build."""
    build = Build(bladder_thickness_m=0.0, fiber_thickness_m=0.0, cone_generator_m=0.0)
    muscle = ThesisMuscle(build, Departures(wind=wind, bladder_scale=0.0))
    n = build.fiber_revolutions * (1 + wind)
    b2 = build.length_m**2 + (math.pi * n * build.diameter_m) ** 2
    lengths = np.linspace(0.16, 0.22, 7)
    gauge = 200e3
    expected = gauge * (3 * lengths**2 - b2) / (4 * math.pi * n * n)
    assert muscle.forces(lengths, gauge).static == pytest.approx(expected, rel=1e-12, abs=1e-9)


def test_the_deflated_build_is_the_braids_reference():
    """At the deflated length the braid has its declared diameter, the bladder its table-3.1
    strains (none longitudinally, D₀/D_b0 − 1 round), and the wall its eq. 3.1.3 volume."""
    build = Build()
    for departures in (Departures(), Departures(wind=0.02, wall_held=1.0)):
        shape = ThesisMuscle(build, departures).braid.shape(np.array([build.length_m]))
        assert shape.diameter[0] == pytest.approx(build.diameter_m, rel=1e-12)
        assert shape.strain_l[0] == pytest.approx(0.0, abs=1e-12)
        assert shape.strain_h[0] == pytest.approx(build.diameter_m / build.bladder_diameter_m - 1, rel=1e-12)


def test_the_matched_membrane_laws_differ_in_shape_not_stiffness():
    """The Mooney-Rivlin and neo-Hookean laws blended in are matched to eqs. 3.1.12-13 along the
    muscle's own strains: swapped in whole, they move the force along a stretch by less than a
    quarter of what the whole bladder contributes (there: 2-3 N of about 20 N), yet by more than the
    load cell's 0.2 N step; a Mooney-Rivlin membrane is stable (initial shear modulus 2 (C₁ + C₂) > 0)."""
    build = Build()
    for law in ("mooney_rivlin", "neo_hookean"):
        c1, c2 = matched_constants(ThesisMuscle(build).braid, law)
        assert c1 + c2 > 0
        for gauge in (35e3, 250e3):
            base = ThesisMuscle(build)
            free = base.free_length(gauge)
            lengths = np.linspace(free, free + 0.9 * (build.length_m - free), 20)
            thesis = base.forces(lengths, gauge).static
            bladder = thesis - ThesisMuscle(build, Departures(bladder_scale=0.0)).forces(lengths, gauge).static
            other = ThesisMuscle(build, Departures(membrane=law, membrane_share=1.0)).forces(lengths, gauge).static
            rms = lambda x: float(np.sqrt(np.mean(x**2)))  # noqa: E731
            assert 0.2 < rms(other - thesis) < 0.25 * rms(bladder)


def test_the_membrane_stresses_derive_from_its_strain_energy():
    """σ_i = ∂W/∂λ_i of W = C₁ (I₁ − 3) + C₂ (I₂ − 3), λ₃ = 1/(λ_l λ_h): against central differences."""
    strain_l, strain_h, h = np.array([-0.2, 0.0]), np.array([0.5, 0.9]), 1e-7

    def energy(el, eh, c1=0.3, c2=-0.1):
        ll, lh = 1 + el, 1 + eh
        return c1 * (ll**2 + lh**2 + (ll * lh) ** -2 - 3) + c2 * (ll**-2 + lh**-2 + (ll * lh) ** 2 - 3)

    (al, ah), (bl, bh) = _mooney_rivlin_basis(strain_l, strain_h)
    d_l = (energy(strain_l + h, strain_h) - energy(strain_l - h, strain_h)) / (2 * h)
    d_h = (energy(strain_l, strain_h + h) - energy(strain_l, strain_h - h)) / (2 * h)
    assert 0.3 * al - 0.1 * bl == pytest.approx(d_l, rel=1e-7)
    assert 0.3 * ah - 0.1 * bh == pytest.approx(d_h, rel=1e-7)


def test_extensible_fibres_balance_their_tension_and_keep_virtual_work():
    """Fibres of stiffness EA stretch until EA ε equals their tension, the force conjugate to the
    fibre length: N T = −∂(E_b − p V)/∂b (a central difference here). The force is then the derivative
    of the potential minimised over the fibre length, Π(L) = min_b [E_b − p V + N EA (b − b₀)²/(2 b₀)]
    (envelope theorem): both against numbers computed from the volume and energy alone."""
    stiffness, gauge = 150.0, 200e3
    muscle = ThesisMuscle(Build(), effects=Effects(fiber_stiffness_N=stiffness))
    b0, fibers = muscle.braid.fiber_length, Build().fiber_count

    def total(length, b):
        return float(potential(muscle, length, gauge, np.array([b]))[0]) + fibers * stiffness * (b - b0) ** 2 / (2 * b0)

    def relaxed(length):
        return minimize_scalar(
            lambda b: total(length, b), bounds=(b0, b0 * 1.05), method="bounded", options={"xatol": 1e-13}
        ).fun

    for length in (0.17, 0.19, 0.21):
        f = muscle.forces(np.array([length]), gauge)
        strain = float(f.fiber_strain[0])
        assert strain > 1e-3  # these fibres do stretch, by T/EA ~ 1 %
        b, h = b0 * (1 + strain), 1e-9
        tension = (
            -(
                float(potential(muscle, length, gauge, np.array([b + h]))[0])
                - float(potential(muscle, length, gauge, np.array([b - h]))[0])
            )
            / (2 * h)
            / fibers
        )
        assert stiffness * strain == pytest.approx(tension, rel=1e-5)
        step = 1e-5
        assert float(f.static[0]) == pytest.approx(
            (relaxed(length + step) - relaxed(length - step)) / (2 * step), rel=2e-3
        )


# ----------------------------------------------------------------------------------------------
# the gas and the energy balance


def cycle(top=0.04, speed=0.02, rest=1.0, hold=0.0):
    ramp = top / speed
    if hold:
        return Motion(np.cumsum([0.0, rest, ramp, hold, ramp, rest]), np.array([0.0, 0.0, top, top, 0.0, 0.0]))
    return Motion(np.cumsum([0.0, rest, ramp, ramp, rest]), np.array([0.0, 0.0, top, 0.0, 0.0]))


def sealed(effects=None, departures=None, gauge_kPa=150.0):
    muscle = ThesisMuscle(Build(), departures or Departures(), effects or Effects())
    return SealedTest(muscle, gauge_kPa, 22.0, round(muscle.free_length(gauge_kPa * 1e3), 4))


def test_a_sealed_isothermal_gas_keeps_boyles_product_with_its_dead_volume():
    """Isothermal and sealed: p_abs (V + V_dead) is the same at every instant (Boyle), and a dead
    volume scales the pressure swing down."""
    motion = cycle()
    times = np.linspace(0, motion.corner_t[-1], 301)
    swings = []
    for fraction in (0.0, 0.25):
        test = sealed(Effects(dead_volume_fraction=fraction))
        run = test.run(motion, times)
        volume = test.muscle.braid.shape(test.initial_length_m + run.elongation_m).gas_volume + test.dead_m3
        product = (run.gauge_kPa * 1e3 + ATMOSPHERE_PA) * volume
        assert np.ptp(product) / product.mean() < 1e-12
        swings.append(np.ptp(run.gauge_kPa))
    assert swings[1] < 0.85 * swings[0]


def test_a_gas_that_cannot_exchange_heat_follows_the_adiabat():
    """τ_h far beyond the test: p_abs V^γ and T V^(γ−1) stay constant (γ = 1.4 for c_v = 5R/2)."""
    test = sealed(Effects(heat_time_constant_s=1e9))
    motion = cycle(top=0.045, speed=0.01)
    run = test.run(motion, np.linspace(0, motion.corner_t[-1], 201))
    volume = test.muscle.braid.shape(test.initial_length_m + run.elongation_m).gas_volume
    adiabat = (run.gauge_kPa * 1e3 + ATMOSPHERE_PA) * volume**GAMMA_AIR
    temperature = (run.temperature_C + 273.15) * volume ** (GAMMA_AIR - 1)
    assert np.ptp(adiabat) / adiabat.mean() < 1e-7
    assert np.ptp(temperature) / temperature.mean() < 1e-7
    assert np.ptp(run.temperature_C) > 5.0  # and it does heat up


def test_a_leak_at_rest_decays_with_its_time_constant():
    """Held still and isothermal, the gauge pressure decays as p₀ e^(−t/τ_L) (the leak's definition)."""
    tau = 200.0
    test = sealed(Effects(leak_time_constant_s=tau))
    motion = Motion(np.array([0.0, 100.0]), np.array([0.0, 0.0]))
    times = np.linspace(0, 100, 11)
    run = test.run(motion, times)
    assert run.gauge_kPa == pytest.approx(run.gauge_kPa[0] * np.exp(-times / tau), rel=1e-7)


def work(run, motion, force):
    """∫ F dx along the motion, by the trapezoid rule on the run's (fine) samples."""
    return float(np.trapezoid(force, run.elongation_m))


def test_over_a_closed_cycle_friction_alone_dissipates():
    """Isothermal gas, elastic bladder: the static force is conservative, so the crosshead's work
    over a closed cycle is the friction's dissipation ∫ F_f v dt > 0 (trapezoid error < 1e-6 of it)."""
    motion = cycle(top=0.04, speed=0.02)
    times = np.linspace(0, motion.corner_t[-1], 40001)
    for departures in (Departures(), Departures(friction_law="dahl", friction_share=0.7, dahl_length_m=1e-3)):
        test = sealed(departures=departures)
        run = test.run(motion, times)
        friction = test.friction(motion, times, run.gauge_kPa * 1e3)
        dissipated = work(run, motion, friction)
        assert dissipated > 1.0
        assert work(run, motion, run.force_N) == pytest.approx(dissipated, rel=1e-4)
        assert abs(work(run, motion, run.force_N - friction)) < 1e-6 * dissipated


def test_with_heat_exchange_the_cycles_work_is_the_heat_given_to_the_wall():
    """No friction, gas exchanging heat with the wall at τ_h: the first law over a cycle,
    ∮ F dx = ΔU + ∫ n c_v (T − T_a)/τ_h dt (work on the gas = its energy gained + heat lost), with
    both sides integrated on a 2 ms grid (trapezoid error well below 1e-3 of the work)."""
    tau = 2.0
    test = sealed(Effects(heat_time_constant_s=tau), Departures(friction_scale=0.0), gauge_kPa=200.0)
    motion = cycle(top=0.045, speed=0.03, rest=0.5, hold=3.0)
    times = np.arange(0, motion.corner_t[-1] + 1e-9, 0.002)
    run = test.run(motion, times)
    temperature = run.temperature_C + 273.15
    heat_out = float(np.trapezoid(test.moles0 * CV_AIR * (temperature - test.ambient_K) / tau, times))
    gained = test.moles0 * CV_AIR * (temperature[-1] - temperature[0])
    done = work(run, motion, run.force_N)
    assert done > 0.05  # a hysteresis loop: the gas gives heat away
    assert done == pytest.approx(gained + heat_out, rel=1e-3)


# ----------------------------------------------------------------------------------------------
# the causes' mechanisms


def test_a_fixture_with_play_holds_the_muscle_until_the_crosshead_meets_it():
    """A play of s: each stretch starts after the crosshead has travelled s, each return as soon as
    the crosshead moves back (the muscle was left where the crosshead turned minus s), exactly."""
    motion = Motion(np.array([0.0, 1.0, 3.0, 5.0, 7.0]), np.array([0.0, 0.0, 0.02, 0.0, 0.02]))
    play = fixture_play(motion, 0.002)
    t = np.linspace(0, 7, 7001)
    crosshead = motion.elongation(t)
    muscle = play.elongation(t)
    assert muscle == pytest.approx(np.clip(muscle, crosshead - 0.002, crosshead), abs=1e-15)
    assert play.elongation(np.array([1.2, 3.0, 3.1, 5.0, 5.2])) == pytest.approx(
        [0.0, 0.018, 0.018, 0.0, 0.0], abs=1e-12
    )
    assert play.elongation(np.array([2.0, 4.0])) == pytest.approx([0.008, 0.010], abs=1e-12)


def test_dahl_friction_turns_over_its_presliding_length_and_holds_in_a_hold():
    """dz/dx = (1 − z sgn v)/x_d: from rest z = 1 − e^(−x/x_d) while stretching; in a hold z stays."""
    motion = Motion(np.array([0.0, 1.0, 2.0, 3.0]), np.array([0.0, 0.01, 0.01, 0.0]))
    x_d = 1e-3
    z = dahl_state(motion, np.array([0.1, 0.5, 1.5, 2.1]), x_d)
    assert z[:2] == pytest.approx(1 - np.exp(-np.array([0.001, 0.005]) / x_d), rel=1e-12)
    assert z[2] == pytest.approx(1 - math.exp(-10), rel=1e-12)
    assert z[3] == pytest.approx(-1 + (1 + z[2]) * math.exp(-0.001 / x_d), rel=1e-12)


def test_the_lag_filter_is_exact_for_a_ramp():
    """y' = (u − y)/τ with u = s t from y(0) = 0: y = s (t − τ (1 − e^(−t/τ))), on any grid."""
    tau, slope = 0.7, 3.0
    t = np.sort(np.concatenate([[0.0], np.random.default_rng(1).uniform(0, 5, 40)]))
    assert first_order_lag(t, slope * t, tau) == pytest.approx(slope * (t - tau * (1 - np.exp(-t / tau))), rel=1e-12)


def test_pressure_hysteresis_lifts_the_venting_branch_by_twice_the_friction():
    """Held at one length, the pressure stepped to 150 kPa from below and from above: the force
    on venting exceeds the force on pressurising by 2 c p π D²/4 once the friction has turned."""
    muscle = ThesisMuscle(Build())
    up = np.concatenate([np.linspace(0, 150, 200), np.full(10, 150.0)])
    down = np.concatenate([np.linspace(300, 150, 200), np.full(10, 150.0)])
    c, length = 0.1, 0.2
    rising = supplied_force(muscle, length, up, hysteresis=c)[-1]
    venting = supplied_force(muscle, length, down, hysteresis=c)[-1]
    diameter = muscle.braid.shape(np.array([length])).diameter[0]
    assert venting - rising == pytest.approx(2 * c * 150e3 * math.pi * diameter**2 / 4, rel=1e-6)


def test_fibre_compliance_softens_the_top_of_a_stretch():
    """The same crosshead travel with fibres of EA = 100 N: the fibres stretch more where the force
    is higher, and the force and pressure at the top fall below the inextensible muscle's."""
    motion = cycle(top=0.04)
    times = np.linspace(0, motion.corner_t[-1], 101)
    rigid = sealed().run(motion, times)
    soft = sealed(Effects(fiber_stiffness_N=100.0)).run(motion, times)
    top = np.argmax(rigid.elongation_m)
    assert soft.force_N[top] < rigid.force_N[top] - 5.0
    assert soft.gauge_kPa[top] < rigid.gauge_kPa[top]
    assert soft.fiber_strain[top] > soft.fiber_strain[0] > 0


def test_a_viscoelastic_bladder_opens_the_force_loop_more_at_higher_rate_and_leaves_the_pressure():
    """A Maxwell branch (τ 2 s, strength 1) adds a loop to the force that grows with rate; the gas,
    which it does not touch, keeps the elastic muscle's pressure."""
    areas = []
    for speed in (0.004, 0.03):
        motion = cycle(top=0.04, speed=speed)
        times = np.linspace(0, motion.corner_t[-1], 4001)
        elastic = sealed(departures=Departures(friction_scale=0.0)).run(motion, times)
        viscous = sealed(Effects(viscoelastic_strength=1.0), Departures(friction_scale=0.0)).run(motion, times)
        assert viscous.gauge_kPa == pytest.approx(elastic.gauge_kPa, rel=1e-9)
        areas.append(work(viscous, motion, viscous.force_N))
    assert 0 < areas[0] < areas[1]


# ----------------------------------------------------------------------------------------------
# the written datasets: each cause's signature, against the null of the same seed


def family_data(tmp_path, family, strength, seed=1):
    dataset = FAMILIES[family].make(seed, tmp_path / f"{family}-{strength}-{seed}", strength)
    return dataset, read_csv(dataset.experiment)


def without_cause(tmp_path, family, seed=1):
    """The family's test for `seed` with nothing hidden: same build, departures, protocol, noise."""
    return read_csv(FAMILIES[family].without_cause(seed, tmp_path / f"{family}-none-{seed}").experiment)


def cycles_of(columns):
    """Sample indices of each stretch-return cycle (between the crosshead's returns to zero)."""
    moving = columns["elongation_m"] > 0
    starts = np.flatnonzero(moving[1:] & ~moving[:-1]) + 1
    ends = np.flatnonzero(~moving[1:] & moving[:-1]) + 1
    return [np.arange(a, b) for a, b in zip(starts, ends)]


def test_a_leaks_peaks_drift_down_cycle_after_cycle(tmp_path):
    _, leak = family_data(tmp_path, "leak", "strong")
    null = without_cause(tmp_path, "leak")
    peaks = [leak["pressure_kPa"][c].max() for c in cycles_of(leak)]
    null_peaks = [null["pressure_kPa"][c].max() for c in cycles_of(null)]
    assert np.all(np.diff(peaks) < 0)  # every cycle lower: τ 150 s loses more than an ADC count a cycle
    assert np.ptp(null_peaks) <= 2 * 0.842  # the null's peaks stay within two counts


def test_heat_exchange_swings_the_temperature_that_the_null_holds(tmp_path):
    _, heat = family_data(tmp_path, "heat_transfer", "strong")
    null = without_cause(tmp_path, "heat_transfer")
    count = 5.0 / 1024 / 0.01  # one ADC count of the TMP36 [°C]
    assert np.ptp(heat["temperature_C"]) > 8 * count
    assert np.ptp(null["temperature_C"]) <= 3 * count + 1e-9  # the isothermal null: 2 mV of noise, a count or so


@pytest.mark.parametrize("strength", ["medium", "strong"])
def test_a_time_skew_shifts_the_pressures_cross_correlation(tmp_path, strength):
    """The skewed pressure matches the same test's without the skew best when shifted by the skew,
    in samples: the sample the logger wrote at t is the muscle's pressure at t + skew."""
    dataset, skewed = family_data(tmp_path, "time_skew", strength)
    null = without_cause(tmp_path, "time_skew")
    skew, rate = dataset.truth["cause"]["time_skew"]["offset_s"], dataset.truth["rate_Hz"]
    a, b = skewed["pressure_kPa"], null["pressure_kPa"]
    lags = np.arange(-80, 81)
    mismatch = [np.mean((a[max(0, -k) : a.size - max(0, k)] - b[max(0, k) : b.size - max(0, -k)]) ** 2) for k in lags]
    assert lags[int(np.argmin(mismatch))] == round(skew * rate)


def test_instrument_offsets_read_as_offsets(tmp_path):
    """Load cell, thermometer and transducer causes shift their channel against the same test without
    them by what was hidden (the same noise draws; quantisation leaves a fraction of a step)."""
    d, thermo = family_data(tmp_path, "thermometer", "strong")
    null = without_cause(tmp_path, "thermometer")
    assert np.mean(thermo["temperature_C"] - null["temperature_C"]) == pytest.approx(
        d.truth["cause"]["thermometer"]["offset_C"], abs=0.25
    )
    d, cell = family_data(tmp_path, "load_cell", "strong")
    null = without_cause(tmp_path, "load_cell")
    tare, c = d.truth["cause"]["load_cell"]["offset_N"], d.truth["cause"]["load_cell"]["nonlinearity_per_kN"] * 1e-3
    f = null["force_N"]
    assert np.mean(cell["force_N"] - (tare + f * (1 + c * f))) == pytest.approx(0.0, abs=0.2)
    d, offset = family_data(tmp_path, "sensor_offset", "strong")
    null = without_cause(tmp_path, "sensor_offset")
    o, g = d.truth["cause"]["sensor_offset"]["offset_kPa"], d.truth["cause"]["sensor_offset"]["gain"]
    assert np.mean(offset["pressure_kPa"] - (o + g * null["pressure_kPa"])) == pytest.approx(0.0, abs=0.5)


def test_a_slack_braid_reads_zero_where_the_thesis_braid_would_push(tmp_path):
    """The braid_slack family vents below the pressure where the muscle goes slack: those rows read
    the load cell's noise about zero; the null sweep stays taut (no slack row, every plateau pulling)."""
    d, slack = family_data(tmp_path, "braid_slack", "strong")
    assert d.truth["slack_rows"] > 50
    low = slack["pressure_kPa"] < d.truth["floor_kPa"] + 1.0
    assert abs(np.mean(slack["force_N"][low])) < 4 * d.truth["force_noise_N"] / math.sqrt(low.sum())
    n, null = family_data(tmp_path, "supplied_null", None)  # a null sweep of its own
    assert n.truth["slack_rows"] == 0 and not n.present
    assert np.min(null["force_N"]) > 10.0 - 5 * n.truth["force_noise_N"]


# ----------------------------------------------------------------------------------------------
# the generator: blind to pamkit, deterministic, truth kept out of the files


def test_departure_draws_are_one_or_two_and_within_their_ranges():
    from independent.near_families import DEPARTURE_RANGES, DEPARTURES, SEALED

    counts = []
    for seed in range(40):
        d, multiple = draw_departures(np.random.default_rng(seed), SEALED)
        assert 2.0 <= multiple <= 5.0
        on = {
            "wall_held": d.wall_held > 0,
            "wind": d.wind != 0,
            "end_flattening": d.end_flattening != 0,
            "membrane_share": d.membrane_share > 0,
            "friction_share": d.friction_share > 0,
        }
        counts.append(sum(on.values()))
        for name in DEPARTURES:
            if on[name]:
                low, high = DEPARTURE_RANGES[name]
                assert low <= abs(getattr(d, name)) <= high
    assert set(counts) == {1, 2}


def test_the_near_model_generator_never_imports_pamkit_nor_writes_the_truth(tmp_path):
    """Every family at medium strength (the quick set): written without pamkit in the process, and
    no file pamkit reads names the hidden cause or its departures."""
    script = (
        "import sys; from pathlib import Path; from independent.near_families import FAMILIES, QUICK\n"
        "for name, seed, strength in QUICK: FAMILIES[name].make(seed, Path(sys.argv[1]) / f'{name}-{seed}', strength)\n"
        "assert not any(m == 'pamkit' or m.startswith('pamkit.') for m in sys.modules), 'pamkit was imported'\n"
    )
    env = {**os.environ, "PYTHONPATH": str(SOURCE_DIR / "tests")}
    done = subprocess.run(
        [sys.executable, "-c", script, str(tmp_path)], check=False, capture_output=True, text=True, env=env, timeout=600
    )
    assert done.returncode == 0, done.stderr
    words = {h for f in FAMILIES.values() for h in f.hidden} | {
        "heat", "dead", "leak", "viscoelastic", "compliance", "slack", "lag", "skew", "offset", "thermometer",
        "hysteresis", "wind", "dahl", "coulomb", "mooney", "hookean", "flatten", "departure", "truth", "hidden",
    }  # fmt: skip
    for name, seed, _ in QUICK:
        text = (tmp_path / f"{name}-{seed}" / "test.toml").read_text().lower()
        assert not [w for w in words if w in text], (name, text)


@pytest.mark.parametrize("family", ["null", "heat_transfer", "supplied_sensor_lag", "leak+time_skew"])
def test_the_same_seed_writes_the_same_bytes(family, tmp_path):
    strength = None if not FAMILIES[family].hidden else "medium"
    first = FAMILIES[family].make(5, tmp_path / "a", strength)
    second = FAMILIES[family].make(5, tmp_path / "b", strength)
    assert first.experiment.with_suffix(".csv").read_bytes() == second.experiment.with_suffix(".csv").read_bytes()
    other = FAMILIES[family].make(6, tmp_path / "c", strength)
    assert other.experiment.with_suffix(".csv").read_bytes() != first.experiment.with_suffix(".csv").read_bytes()


def test_the_registry_has_every_catalog_cause_at_three_strengths_and_a_quick_set():
    hidden = {h for f in FAMILIES.values() for h in f.hidden}
    assert hidden == {
        "heat_transfer", "dead_volume", "leak", "bladder_viscoelasticity", "fiber_compliance", "fixture_slack",
        "sensor_lag", "time_skew", "sensor_offset", "load_cell", "thermometer", "braid_slack", "pressure_hysteresis",
    }  # fmt: skip
    for family in FAMILIES.values():
        assert set(family.levels) == (set(STRENGTHS) if family.hidden else set())
        for strength in family.levels.values():
            assert set(strength) == set(family.hidden)
    assert {name for name, _, _ in QUICK} == set(FAMILIES)
    assert 20 <= len(QUICK) <= 30
