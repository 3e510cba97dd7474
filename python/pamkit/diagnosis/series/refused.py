"""Candidates refused alone that a second cause may clear (rule 6 of docs/diagnosis.md): two
that tie alone told apart beside a second, and a lead outdone by a candidate that cannot be named
that, beside a second, explains as much with credible values. series/causes.py fits the pairs."""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from pamkit.diagnosis.series.calibrate import Fit
from pamkit.diagnosis.series.causes import add_cause, explains_more, pairs_beside, placed, reads_explained, resolves
from pamkit.diagnosis.series.decide import PAIR_TRIGGER, Cause, Decision, Judgement, keeps_gain, outdone
from pamkit.diagnosis.series.instruments import structured
from pamkit.diagnosis.series.kinds import Problem
from pamkit.diagnosis.series.score import score
from pamkit.diagnosis.significance import NONE_WITHIN_NOISE


def _untied(j: Judgement) -> Judgement:
    """`j` as judged without its rival: its objections less the tie's, which decide() adds last, to
    a lead that was credible before it."""
    objections = j.objections[:-1] if j.tied_with is not None else j.objections
    return replace(j, objections=list(objections), tied_with=None, close_rival=None)


def _lone(problem: Problem, decision: Decision, alone: Judgement) -> Decision:
    """`decision` with `alone` named as the lone cause, nothing rejected: what add_cause extends."""
    return replace(
        decision,
        cause=alone.fit.effects[0].name(),
        causes=[Cause(alone.fit.name, alone, alone.score)],
        rejected=None,
        left_structure=structured(problem, alone.fit, NONE_WITHIN_NOISE),
    )


def tie_beside_a_second(
    problem: Problem, baseline: Fit, decision: Decision, judged: list[Judgement], factories, seed: int, threads, report
) -> Decision | None:
    """Two candidates the data do not tell apart alone (rule 6) may be told apart beside a second
    cause. A time skew and a lag of the pressure transducer open the same loop; beside a slow
    leak's drift the skew leaves the pressure within its noise and the lag does not (near-model
    leak+time_skew: the skew and the leak gain 0.92-0.95, the lag with its best second 0.39-0.60).
    Each of the two that leaves structure calling for a second (PAIR_TRIGGER) is given the second
    `add_cause` would add beside it as the lone cause. Where one's pair explains the held-out units
    better than the other's best model (`explains_more`: the paired difference's 95 % interval above
    zero, and a cause's worth of what that model leaves), the one credible but for the tie, its
    second not the other, and both kept when their instruments are checked (`reads_explained`),
    the tie is broken: the one leads with its second beside it. None where the tie stands."""
    tied = decision.rejected
    if decision.causes or tied is None or tied.tied_with is None:
        return None
    sides = []  # each side untied, and its decision as the lone cause with a second where one holds
    for side in (tied, tied.tied_with):
        alone = _untied(side)
        lone = _lone(problem, decision, alone)
        if structured(problem, alone.fit, PAIR_TRIGGER):
            lone = add_cause(problem, baseline, lone, judged, factories, seed, threads, report)
        sides.append((alone, lone))
    for (one, beside), (other, against) in (sides, sides[::-1]):
        paired = len(beside.causes) == 2 and beside.causes[0].judgement is one
        if not (paired and one.credible) or beside.causes[1].label == other.fit.name:
            continue
        if not explains_more(beside.named, against.named):
            continue
        checked = reads_explained(problem, baseline, beside)
        if len(checked.causes) != 2:
            continue
        report(
            f"{one.fit.name} and {other.fit.name} tie alone; beside {beside.causes[1].label}, {one.fit.name} explains "
            f"the held-out units better than {other.fit.name} does with its best second: {one.fit.name} leads"
        )
        low = float(np.percentile(beside.named.score.combined_samples - against.named.score.combined_samples, 2.5))
        return replace(
            checked, margins={**decision.margins, "over_tied_beside_a_second": low}, untied_from=against.named
        )
    return None


