"""What the diagnosis of one time series found: the record pamkit.diagnosis.report writes as
JSON, as a sentence and as a figure, and campaign.py gathers test by test."""

from __future__ import annotations

from dataclasses import dataclass, field

from pamkit.diagnosis.coordinates import Finding
from pamkit.diagnosis.series.calibrate import Fit
from pamkit.diagnosis.series.decide import Decision, Judgement
from pamkit.diagnosis.series.declared import DeclaredBuild
from pamkit.diagnosis.series.kinds import Problem
from pamkit.diagnosis.series.separate import Separation


@dataclass
class Diagnosis:
    """Everything the report says; see pamkit.diagnosis.report for the JSON, text and plot."""

    problem: Problem
    baseline: Fit
    candidates: list[Judgement]  # every fitted candidate, best held-out gain first
    skipped: dict[str, str]  # candidates that could not act or whose fit failed, and why
    decision: Decision
    extended: Fit  # the named cause's model, or the baseline
    extended_judgement: Judgement | None
    warnings: list[Finding]  # baseline and extended parameters at a bound or implausible
    discovered: dict = field(default_factory=dict)
    seconds: dict[str, float] = field(default_factory=dict)
    data_notes: list[dict] = field(default_factory=list)  # what was done to the data first (glitches, thinned, zeroed)
    separation: Separation | None = None  # the test that would tell a tie apart (separate.py)
    # a named transducer's gain beside the declared build with its lengths free (declared.py)
    declared_build: DeclaredBuild | None = None

    @property
    def cause(self) -> str:
        return self.decision.cause

    @property
    def data_clause(self) -> str:
        """What was done to the data before the diagnosis (glitches left out, the zero run's
        offsets taken off), as a verdict's closing clauses ('' when nothing was)."""
        return "".join(f"; {n[key]}" for n in self.data_notes for key in ("glitches", "zeroed") if key in n)
