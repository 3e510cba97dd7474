"""What an instrument's error must show to be named: its channel off where the model without it
leaves it (unfounded), gaining on the force more than an instrument takes of another misfit
(misread), standing out from the base model's misfit on the coupled channels
(stands_out), gaining on the channels it changes (uncredited), leaving its channel whole
(reads_left), and no vacuum behind a supplied test's reading (holds_vacuum); the values that split
one reading with a calibrated one, judged by their intervals (shares_a_reading); and the channels'
held-out ratios to their noise that these rules read (docs/diagnosis.md, rules 3 and 6)."""

from __future__ import annotations

from pamkit._core import EffectStage, GasMode, Resolution
from pamkit.diagnosis import evidence
from pamkit.diagnosis.series.calibrate import Fit
from pamkit.diagnosis.series.findings import baseline_findings, off_neutral
from pamkit.diagnosis.series.kinds import Problem
from pamkit.diagnosis.series.score import Score, credited_channels
from pamkit.diagnosis.significance import MIN_GAIN, NONE_WITHIN_NOISE
from pamkit.diagnosis.supply import implied_vacuum
from pamkit.io.columns import value_from_si

# An effect on one instrument's channels is a cause beside structure the base model leaves on the
# channels it cannot change only if its own channel stood this many times further above the noise:
# a base model that misfits one channel by r noise sigmas misfits the channels coupled to it by
# the same order (another team's model: force 3.9-5.3x, pressure 4.7x; a pressure offset fitted
# to the latter explained nothing of the muscle). The factor is NONE_WITHIN_NOISE's: as "none" needs
# every channel within twice its noise, a cause needs its channel twice as far out as the rest.
STANDS_OUT = 2.0
# A channel left above this many times its noise holds structure, not an error of the noise's
# estimate: the calibrated baseline reaches at most 1.52x on pamkit's own nulls.
STRUCTURE_LEFT = 1.5
# The channels one misfit of the base model moves together: the braid's kinematics set both the
# gas's volume (so its pressure) and the force. The temperature, held near the wall's by the gas
# law and the heat exchange, is not moved by a wrong wind or membrane: a thermometer's offset stands
# on its own channel whatever the force shows.
COUPLED = frozenset({"force_N", "gauge_pressure_Pa"})
PRESSURE = "gauge_pressure_Pa"
FORCE = "force_N"
MODULUS = "bladder_scale"  # the calibrated scale on the bladder's stress law
OFFSET = "offset_N"  # a force instrument's reading at zero force
# What an error of the force's instrument (a load cell's offset, and its share growing with the
# force) takes of a force misfit it did not make: where a load cell was named but was not in the
# data, it gained 0.045-0.085 on the force in 10 of 15 namings (bench_near_model seeds 1-24,
# bench_families seeds 1-12: a sealed transducer's offset, a weak dead volume, another team's
# muscle, read there as an offset of -12 to -19 N); a load cell in the data was named below this in
# 3 of 39.
MISREAD_GAIN = 0.09
INFLATION = "inflation_gauge_pressure_Pa"  # the sealed gas's calibrated starting pressure


def noise_ratios(problem: Problem, fit: Fit) -> dict[str, float]:
    """Held-out RMSE over noise, per channel."""
    return {
        c: evidence.rmse((fit.predicted[c] - problem.measured[c])[problem.held_mask]) / problem.sigma[c]
        for c in problem.channels
    }


def structured(problem: Problem, fit: Fit, factor: float) -> list[str]:
    """Channels whose held-out residual RMS is above `factor` times their noise."""
    return [c for c, ratio in noise_ratios(problem, fit).items() if ratio > factor]


def corrects_output(problem: Problem, effect) -> bool:
    """An effect that edits what the instruments read of the model (a load cell's offset), not what
    drives it: a supplied test's transducer error changes the pressure the muscle is driven with,
    whose force then follows the physics."""
    supplied_input = problem.experiment.gas == GasMode.supplied and effect.reads_supplied_pressure()
    return effect.stage() == EffectStage.measurement and not supplied_input


