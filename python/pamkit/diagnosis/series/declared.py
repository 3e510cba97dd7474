"""The declared build beside a named pressure transducer's error. On a sealed test the gas's volume
sets the pressure's swing, so a transducer reading a few per cent high or low and a muscle whose
declared length or diameter is a millimetre off draw the same pressure (another team's muscles
declared 1-2 mm off in length or 0.3-0.6 mm in diameter read as gains of 1.05-1.07). Freeing the
lengths in every baseline cost more right names than it spared wrong ones (docs/diagnosis.md, rule
7), so they stay as declared; but where such a correction is named, the baseline is calibrated
once more with them free within what a rule and calipers read. Where that build explains the
held-out units as well as the causes named, the data do not tell the transducer from the declared
build (rule 6's tie): nothing is named, the verdict says which two readings remain, and a reference
gauge on the transducer tells them apart. Over another team's muscles declared off this turned four
wrong names into that; on near-model data three of 82 true offsets were lost to it
(docs/diagnosis.md, rule 7)."""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from pamkit.diagnosis.series.calibrate import Fit, fit_baseline
from pamkit.diagnosis.series.decide import Decision
from pamkit.diagnosis.series.instruments import noise_ratios, rereading, shifts_in_time
from pamkit.diagnosis.series.kinds import Problem, build_problem
from pamkit.diagnosis.series.score import score
from pamkit.diagnosis.significance import NONE_WITHIN_NOISE
from pamkit.io.sections import declared_value

# What a builder's rule and calipers read a muscle's deflated length and its braid's diameter to
# (± m): a millimetre at each end of the length, half a millimetre on a braid the jaws squeeze.
FREED = {"length_m": 2e-3, "diameter_m": 0.5e-3}


@dataclass
class DeclaredBuild:
    """The baseline with the declared lengths free, beside the causes named."""

    freed: dict[str, float]  # the fields freed and their tolerance [m]
    declared: dict[str, float]  # their declared values [m]
    values: dict[str, float]  # where the calibration put them [m]
    gain: float  # its combined held-out gain over the calibrated baseline
    causes_gain: float  # the causes' own, on the same draws
    difference_ci95: tuple[float, float]  # of the causes' gain less its, over the same draws

    @property
    def as_well(self) -> bool:
        """Whether the causes do not explain the held-out units significantly better (rule 6's tie)."""
        return self.difference_ci95[0] <= 0.0

    def to_json(self) -> dict:
        return {
            "freed": self.freed,
            "declared": self.declared,
            "values": self.values,
            "at_tolerance": self.at_tolerance,
            "gain": self.gain,
            "causes_gain": self.causes_gain,
            "difference_ci95": list(self.difference_ci95),
            "explains_as_well": self.as_well,
        }

    @property
    def at_tolerance(self) -> list[str]:
        """The freed fields calibrated at the edge of their tolerance: the build as it may be, at
        the most a rule or calipers could misread it."""
        return [n for n, v in self.values.items() if abs(v - self.declared[n]) >= self.freed[n] * (1 - 1e-6)]

    def objection(self) -> str:
        """Why the causes are not named where the build explains as well."""
        edge = set(self.at_tolerance)
        where = ", ".join(
            f"{name} {1e3 * value:.4g} mm" + (" at its tolerance's edge" if name in edge else "")
            for name, value in self.values.items()
        )
        tolerances = " and ".join(f"{name} ±{1e3 * t:g} mm" for name, t in self.freed.items())
        low, high = self.difference_ci95
        how, interval = ("better", "lies below zero") if high < 0.0 else ("as well", "holds zero")
        return (
            f"the declared build with {tolerances} ({where}) explains the held-out units {how} (combined "
            f"gain {self.gain:.3f} against the causes' {self.causes_gain:.3f}; the difference's 95 % interval "
            f"[{low:.3f}, {high:.3f}] {interval}): the data do not tell the transducer from the build; a "
            "reference gauge on the transducer does, and [uncertain] says how well the build was measured"
        )


def declared_build(
    problem: Problem, baseline: Fit, decision: Decision, seed: int, progress=lambda message: None
) -> DeclaredBuild | None:
    """The baseline calibrated with the declared lengths free (FREED, those the file does not free
    or calibrate already), scored on the held-out units beside the causes named, where one of them
    corrects what a sealed test's pressure transducer reads (not when: a lag or a skew is no
    volume's doing); else None."""
    scales = [e for c in decision.causes for e in rereading(problem, c.judgement.fit) if not shifts_in_time(e)]
    if not scales:
        return None
    e = problem.experiment
    freed = {name: t for name, t in FREED.items() if name not in e.uncertain and name not in e.calibrate}
    if not freed:
        return None
    progress(f"calibrating again with {' and '.join(freed)} free beside the transducer's correction")
    other = build_problem(replace(e, uncertain={**e.uncertain, **freed}))
    alternative = fit_baseline(other)
    mine = score(problem, baseline, alternative, np.random.default_rng(seed))
    causes = decision.named.score
    low, high = np.percentile(causes.combined_samples - mine.combined_samples, [2.5, 97.5])
    return DeclaredBuild(
        freed,
        {name: declared_value(name, e.build, e.bladder) for name in freed},
        {name: alternative.baseline_params[name] for name in freed},
        mine.combined_gain,
        causes.combined_gain,
        (float(low), float(high)),
    )


def told_from_the_build(problem: Problem, baseline: Fit, decision: Decision, declared: DeclaredBuild) -> Decision:
    """`decision`, or where the declared build explains the held-out units as well as its causes,
    the decision that names none of them (rule 6): the lead refused with the build as its reason,
    "unexplained" where the calibrated baseline leaves structure, else "none"."""
    if not declared.as_well:
        return decision
    lead = decision.causes[0].judgement
    lead.objections.append(declared.objection())
    margins = {**decision.margins, "over_declared_build": declared.difference_ci95[0]}
    left = [c for c, r in noise_ratios(problem, baseline).items() if r > NONE_WITHIN_NOISE]
    return Decision("unexplained" if left else "none", [], lead, margins, left)
