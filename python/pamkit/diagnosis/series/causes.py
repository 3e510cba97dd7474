"""More than one cause: what the causes named leave tried beside them (a second cause), the first
cause's nearest rival fitted beside that second, a lone cause that stands in for its rival with a
second, and the instrument whose channel the causes leave structured dropped (rule 6 of
docs/diagnosis.md; candidates refused alone that a second clears: series/refused.py). A real rig
has more than one thing wrong."""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from pamkit.diagnosis.coordinates import configure
from pamkit.diagnosis.series.calibrate import Fit, thread_pool
from pamkit.diagnosis.series.candidates import fit_pair
from pamkit.diagnosis.series.decide import (
    PAIR_PARTNERS,
    PAIR_TRIGGER,
    Cause,
    Decision,
    Judgement,
    gain_over,
    judge,
    keeps_gain,
)
from pamkit.diagnosis.series.findings import off_neutral
from pamkit.diagnosis.series.instruments import (
    STRUCTURE_LEFT,
    misread,
    noise_ratios,
    reads_left,
    stands_out,
    structured,
    unfounded,
)
from pamkit.diagnosis.series.kinds import Problem
from pamkit.diagnosis.series.score import Score, score
from pamkit.diagnosis.significance import MIN_GAIN, NONE_WITHIN_NOISE


def _in_noise_units(problem: Problem, values: dict[str, np.ndarray]) -> np.ndarray:
    """`values` on the fitted units, every channel in units of its noise, stacked."""
    return np.concatenate([values[c][problem.fit_mask] / problem.sigma[c] for c in problem.channels])


def _share(change: np.ndarray, left: np.ndarray) -> float:
    """The share of the remainder `left` that a step along `change` takes at its best size."""
    size = float(change @ change)
    return (float(change @ left) ** 2 / size / float(left @ left)) if size > 0 else 0.0


def _remainder(problem: Problem, fit: Fit) -> np.ndarray:
    """What `fit` leaves of the measured channels, in noise units (`_in_noise_units`)."""
    return _in_noise_units(problem, {c: problem.measured[c] - fit.predicted[c] for c in problem.channels})


def _ranked(problem: Problem, baseline: Fit, left: np.ndarray, others: list[Judgement]) -> list[Judgement]:
    """`others` by the share of a first cause's remainder `left` that each one's change of the
    prediction (its fit against the calibrated baseline) takes; those that take none left out.
    Credible alone or not, significant alone or not: beside a first cause one may be what it could
    not be alone (a pressure offset whose channel did not stand out from a heat exchange's misfit)."""
    shares = [
        _share(
            _in_noise_units(problem, {c: j.fit.predicted[c] - baseline.predicted[c] for c in problem.channels}), left
        )
        for j in others
    ]
    order = np.argsort(shares)[::-1]
    return [others[i] for i in order if shares[i] > 0.0]


def _partners(
    problem: Problem, baseline: Fit, single: Judgement, others: list[Judgement], factories
) -> list[Judgement]:
    """The candidates to fit beside `single`: the PAIR_PARTNERS first of `_ranked`, and the one more
    whose step beside `single` takes most of what it leaves (`_step_beside`): a fit alone may see
    nothing of what a candidate explains beside the first cause. The pairs are judged."""
    left = _remainder(problem, single.fit)
    partners = _ranked(problem, baseline, left, others)[:PAIR_PARTNERS]
    beside = _step_beside(problem, single.fit, left, [j for j in others if j not in partners], factories)
    return partners + ([beside] if beside is not None else [])


def _step_beside(problem: Problem, single: Fit, left: np.ndarray, others: list[Judgement], factories):
    """The candidate whose step from its search's start, added to `single`'s fit, takes the largest
    share of what `single` leaves (`left`, in noise units), or None: one run each. A slow leak
    under a half-second skew of the pressure gains nothing fitted alone (the skew's misfit dwarfs
    its drift) and so does not change the prediction the first way, while the skew leaves the
    pressure growing away over the test, its drift (near-model leak+time_skew, medium seed 5)."""
    best, best_share = None, 0.0
    for j in others:
        first, second = factories[single.name](), factories[j.fit.name]()
        first_space, second_space = problem.search_space(first), problem.search_space(second)
        if not second_space:
            continue
        configure(first, first_space, np.array([c.of(single.params[c.name]) for c in first_space]))
        configure(second, second_space, np.array([c.start for c in second_space]))
        try:
            predicted = problem.predictor.predict(single.baseline_x, [first, second])
        except (ValueError, RuntimeError):
            continue  # a step the model cannot run is no direction
        share = _share(
            _in_noise_units(problem, {c: predicted[c] - single.predicted[c] for c in problem.channels}), left
        )
        if share > best_share:
            best, best_share = j, share
    return best


