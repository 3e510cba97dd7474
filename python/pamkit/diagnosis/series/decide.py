"""Decisions: held-out gain with its interval, the information criterion, credibility
(plausible, not at a bound, resolvable), and the verdict with its margins.

The rules (docs/diagnosis.md gives them in full, with the measurements behind each):
1. A candidate is *significant* when its combined held-out gain (every channel, weighted by its
   noise: one yardstick for all) is at least MIN_GAIN with the 95 % interval above zero and the
   BIC falls by more than MIN_BIC_DROP.
2. It is *credible* when, besides, every fitted parameter (its own and the baseline's it moved)
   lies inside its physically plausible range and away from the search's bounds, the data
   resolve it (a skew or lag of at least one sample interval, a slack of at least the travel
   between samples), and its effects earn their gain where they act: significant on the channels
   they change, and no other channel made worse (a measurement effect refitted with the
   baseline free moves the baseline to fit the channels it cannot touch; that part is not its);
   what they explain stands out from the base model's misfit on the channels coupled to theirs
   (stands_out), and an instrument's error is needed where it acts (unfounded).
3. The best significant, credible candidate is named, and every cause present beside it (the
   engine adds a second cause). A better candidate that cannot be named is reported beside it
   (`rejected`); when that one explains a channel both explain significantly
   better on the same draws, the lesser is likely a piece of it and is not named either
   (outdone). With nothing named the verdict says what the best rejected fit looks like, and the
   cause is "none" if the baseline already reaches the noise on every channel (rule 4).
4. With no significant candidate the cause is "none" only if every channel's held-out RMSE is
   within NONE_WITHIN_NOISE of its noise; otherwise "unexplained".
5. Every decision carries its margin: how far the deciding number is from its threshold.
6. The named cause must beat every other significant candidate that is credible, or misses
   credibility only narrowly (marginal), on the same bootstrap draws (the paired difference of
   combined held-out gains, its 95 % interval above zero; margin `over_rival`). Otherwise two
   mechanisms explain the data alike, and naming either would be a guess: "unexplained", the
   verdict naming both.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from pamkit._core import EffectStage, GasMode, Resolution
from pamkit.diagnosis import evidence
from pamkit.diagnosis.coordinates import Finding, findings
from pamkit.diagnosis.series.calibrate import Fit
from pamkit.diagnosis.series.findings import baseline_findings, mimicked_by_a_shift, unresolved, within_resolution
from pamkit.diagnosis.series.kinds import Problem
from pamkit.diagnosis.series.score import Score, credited_channels, significance_margin, significant
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
INFLATION = "inflation_gauge_pressure_Pa"  # the sealed gas's calibrated starting pressure
# A named cause leaving a channel this many noise sigmas off tries pairs.
PAIR_TRIGGER = 2.0
PAIR_PARTNERS = 3


@dataclass
class Judgement:
    """A candidate's score and whether it may be named."""

    fit: Fit
    score: Score
    significant: bool
    # its own parameters at a bound or implausible, and the baseline's that it moved there
    findings: list[Finding] = field(default_factory=list)
    objections: list[str] = field(default_factory=list)  # unresolved or uncredited, as sentences
    # the baseline's parameters at a bound or implausible in this fit as in the calibrated baseline
    # alone: the base model straining, which the candidate neither caused nor cured (reported)
    strain: list[Finding] = field(default_factory=list)
    # an instrument's error where its channel was within the noise (unfounded): not named, but as
    # good a reading of the data as a cause it ties with
    unneeded: list[str] = field(default_factory=list)
    # parameters below what one sample resolves (findings.unresolved): a shift or slack of less than
    # a sample mimics the sampling's own artefacts, not a mechanism
    below_resolution: list[str] = field(default_factory=list)
    # every such parameter's interval reaches one sample (findings.within_resolution)
    near_resolution: bool = False
    # the candidate that explains the held-out units as well (rule 6): the data do not tell them apart
    tied_with: Judgement | None = None
    # the rival a named cause beats on the same draws, but by less than a cause explains (close_rival)
    close_rival: Judgement | None = None

    @property
    def credible(self) -> bool:
        return not self.findings and not self.objections and not self.unneeded and not self.below_resolution

    def reasons(self) -> list[str]:
        return [f.sentence() for f in self.findings] + self.unneeded + self.below_resolution + self.objections