def shifts_in_time(effect) -> bool:
    """An effect that moves its channel in time (a skew, a lag): its first parameter must resolve
    the sample interval."""
    parameters = effect.parameters()
    return bool(parameters) and parameters[0].resolution == Resolution.sample_interval


def rereading(problem: Problem, fit: Fit) -> list:
    """A fit's corrections of a sealed test's pressure transducer. The declared inflation pressure,
    whose search box is the hand-read transducer's 5 %, was read on that transducer, so the box
    does not bind the fit (a 0.97 gain and a 4.8 kPa offset put the truth 6 % from the reading at
    56 kPa); and a correction and the inflation pressure split one reading between them, so where
    along it the fit ended is not what the data say (a 10 kPa offset fitted at 15.5 kPa, 9.4-21.7 kPa
    its interval, with the inflation pressure 5 % low)."""
    if problem.experiment.gas != GasMode.sealed:
        return []
    return [e for e in fit.effects if corrects_output(problem, e) and list(e.channels_changed()) == [PRESSURE]]


def shares_a_reading(problem: Problem, fit: Fit) -> set[str]:
    """The values of `fit` (keyed as in its coordinates) that split one reading with a value
    calibrated beside them, so that where along that reading the fit ended is not what the data
    say, only how far its interval reaches: a sealed test's transducer correction, sharing the
    pressure it read with the declared inflation pressure (rereading), and a load cell placed by
    more than its offset, that offset sharing the force with the bladder's modulus (bladder_scale,
    plausible where it ended), whose force changes little over a stretch (another base model's
    membrane: a -10 N offset fitted beside a dead volume at -20.2 N, -23.0 to -17.5 N its interval,
    the modulus at 0.49-0.70 of its declared value; near-model dead_volume+load_cell, strong seed
    25)."""
    prefix = (lambda e: f"{e.name()}.") if len(fit.effects) > 1 else (lambda e: "")
    out = {prefix(e) + p.name for e in rereading(problem, fit) for p in e.parameters()}
    if _plausible_at(fit, MODULUS):
        out |= {
            prefix(e) + OFFSET
            for e in fit.effects
            if reads_off(problem, e) and _on_force(e) and _placed_beyond_offset(fit, e, prefix(e))
        }
    return out


def _placed_beyond_offset(fit: Fit, effect, prefix: str) -> bool:
    """Whether the data place `effect` in `fit` by a value other than its offset (a load cell's
    nonlinearity, findings.off_neutral). An offset alone is the very share of the force the modulus
    trades against; its value is then all the evidence for the cell (a 20.04 N offset, its
    nonlinearity's interval holding zero, named for a pressure transducer's weak offset: near-model
    sensor_offset, weak seed 25)."""
    return any(placed for name, placed in off_neutral(fit, effect, prefix).items() if name != OFFSET)


def _plausible_at(fit: Fit, name: str) -> bool:
    """Whether baseline value `name` is calibrated in `fit` and ended inside its plausible range.
    A share of one reading is given its interval once: an offset and a modulus both outside their
    ranges would each be excused by the other's trade (a friction with memory on another team's
    muscle read as a -24 N offset beside a modulus of 0.09: bench_families dahl, seed 2)."""
    if name not in fit.coordinates:
        return False
    coordinate, x = fit.coordinates[name]
    return not coordinate.implausible(float(coordinate.value(x)))


def _on_force(effect) -> bool:
    return list(effect.channels_changed()) == [FORCE]