def placed(fit: Fit, effect) -> bool:
    """Whether the data place one of `effect`'s values in `fit` (a pair's, keyed by the effect's
    name) off its neutral value (findings.off_neutral): the effect is there, not fitted at nothing.
    An effect none of whose fitted values has a neutral value (a band, a slip distance) cannot be at
    nothing."""
    judged = off_neutral(fit, effect, f"{effect.name()}.")
    return any(judged.values()) or not judged


def second_holds(problem: Problem, first: Fit, pair: Judgement, own: Score) -> bool:
    """Whether the second effect of `pair`, fitted beside `first`, may be named with it: every
    parameter of the pair credible, the second placed off its neutral values by the data, its own
    gain (`own`, the pair scored against `first`) significant on its channels, and what it explains
    there standing out from what the base model leaves on the channels it cannot change, and needed
    where it reads, as a single cause's must (instruments.stands_out, instruments.unfounded,
    instruments.misread). A second whose interval holds its neutral value gains only what the
    calibration's refit beside it does: a dead volume of 0.15 % [0, 1.1 %] beside a load cell, its
    own gain 0.20 from the bladder's modulus refitted to nothing (near-model load_cell, strong seed
    14)."""
    second = pair.fit.effects[1:]
    return (
        pair.credible
        and all(placed(pair.fit, effect) for effect in second)
        and keeps_gain(own)
        and not stands_out(problem, first, own, second)
        and not unfounded(problem, first, second)
        and not misread(problem, own, second)
    )


def resolves(problem: Problem, single: Fit, pair: Fit) -> bool:
    """Whether `pair` takes every channel `single` left above PAIR_TRIGGER (the structure that
    called for a second cause) within STRUCTURE_LEFT. A second cause that leaves it there explains
    a share of a misfit it does not account for: on the near-model bench, a dead volume of 1.5-3 %
    took 8-18 % of the force a friction with memory and flatter ends left beside a lag or a skew,
    the force still 1.7-1.9 times its noise; every right second cause left it within 1.2 times."""
    before, after = noise_ratios(problem, single), noise_ratios(problem, pair)
    return all(after[c] <= STRUCTURE_LEFT for c in problem.channels if before[c] > PAIR_TRIGGER)


def pairs_beside(
    problem: Problem, baseline: Fit, single: Judgement, judged: list[Judgement], factories, seed: int, threads, report
) -> list[tuple[Judgement, Judgement, Score]]:
    """The candidates `_partners` picks, each fitted beside `single`: (the partner alone, the pair
    judged against the calibrated baseline, the partner's own gain beside `single`), for the pairs
    whose fit ran."""
    taken = {e.name() for e in single.fit.effects}
    partners = _partners(
        problem, baseline, single, [j for j in judged if j.fit.effects[0].name() not in taken], factories
    )
    if not partners:
        return []
    left = structured(problem, single.fit, PAIR_TRIGGER)
    report(
        (f"{single.fit.name} leaves {', '.join(left)} above noise: " if left else "")
        + f"trying {single.fit.name} with {', '.join(p.fit.name for p in partners)}"
    )
    out = []
    # A second holds only with a cause's worth of its own beside the first (second_holds): where a
    # step from the pair's scan cannot take the first's fitted chi-square SCREEN_DROP lower, the
    # pair is not fitted further.
    beat = sum(single.fit.training_chi2.values())
    with thread_pool(threads) as pool:
        futures = [
            (
                p,
                pool.submit(
                    fit_pair,
                    problem,
                    single.fit,
                    factories[single.fit.name],
                    factories[p.fit.name],
                    f"{single.fit.name}+{p.fit.name}",
                    beat,
                ),
            )
            for p in partners
        ]
        for partner, future in futures:
            pair = future.result()
            if pair.error is not None:
                continue
            own = score(problem, single.fit, pair, np.random.default_rng(seed), credit=pair.effects[1:])
            candidate = judge(problem, pair, score(problem, baseline, pair, np.random.default_rng(seed)), baseline)
            out.append((partner, candidate, own))
    return out