def stands_out(problem: Problem, before: Fit, s: Score, effects) -> list[str]:
    """Why what an effect explains on its channels `credited` may be the base model's misfit: on the
    coupled channels, its own stood less than STANDS_OUT times as far above the noise in `before`
    (the model without it) as the other stays with it (`s`), beyond STRUCTURE_LEFT. `effects` are
    the effects whose channels are credited (the fit's, or the ones it adds to `before`)."""
    credited = credited_channels(problem, before, effects)
    others = [c for c in problem.channels if c not in credited and c in COUPLED]
    if not (others and set(credited) & COUPLED):
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
        and all(_corrects_output(problem, e) and not _shifts_in_time(e) for e in effects)
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
        if not _corrects_output(problem, effect):
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


def reads_off(problem: Problem, effect) -> bool:
    """An instrument that reads its channel off by a function of what it reads (an offset, a gain, a
    nonlinearity), as opposed to one that moves its channel in time."""
    return _corrects_output(problem, effect) and not _shifts_in_time(effect)


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
    it makes one of those other channels worse, or what it explains does not stand out from the
    structure the base model leaves on the channels it cannot change (stands_out)."""
    credited = credited_channels(problem, fit)
    out = stands_out(problem, baseline, s, fit.effects)
    if set(credited) != set(problem.channels) and (s.credited_gain < MIN_GAIN or s.credited_ci95[0] <= 0.0):
        out.append(
            f"its gain on the channels it changes ({', '.join(credited)}) is only {s.credited_gain:.3f}; "
            "the rest comes from channels it cannot change"
        )
    out += [
        f"it makes {c} worse (held-out gain {s.gain[c]:.2f})"
        for c in problem.channels
        if c not in credited and s.gain[c] < -MIN_GAIN
    ]
    return out


def _same(a: Finding, b: Finding) -> bool:
    return a.parameter == b.parameter and a.bound == b.bound


def _corrects_output(problem: Problem, effect) -> bool:
    """An effect that edits what the instruments read of the model (a load cell's offset), not what
    drives it: a supplied test's transducer error changes the pressure the muscle is driven with,
    whose force then follows the physics."""
    supplied_input = problem.experiment.gas == GasMode.supplied and effect.reads_supplied_pressure()
    return effect.stage() == EffectStage.measurement and not supplied_input


def _shifts_in_time(effect) -> bool:
    """An effect that moves its channel in time (a skew, a lag): its first parameter must resolve
    the sample interval."""
    parameters = effect.parameters()
    return bool(parameters) and parameters[0].resolution == Resolution.sample_interval


def _rereading(problem: Problem, fit: Fit) -> list:
    """A fit's corrections of a sealed test's pressure transducer. The declared inflation pressure,
    whose search box is the hand-read transducer's 5 %, was read on that transducer, so the box
    does not bind the fit (a 0.97 gain and a 4.8 kPa offset put the truth 6 % from the reading at
    56 kPa); and a correction and the inflation pressure split one reading between them, so where
    along it the fit ended is not what the data say (a 10 kPa offset fitted at 15.5 kPa, 9.4-21.7 kPa
    its interval, with the inflation pressure 5 % low)."""
    if problem.experiment.gas != GasMode.sealed:
        return []
    return [e for e in fit.effects if _corrects_output(problem, e) and list(e.channels_changed()) == [PRESSURE]]


def _plausible_within(fit: Fit, finding: Finding) -> bool:
    """Whether the 95 % interval of a value found outside its plausible range reaches into that
    range: the data do not say it is implausible (a friction scale ended at 0.05 in a test whose
    crosshead holds still, [0, 0.95] its interval)."""
    band = fit.intervals.get(finding.parameter)
    if band is None:
        return False
    low, high = band
    return low <= finding.plausible[1] and high >= finding.plausible[0]


def judge(problem: Problem, fit: Fit, s: Score, baseline: Fit) -> Judgement:
    """`fit` scored by `s` against the calibrated `baseline`: significant, and credible unless
    its own parameters, or a baseline parameter it moved to a bound or out of its plausible range,
    say otherwise (rule 3). A baseline parameter that the calibrated baseline leaves there too is
    the base model's strain, reported beside the candidate and not held against it: the cause
    neither made nor cured it (a hysteresis, seen between the branches of an isotonic sweep, is
    not refused for a membrane straining to fit the branches' mean); one the data do not determine
    in this fit says nothing wherever it ends (identify.py). Except for an effect on the
    measurement's output that changes every channel measured: with no other channel to check it
    against, it would be a corrector of whatever the straining base model misses."""
    calibrated = baseline_findings(baseline)
    corrector = all(_corrects_output(problem, e) for e in fit.effects) and set(credited_channels(problem, fit)) == set(
        problem.channels
    )
    own, strain = [], []
    rereading = _rereading(problem, fit)
    shares_reading = {p.name for e in rereading for p in e.parameters()}
    for finding in findings(fit):
        in_baseline = finding.parameter in baseline.coordinates
        if in_baseline and finding.parameter in fit.undetermined:
            continue  # not determined by the data: its bound says nothing (identify.py)
        if (
            finding.bound is None
            and (in_baseline or finding.parameter in shares_reading)
            and _plausible_within(fit, finding)
        ):
            continue  # a nuisance, or a share of one reading, the data leave free to be plausible
        if rereading and finding.parameter == INFLATION:
            strain.append(finding)  # the declared value was read on the transducer it corrects
            continue
        inherited = in_baseline and any(_same(finding, f) for f in calibrated)
        (strain if inherited and not corrector else own).append(finding)
    if corrector:  # fitted on the calibrated baseline, whose strain it then corrects
        own += [f for f in calibrated if not any(_same(f, mine) for mine in own)]
    return Judgement(
        fit,
        s,
        significant(s),
        own,
        uncredited(problem, fit, s, baseline) + holds_vacuum(problem, fit),
        strain,
        unneeded=unfounded(problem, baseline, fit.effects),
        below_resolution=unresolved(problem, fit),
        near_resolution=within_resolution(problem, fit),
    )


def structured(problem: Problem, fit: Fit, factor: float) -> list[str]:
    """Channels whose held-out residual RMS is above `factor` times their noise."""
    return [
        c
        for c in problem.channels
        if evidence.rmse((fit.predicted[c] - problem.measured[c])[problem.held_mask]) > factor * problem.sigma[c]
    ]


def noise_ratios(problem: Problem, fit: Fit) -> dict[str, float]:
    """Held-out RMSE over noise, per channel."""
    return {
        c: evidence.rmse((fit.predicted[c] - problem.measured[c])[problem.held_mask]) / problem.sigma[c]
        for c in problem.channels
    }


@dataclass
class Cause:
    """One cause present in the data: the model with it and the causes named before it, and the
    gain it adds on its own (that model scored against the one without it)."""

    label: str  # the candidate's label (an effect, with its channel option where it has one)
    judgement: Judgement  # the model up to this cause, judged against the calibrated baseline
    own: Score  # this cause's own gain: against the model without it, credited on its channels


@dataclass
class Decision:
    """The verdict and what it rests on."""

    cause: str  # the leading cause, "none" or "unexplained"
    causes: list[Cause]  # every cause present, the leading one first
    rejected: Judgement | None  # the best significant candidate, when it is not among the causes
    margins: dict[str, float]  # each decision's distance from its threshold
    left_structure: list[str]  # channels above NONE_WITHIN_NOISE after the causes: the remainder

    @property
    def named(self) -> Judgement | None:
        """Every cause fitted together, judged against the calibrated baseline."""
        return self.causes[-1].judgement if self.causes else None


def _overlap(problem: Problem, a: Fit, b: Fit) -> bool:
    return bool(set(credited_channels(problem, a)) & set(credited_channels(problem, b)))


def explained(problem: Problem, s: Score) -> set[str]:
    """The channels on which a fit gains significantly (at least MIN_GAIN, interval above zero)."""
    return {c for c in problem.channels if s.gain[c] >= MIN_GAIN and s.gain_ci95[c][0] > 0.0}


def keeps_gain(own: Score) -> bool:
    """A cause's own gain (against the model without it) is significant, on its own channels too."""
    return significant(own) and own.credited_gain >= MIN_GAIN and own.credited_ci95[0] > 0.0


def outdone(problem: Problem, candidate: Judgement, judged: list[Judgement]) -> list[str]:
    """Why `candidate` is only a part of what a better fit explains: a significant candidate that
    cannot be named explains the held-out units significantly better on the same draws, on a channel
    both explain. What `candidate` fits is then likely a piece of that (a load cell's nonlinearity
    absorbing the shape a wrong braid wind leaves), so naming it would be a guess. Except where the
    better one is refused only for its own values and is better by less than a cause's worth
    (`gain_over` below MIN_GAIN): it explains the same thing with a mechanism the values rule out,
    not more of it (in a supplied test a load cell lagging an implausible 1.5 s draws the force a
    transducer lagging 1.5 s draws: 0.899 against 0.898). Values only narrowly out (`marginal`)
    leave it as good a reading as `candidate`: the two are untold apart. A better one refused for
    what it explains (not standing out from the base model's misfit, an instrument not needed)
    says that the structure may be the base model's, which `candidate` explains no better."""
    mine = explained(problem, candidate.score)
    for better in judged:
        if better is candidate:
            break
        if not better.significant or better.credible or not mine & explained(problem, better.score):
            continue
        if not (better.findings or better.objections or better.unneeded or better.near_resolution):
            continue  # only below what a sample resolves: the sampling's artefact, of which no cause is a part
        low = float(np.percentile(better.score.combined_samples - candidate.score.combined_samples, 2.5))
        if low <= 0.0:
            continue
        gains = f"(gain {better.score.combined_gain:.3f} against {candidate.score.combined_gain:.3f})"
        own_values_only = bool(better.findings) and not (better.objections or better.unneeded)
        if gain_over(better, candidate) >= MIN_GAIN or not own_values_only:
            return [
                f"{better.fit.name} explains the held-out units significantly better {gains} but cannot be named "
                f"({'; '.join(better.reasons())}): this may be a part of what it fits"
            ]
        if marginal(better):
            return [
                f"{better.fit.name} explains the held-out units as well {gains} and misses being named only "
                f"narrowly ({'; '.join(better.reasons())}): the data do not tell the two apart"
            ]
    return []


# A value outside its plausible range by less than this factor of the range's end is a near miss:
# plausible ranges are a physicist's bounds, not sharp ones, and a base model that strains moves a
# fitted value by tens of per cent (a fibre stiffness fitted at 46 N where the muscle's was 100 N).
NEAR_PLAUSIBLE = 2.0


def marginal(j: Judgement) -> bool:
    """A candidate that cannot be named only because a parameter lies just outside its plausible
    range (within NEAR_PLAUSIBLE of its end; none at a search bound, no other objection), or only
    because it is an instrument's error on a channel the base model already fits within the noise
    (unneeded), or only because a shift is fitted below one sample with its interval reaching one
    (near_resolution): not a cause, but a rival that explains the data as well as a cause is one
    the data do not rule out. Naming the cause beside it would read a tie as a win."""
    if j.below_resolution and j.near_resolution and not (j.objections or j.findings or j.unneeded):
        return True
    if j.objections or j.below_resolution:
        return False
    if j.unneeded:
        return not j.findings
    if not j.findings:
        return False
    for f in j.findings:
        if f.bound is not None:
            return False
        low, high = f.plausible
        end = low if f.value < low else high
        if end == 0.0 or not math.isfinite(end) or not 1.0 / NEAR_PLAUSIBLE <= f.value / end <= NEAR_PLAUSIBLE:
            return False
    return True


def gain_over(lead: Judgement, rival: Judgement) -> float:
    """The lead's combined held-out gain with the rival's model for the baseline: the share of the
    squared error the rival leaves that the lead explains. Below MIN_GAIN, the lead would not be a
    cause over the rival (rule 1), though it beats it on the same draws: named, it carries the
    rival as a close one (`close_rival`) and the test that would confirm it (separate.py)."""
    left = 1.0 - rival.score.combined_gain
    return (lead.score.combined_gain - rival.score.combined_gain) / left if left > 0.0 else 0.0


def decide(problem: Problem, baseline: Fit, judged: list[Judgement]) -> Decision:
    """The leading cause (rules 3-6 of the module docstring), `judged` sorted by held-out gain,
    best first: the best candidate that is significant and credible. Its rivals are the other
    significant candidates acting on a channel it acts on that are credible, or miss credibility
    only by a parameter just outside its plausible range (marginal): one that explains the held-out
    units as well (rule 6) leaves the two untold apart. A better candidate that is not
    credible is reported (`rejected`) beside the cause, not in its place: what it fits with an
    implausible parameter is part of the remainder."""
    best = next((j for j in judged if j.significant), None)
    margins: dict[str, float] = {}
    if best is not None:
        margins["significance"] = significance_margin(best.score)
        runner = next((j for j in judged if j is not best), None)
        if runner is not None:
            margins["over_runner_up"] = best.score.combined_gain - runner.score.combined_gain
    present = [j for j in judged if j.significant and j.credible]
    for j in present:
        j.objections += outdone(problem, j, judged) + mimicked_by_a_shift(problem, j, judged)
    present = [j for j in present if j.credible]
    lead = present[0] if present else None
    if lead is not None:
        rivals = [
            j
            for j in judged
            if j is not lead and j.significant and (j in present or marginal(j)) and _overlap(problem, lead.fit, j.fit)
        ]
        closest = [
            (float(np.percentile(lead.score.combined_samples - j.score.combined_samples, 2.5)), j) for j in rivals
        ]
        rival = min(closest, key=lambda pair: pair[0])[1] if closest else None
        if rival is not None:
            low, high = np.percentile(lead.score.combined_samples - rival.score.combined_samples, [2.5, 97.5])
            margins["over_rival"] = float(low)
            nearest = min(rivals, key=lambda j: gain_over(lead, j))
            lead.close_rival = nearest if gain_over(lead, nearest) < MIN_GAIN else None
            if low <= 0.0:  # rule 6: the data cannot tell the two apart
                lead.tied_with = rival
                # Its interval may lie wholly below zero (a rival ranked behind on its point gain,
                # ahead on the draws): the message says which.
                how, where = ("better", "lies below zero") if high < 0.0 else ("as well", "holds zero")
                lead.objections.append(
                    f"{rival.fit.name} explains the held-out units {how} (gain {rival.score.combined_gain:.3f} "
                    f"against {lead.score.combined_gain:.3f}; the difference's 95 % interval [{low:.3f}, {high:.3f}] "
                    f"{where}): the data do not tell the two apart"
                )
    if lead is not None and lead.credible:
        margins["lead_significance"] = significance_margin(lead.score)
        rejected = best if best is not lead else None
        cause = Cause(lead.fit.name, lead, lead.score)
        return Decision(
            lead.fit.effects[0].name(), [cause], rejected, margins, structured(problem, lead.fit, NONE_WITHIN_NOISE)
        )
    rejected = lead if lead is not None else best
    ratios = noise_ratios(problem, baseline)
    margins["within_noise"] = float(NONE_WITHIN_NOISE - max(ratios.values()))
    if judged and best is None:
        margins["best_candidate_below_significance"] = -significance_margin(judged[0].score)
    left = [c for c, r in ratios.items() if r > NONE_WITHIN_NOISE]
    return Decision("unexplained" if left else "none", [], rejected, margins, left)