def outdone_beside_a_second(
    problem: Problem, baseline: Fit, decision: Decision, judged: list[Judgement], factories, seed: int, threads, report
) -> Decision | None:
    """A candidate refused only because one that cannot be named explains the held-out units
    significantly better (decide.outdone: it may be a part of what that one fits) may be the whole
    of it beside a second cause. A dead volume damps the pressure swing as a transducer reading
    11 % low does; beside a load cell's nonlinearity it explains the force too, and then more than
    the transducer's implausible gain (near-model dead_volume+load_cell, medium seed 4: 0.846
    against 0.820, each at its truth's values). The best such candidate is given the second
    add_cause would add; where the pair is outdone by nothing (no candidate that cannot be named
    explains the held-out units significantly better on the same draws) and both are kept when
    their instruments are checked, the pair is named, the outdoing one reported beside it. Where
    none is named, structure is left, and a pair that cannot be named either explains more than
    the outdoing one, that pair is reported as what the data look like (`rejected`). None
    otherwise."""
    if decision.causes:
        return None
    # The lead but for what outdoes it: the best significant candidate that outdoes none, refused
    # for nothing but being outdone (its values credible, that its one objection). Below one
    # refused otherwise it would not lead if it could be named: a viscoelastic bladder outdone by an
    # implausible load cell, below a leak tied with a transducer's offset, is no lead (near-model
    # leak, weak seed 3, where the bladder beside the leak was named before this check).
    outdoing = [j.outdone_by for j in judged if j.outdone_by is not None]
    blocked = next((j for j in judged if j.significant and not any(j is o for o in outdoing)), None)
    if blocked is None or not blocked.only_outdone:
        return None
    better = blocked.outdone_by
    alone = replace(blocked, objections=[], outdone_by=None)
    lone = _lone(problem, decision, alone)
    report(
        f"{better.fit.name} explains more than {alone.fit.name} but cannot be named: {alone.fit.name} beside a second"
    )
    pairs = pairs_beside(problem, baseline, alone, judged, factories, seed, threads, report)
    paired = add_cause(problem, baseline, lone, judged, factories, seed, threads, report, pairs)
    if len(paired.causes) == 2 and not outdone(problem, paired.named, judged):
        checked = reads_explained(problem, baseline, paired)
        if len(checked.causes) == 2:
            report(
                f"{paired.named.fit.name} explains the held-out units as well as {better.fit.name} or better: "
                "both named"
            )
            low = float(np.percentile(paired.named.score.combined_samples - better.score.combined_samples, 97.5))
            return replace(
                checked, rejected=better, margins={**decision.margins, "beside_a_second_against_outdoing": low}
            )
    # None named: a pair that explains more than the outdoing one, each of its causes gaining on
    # its own beside the other, is still the better picture of the data, and its values say what
    # keeps it from being named (a dead volume beside a load cell reading 23 N at zero force,
    # against an 11 % transducer). A pair one of whose effects the data leave at nothing (its
    # intervals holding its neutral values) is the other alone: on the near-model bench a dead
    # volume of 4e-12 beside a load cell was such a pair, and a leak of time constant 4e19 s, their
    # gain the baseline's refit. Within the noise (`none`) nothing is left to picture.
    if decision.cause != "unexplained":
        return None
    looks = [
        pair
        for partner, pair, own in pairs
        if pair.significant
        and not pair.unneeded
        and pair.score.combined_gain > better.score.combined_gain
        and all(placed(pair.fit, effect) for effect in pair.fit.effects)
        and resolves(problem, alone.fit, pair.fit)
        and keeps_gain(own)
        and keeps_gain(score(problem, partner.fit, pair.fit, np.random.default_rng(seed), credit=alone.fit.effects))
    ]
    if not looks:
        return None
    best = max(looks, key=lambda j: j.score.combined_gain)
    report(f"{best.fit.name} explains more than {better.fit.name} but cannot be named either")
    return replace(decision, rejected=best)