def add_cause(
    problem: Problem,
    baseline: Fit,
    decision: Decision,
    judged: list[Judgement],
    factories,
    seed: int,
    threads,
    report,
    pairs: list[tuple[Judgement, Judgement, Score]] | None = None,
) -> Decision:
    """The causes named leave structure: try the next candidates beside them (`pairs`, fitted by
    pairs_beside where not given), and add the one that gains most, if it gains significantly on
    its own channels over the causes alone (rule 6 of docs/diagnosis.md) with every parameter of the
    pair credible. A real rig has more than one thing wrong; what no partner explains stays the
    remainder."""
    single = decision.causes[-1].judgement
    if pairs is None:
        pairs = pairs_beside(problem, baseline, single, judged, factories, seed, threads, report)
    best: Cause | None = None
    alone: Judgement | None = None  # the partner of `best` fitted alone
    for partner, candidate, own in pairs:
        if (
            second_holds(problem, single.fit, candidate, own)
            and resolves(problem, single.fit, candidate.fit)
            and (best is None or candidate.score.combined_gain > best.judgement.score.combined_gain)
        ):
            best, alone = Cause(partner.fit.name, candidate, own), partner
    if best is None:
        return decision
    # Each cause must gain on its own beside the other: the first may have been standing in for the
    # second (a load cell's offset for a viscoelastic bladder's hysteresis), which then leads alone.
    first = score(problem, alone.fit, best.judgement.fit, np.random.default_rng(seed), credit=single.fit.effects)
    if not keeps_gain(first):
        if not (alone.significant and alone.credible):
            return decision  # the pair's second cannot be named alone, nor the first beside it
        report(f"{single.fit.name} adds nothing significant beside {alone.fit.name}: {alone.fit.name} leads alone")
        left = structured(problem, alone.fit, NONE_WITHIN_NOISE)
        return replace(
            decision,
            cause=alone.fit.effects[0].name(),
            causes=[Cause(alone.fit.name, alone, alone.score)],
            left_structure=left,
        )
    other = _other_first(problem, baseline, single, best, alone, judged, factories, seed, report)
    if other is not None:
        rival, pair = other
        causes = [Cause(rival.fit.name, rival, rival.score), pair]
        return replace(
            decision,
            cause=rival.fit.effects[0].name(),
            causes=causes,
            left_structure=structured(problem, pair.judgement.fit, NONE_WITHIN_NOISE),
        )
    causes = [*decision.causes, best]
    return replace(decision, causes=causes, left_structure=structured(problem, best.judgement.fit, NONE_WITHIN_NOISE))


def _other_first(problem, baseline, single, best, alone, judged, factories, seed, report):
    """The first cause's nearest rival beside the second: alone the first may have won by taking a
    part of what the second explains (compliant fibres absorbing a load cell's curvature, where the
    truth is a dead volume). The significant, credible candidate behind the first that explains
    most is fitted with the same second; if that pair explains the held-out units significantly
    better on the same draws, with the second still gaining on its own beside it and the rival
    beside the second, and every parameter credible, the rival leads in the first's place:
    (the rival, the pair as a Cause), else None."""
    second = best.judgement.fit.effects[1].name()
    rivals = [
        j
        for j in judged
        if j is not single
        and j is not alone
        and j.significant
        and j.credible
        and len(j.fit.effects) == 1
        and j.fit.effects[0].name() != second
    ]
    if not rivals:
        return None
    rival = rivals[0]  # judged is sorted by held-out gain
    label = f"{rival.fit.name}+{best.label}"
    pair = fit_pair(problem, rival.fit, factories[rival.fit.name], factories[best.label], label)
    if pair.error is not None:
        return None
    candidate = judge(problem, pair, score(problem, baseline, pair, np.random.default_rng(seed)), baseline)
    low = float(np.percentile(candidate.score.combined_samples - best.judgement.score.combined_samples, 2.5))
    if not (candidate.credible and low > 0.0):
        return None
    own = score(problem, rival.fit, pair, np.random.default_rng(seed), credit=pair.effects[1:])
    first = score(problem, alone.fit, pair, np.random.default_rng(seed), credit=rival.fit.effects)
    if not (keeps_gain(own) and keeps_gain(first)):
        return None
    report(f"{label} explains the held-out units better than {best.judgement.fit.name}: {rival.fit.name} leads")
    return rival, Cause(best.label, candidate, own)


def explains_more(pair: Judgement, alone: Judgement) -> bool:
    """Whether `pair` explains the held-out units better than `alone` on the same draws (the paired
    difference's 95 % interval above zero) and by a cause's worth of what `alone` leaves
    (gain_over at least MIN_GAIN): what a cause must add to be named (rule 1)."""
    low = float(np.percentile(pair.score.combined_samples - alone.score.combined_samples, 2.5))
    return low > 0.0 and gain_over(pair, alone) >= MIN_GAIN