def stands_out(problem: Problem, before: Fit, s: Score, effects) -> list[str]:
    """Why what an effect explains on its channels `credited` may be the base model's misfit: on the
    coupled channels, its own stood less than STANDS_OUT times as far above the noise in `before`
    (the model without it) as the other stays with it (`s`), beyond STRUCTURE_LEFT. `effects` are
    the effects whose channels are credited (the fit's, or the ones it adds to `before`).

    An effect on the physics or the motion that leaves its own channels within STRUCTURE_LEFT
    explains them whole and stands on them: its model moved them, where an instrument bends what it
    reads (a viscoelastic bladder takes the force from 2.9x to 0.9x its noise beside a pressure the
    base model leaves at 1.6x, bench_diagnose --mismatch seed 3001)."""
    credited = credited_channels(problem, before, effects)
    others = [c for c in problem.channels if c not in credited and c in COUPLED]
    if not (others and set(credited) & COUPLED):
        return []
    physical = not any(corrects_output(problem, e) for e in effects)
    if physical and all(s.rmse[c] / problem.sigma[c] <= STRUCTURE_LEFT for c in credited):
        return []
    ratios = noise_ratios(problem, before)
    left = max(others, key=lambda c: s.rmse[c] / problem.sigma[c])
    worst = s.rmse[left] / problem.sigma[left]
    own = max(ratios[c] for c in credited if c in COUPLED)
    # The transducer that read the sealed gas's declared inflation pressure trades its offset and
    # gain against the calibrated inflation pressure: its error shows only as a pressure channel at
    # odds with a force the model explains. With structure left on the force, however far out the
    # pressure was, the two may be one misfit of the base model.
    inflation_transducer = (
        problem.experiment.gas == GasMode.sealed
        and credited == [PRESSURE]
        and all(corrects_output(problem, e) and not shifts_in_time(e) for e in effects)
    )
    if worst > STRUCTURE_LEFT and (inflation_transducer or own < STANDS_OUT * worst):
        return [
            f"what it explains on {', '.join(credited)} ({own:.1f}x the noise before it) does not stand out "
            f"from what the base model leaves on {left} ({worst:.1f}x), which it cannot change: one misfit of "
            "the base model may show on both"
        ]
    return []


def unfounded(problem: Problem, before: Fit, effects) -> list[str]:
    """Why an instrument's error is not established: an effect that edits what an instrument reads
    (a load cell's tare, a transducer's offset in a sealed test) names an error only where its
    channel is off by more than the noise allows under the model without it (`before`: the
    calibrated baseline, or the first cause; NONE_WITHIN_NOISE, the factor of `none`). Within it
    that model already explains the channel, and such an effect, free to bend what its instrument
    reads, would fit what the base model leaves there (another implementation's muscle, a weak
    leak: a pressure offset named wrongly five times in 182, bench_near_model).

    One reading founds a pressure transducer's error within the noise: the sealed gas's inflation
    pressure, calibrated, at the end of its search (the declared value within the transducer's
    5 %). The pressure the data show at the start is then not the pressure the file declares, which
    is what a transducer reading off says (bench_diagnose seed 1009: a 4.8 kPa offset at 56 kPa
    leaves the pressure 1.7 times its noise)."""
    out = []
    ratios = noise_ratios(problem, before)
    strained = {f.parameter for f in baseline_findings(before) if f.bound is not None}
    for effect in effects:
        if not corrects_output(problem, effect):
            continue
        channels = [c for c in credited_channels(problem, before, [effect])]
        if channels != [PRESSURE] or problem.experiment.gas != GasMode.sealed or INFLATION in strained:
            continue
        if channels and max(ratios[c] for c in channels) <= NONE_WITHIN_NOISE:
            worst = max(channels, key=lambda c: ratios[c])
            out.append(
                f"{worst} was within the noise before it ({ratios[worst]:.1f}x, {NONE_WITHIN_NOISE:g}x allowed): "
                "no error of its instrument is needed there"
            )
    return out


def misread(problem: Problem, s: Score, effects) -> list[str]:
    """Why an error of the force's instrument among `effects` (one that reads off, reads_off) is not
    established by `s`, its own score (alone against the calibrated baseline, or beside the causes
    before it): it gains less than MISREAD_GAIN on the force, which such an error takes of a misfit
    it did not make. Like an error where its channel was within the noise (unfounded), not named,
    but as good a reading of the data as a cause it ties with."""
    load_cell = any(reads_off(problem, e) and _on_force(e) for e in effects)
    if not load_cell or FORCE not in s.gain or s.gain[FORCE] >= MISREAD_GAIN:
        return []
    return [
        f"what it gains on {FORCE} ({s.gain[FORCE]:.3f}) is within what a load cell's offset and nonlinearity "
        f"take of a force misfit that is not theirs (below {MISREAD_GAIN:g})"
    ]


