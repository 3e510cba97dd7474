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
   (instruments.stands_out), and an instrument's error is needed where it acts
   (instruments.unfounded) and gains on the force more than such an error takes of a misfit it
   did not make (instruments.misread).
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

from pamkit.diagnosis.coordinates import Finding, findings
from pamkit.diagnosis.series.calibrate import Fit
from pamkit.diagnosis.series.findings import (
    baseline_findings,
    mimicked_by_a_shift,
    moves_against,
    unresolved,
    within_resolution,
)
from pamkit.diagnosis.series.instruments import (
    INFLATION,
    corrects_output,
    holds_vacuum,
    misread,
    noise_ratios,
    rereading,
    shares_a_reading,
    structured,
    uncredited,
    unfounded,
)
from pamkit.diagnosis.series.kinds import Problem
from pamkit.diagnosis.series.score import Score, credited_channels, significance_margin, significant
from pamkit.diagnosis.significance import MIN_GAIN, NONE_WITHIN_NOISE

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
    # the candidate that explains the held-out units significantly better but cannot be named
    # (outdone): what this one fits may be a part of what that one fits
    outdone_by: Judgement | None = None

    @property
    def credible(self) -> bool:
        return not self.findings and not self.objections and not self.unneeded and not self.below_resolution

    @property
    def only_outdone(self) -> bool:
        """Refused for nothing but being outdone (its values credible, that its one objection): it
        would be named but for a candidate that cannot be named explaining more."""
        return (
            self.outdone_by is not None
            and not (self.findings or self.unneeded or self.below_resolution)
            and len(self.objections) == 1
        )

    def reasons(self) -> list[str]:
        return [f.sentence() for f in self.findings] + self.unneeded + self.below_resolution + self.objections


def _same(a: Finding, b: Finding) -> bool:
    return a.parameter == b.parameter and a.bound == b.bound


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
    not refused for a membrane straining to fit the branches' mean); so is one at a bound that
    costs the fit nothing (Finding.costs_nothing) where its interval reaches back into its
    plausible range (a supplied test's friction at zero beside a hose's lag, which draws the loop
    the friction drew: [0, 1.19]; not a membrane replaced by a load cell's offset: [0, 0.036] for a
    plausible [0.33, 3]); one the data do not determine in this fit says nothing wherever it ends
    (identify.py). Except for an effect on the measurement's output that changes every channel
    measured: with no other channel to check it against, it would be a corrector of whatever the
    straining base model misses."""
    calibrated = baseline_findings(baseline)
    corrector = all(corrects_output(problem, e) for e in fit.effects) and set(credited_channels(problem, fit)) == set(
        problem.channels
    )
    own, strain = [], []
    transducer = rereading(problem, fit)
    shares_reading = shares_a_reading(problem, fit)
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
        if transducer and finding.parameter == INFLATION:
            strain.append(finding)  # the declared value was read on the transducer it corrects
            continue
        if in_baseline and finding.costs_nothing and _plausible_within(fit, finding) and not corrector:
            strain.append(finding)  # a flat floor the data leave free to be plausible: reported, not held
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
        # a lone effect's score is its own; a pair's second is held to it beside the first (causes.py)
        unneeded=unfounded(problem, baseline, fit.effects)
        + (misread(problem, s, fit.effects) if len(fit.effects) == 1 else []),
        below_resolution=unresolved(problem, fit),
        near_resolution=within_resolution(problem, fit),
    )


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
    # the candidate the leading cause tied with alone (rule 6), as its best model beside a second:
    # the model the causes named explain more than (refused.tie_beside_a_second)
    untied_from: Judgement | None = None

    @property
    def named(self) -> Judgement | None:
        """Every cause fitted together, judged against the calibrated baseline."""
        return self.causes[-1].judgement if self.causes else None


def _overlap(problem: Problem, a: Fit, b: Fit) -> bool:
    return bool(set(credited_channels(problem, a)) & set(credited_channels(problem, b)))


def explained(problem: Problem, s: Score) -> set[str]:
    """The channels on which a fit gains significantly (at least MIN_GAIN, interval above zero)."""
    return {c for c in problem.channels if s.gain[c] >= MIN_GAIN and s.gain_ci95[c][0] > 0.0}


def read_elsewhere(a: Fit, b: Fit) -> bool:
    """Whether two fits are one effect fitted on two instruments with the same values: each fitted
    parameter inside the other's 95 % interval. In a supplied test the transducer's reading drives
    the model, so a hose lagging the pressure by 0.4 s and a load cell lagging the force by 0.4 s
    draw the same force (bench_near_model, supplied_sensor_lag: 0.750 against 0.768): one delay,
    and which instrument it belongs to is for the values to say, not for the data."""
    if len(a.effects) != 1 or len(b.effects) != 1 or a.effects[0].name() != b.effects[0].name() or a.name == b.name:
        return False
    numbers = [k for k, v in a.params.items() if isinstance(v, float)]
    if not numbers or any(k not in a.intervals or k not in b.intervals for k in numbers):
        return False
    return all(
        b.intervals[k][0] <= a.params[k] <= b.intervals[k][1] and a.intervals[k][0] <= b.params[k] <= a.intervals[k][1]
        for k in numbers
    )


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
    says that the structure may be the base model's, which `candidate` explains no better. The one
    that outdoes it is kept as `candidate.outdone_by` (refused.outdone_beside_a_second)."""
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
        if own_values_only and read_elsewhere(candidate.fit, better.fit):
            continue  # one effect on another instrument, the same values: not a part of it
        if gain_over(better, candidate) >= MIN_GAIN or not own_values_only:
            candidate.outdone_by = better
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
        j.objections += (
            outdone(problem, j, judged) + mimicked_by_a_shift(problem, j, judged) + moves_against(problem, j)
        )
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