def rival_beside_a_second(
    problem: Problem, baseline: Fit, decision: Decision, judged: list[Judgement], factories, seed: int, report
) -> Decision:
    """A lone cause that leaves nothing calling for a second may still stand in for its rival with
    a second: compliant fibres soften the force and damp the pressure swing, what a dead volume and
    a load cell's nonlinearity do together. The rival (the best significant, credible candidate
    behind it) is fitted beside the candidate that most explains what the rival leaves; the pair
    leads in the cause's place if it is credible, each of its causes gains on its own beside the
    other, and it explains more (`explains_more`) than the cause alone and than the cause beside
    the same second where the second holds beside the cause (`second_holds`). Otherwise the second
    is as much the cause's partner as the rival's, and the cause stands. A second that adds no
    cause's worth beside the cause is no partner of it: the cause alone is what the pair must beat
    (near-model dead_volume+load_cell, medium seed 5: the fibres beside the load cell gain 0.658 →
    0.668, not a cause's worth, where the dead volume beside it reaches 0.669 with the truth's
    values)."""
    if len(decision.causes) != 1:
        return decision
    lead = decision.causes[0].judgement
    rival = next(
        (j for j in judged if j is not lead and j.significant and j.credible and len(j.fit.effects) == 1), None
    )
    if rival is None:
        return decision
    taken = {lead.fit.effects[0].name(), rival.fit.effects[0].name()}
    others = [j for j in judged if j.fit.effects[0].name() not in taken]
    ranked = _ranked(problem, baseline, _remainder(problem, rival.fit), others)
    if not ranked:
        return decision
    second = ranked[0]
    label = f"{rival.fit.name}+{second.fit.name}"
    # The pair leads only by explaining more than the lead: where a step cannot take its fitted
    # chi-square below the lead's, its fit is spared (such pairs took 9 % of bench_diagnose's time,
    # in 31 of its 39 diagnoses).
    beat = sum(lead.fit.training_chi2.values())
    fit = fit_pair(problem, rival.fit, factories[rival.fit.name], factories[second.fit.name], label, beat=beat)
    if fit.error is not None:
        return decision
    pair = judge(problem, fit, score(problem, baseline, fit, np.random.default_rng(seed)), baseline)
    own = score(problem, rival.fit, fit, np.random.default_rng(seed), credit=fit.effects[1:])
    first = score(problem, second.fit, fit, np.random.default_rng(seed), credit=rival.fit.effects)
    if not (second_holds(problem, rival.fit, pair, own) and keeps_gain(first) and explains_more(pair, lead)):
        return decision
    beside = fit_pair(
        problem, lead.fit, factories[lead.fit.name], factories[second.fit.name], f"{lead.fit.name}+{second.fit.name}"
    )
    if beside.error is None:
        lead_pair = judge(problem, beside, score(problem, baseline, beside, np.random.default_rng(seed)), baseline)
        lead_own = score(problem, lead.fit, beside, np.random.default_rng(seed), credit=beside.effects[1:])
        if second_holds(problem, lead.fit, lead_pair, lead_own) and not explains_more(pair, lead_pair):
            return decision
    report(
        f"{label} explains the held-out units better than {lead.fit.name} alone or beside it: {rival.fit.name} leads"
    )
    return replace(
        decision,
        cause=rival.fit.effects[0].name(),
        causes=[Cause(rival.fit.name, rival, rival.score), Cause(second.fit.name, pair, own)],
        left_structure=structured(problem, fit, NONE_WITHIN_NOISE),
    )


def reads_explained(problem: Problem, baseline: Fit, decision: Decision) -> Decision:
    """The causes less an instrument that reads off whose channel the causes named leave structured
    (instruments.reads_left). A second cause is dropped from the causes; a leading one carries the
    objection, and none is left (the decision is to be taken again)."""
    final = decision.named.fit
    for k, cause in enumerate(decision.causes):
        effects = cause.judgement.fit.effects[k:] if k else cause.judgement.fit.effects[:1]
        why = reads_left(problem, final, effects)
        if not why:
            continue
        if k:
            kept = decision.causes[:k]
            return replace(
                decision, causes=kept, left_structure=structured(problem, kept[-1].judgement.fit, NONE_WITHIN_NOISE)
            )
        cause.judgement.objections += why
        return replace(decision, causes=[])
    return decision