def reads_off(problem: Problem, effect) -> bool:
    """An instrument that reads its channel off by a function of what it reads (an offset, a gain, a
    nonlinearity), as opposed to one that moves its channel in time."""
    return corrects_output(problem, effect) and not shifts_in_time(effect)


def reads_left(problem: Problem, fit: Fit, effects) -> list[str]:
    """Why an instrument that reads off (reads_off) among `effects` is not established in `fit`, the
    model with every cause named: its channel still holds structure there (above STRUCTURE_LEFT).
    Such an error is a function of the value its instrument reads, and corrects that channel whole;
    one that leaves it structured has taken the share of another misfit that projects on its form
    (a membrane that softens after its first stretch, read as a load cell's nonlinearity on another
    team's model: bench_families)."""
    out = []
    ratios = noise_ratios(problem, fit)
    for effect in effects:
        if not reads_off(problem, effect):
            continue
        # The temperature is not moved by the base model's misfit (COUPLED): what a thermometer's
        # offset leaves there is a physical cause's (heat exchange), not a share of that misfit.
        channels = [c for c in credited_channels(problem, fit, [effect]) if c in COUPLED]
        left = [c for c in channels if ratios[c] > STRUCTURE_LEFT]
        out += [
            f"{c} stays at {ratios[c]:.1f}x its noise with the causes named: an error of what its instrument "
            "reads would leave it within the noise, and this one explains only a share of it"
            for c in left
        ]
    return out


def holds_vacuum(problem: Problem, fit: Fit) -> list[str]:
    """A supplied test's transducer error that would have the muscle hold a vacuum where a
    sample was read (supply.implied_vacuum), as an objection."""
    e = problem.experiment
    if e.gas != GasMode.supplied:
        return []
    read = ~e.censored
    time, reading = e.columns["time_s"][read], e.columns["gauge_pressure_Pa"][read]
    found = implied_vacuum(fit.effects, time, reading)
    if found is None:
        return []
    k, true_Pa = found
    return [
        f"where the transducer read {value_from_si('gauge_pressure_Pa', reading[k]):.3g} kPa (t = "
        f"{time[k]:.4g} s) the muscle would have held "
        f"{value_from_si('gauge_pressure_Pa', true_Pa):.3g} kPa: a regulator supplies air or vents it, never a vacuum"
    ]


def uncredited(problem: Problem, fit: Fit, s: Score, baseline: Fit) -> list[str]:
    """Why a fit's gain is not its effects' own: it does not gain significantly on the channels
    its effects change (the gain comes from the baseline moving on channels they cannot touch),
    an instrument's correction makes one of those other channels worse (a general corrector: the
    baseline chases one channel while the correction undoes that on its own), or what it explains
    does not stand out from the structure the base model leaves on the channels it cannot change
    (stands_out). An effect on the physics moves the other channels through the model itself: the
    baseline refitted beside it trades them as the model does."""
    credited = credited_channels(problem, fit)
    out = stands_out(problem, baseline, s, fit.effects)
    if set(credited) != set(problem.channels) and (s.credited_gain < MIN_GAIN or s.credited_ci95[0] <= 0.0):
        out.append(
            f"its gain on the channels it changes ({', '.join(credited)}) is only {s.credited_gain:.3f}; "
            "the rest comes from channels it cannot change"
        )
    if all(corrects_output(problem, e) for e in fit.effects):
        out += [
            f"it makes {c} worse (held-out gain {s.gain[c]:.2f})"
            for c in problem.channels
            if c not in credited and s.gain[c] < -MIN_GAIN
        ]
    return out
