"""The muscle a diagnosis found, as a muscle-parameters file (``pamkit diagnose --params-out``): the
calibrated model with every named cause, the physical ones as the C++ model's parameters, the test
rig's as effect specs in [rig]."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from pamkit._core import EffectStage, GasMode, InitialState, MuscleParams, write_muscle_params
from pamkit.diagnosis.series.campaign import SeriesCampaign
from pamkit.diagnosis.series.model import Baseline, muscle_signature
from pamkit.diagnosis.series.result import Diagnosis
from pamkit.diagnosis.tables.engine import TableDiagnosis
from pamkit.diagnosis.tables.fit import TableModel
from pamkit.effects import catalog as builtin_catalog


def effect_spec(effect) -> str:
    """An effect as the catalog parses it back: ``NAME:option=value,...,parameter=value,...``."""
    items = [f"{k}={v}" for k, v in effect.options().items()]
    items += [f"{p.name}={p.value!r}" for p in effect.parameters()]
    return f"{effect.name()}:{','.join(items)}" if items else effect.name()


def _extend(params: MuscleParams, effects) -> tuple[MuscleParams, list[str]]:
    """`params` with the physical effects applied (their fields in [extensions] or [gas]), and the
    specs of the others: the test rig's fixture and instruments, which are not the muscle."""
    rig = []
    for effect in effects:
        if effect.stage() == EffectStage.physics and not effect.reads_supplied_pressure():
            params = effect.apply_to_params(params)
        else:
            rig.append(effect_spec(effect))
    return params, rig


def diagnosed_muscle(
    d: Diagnosis | TableDiagnosis | SeriesCampaign, catalog=None
) -> tuple[MuscleParams, InitialState | None, list[str]]:
    """The muscle the diagnosis found: the calibrated model with every cause named — the physical
    ones as the C++ model's parameters (a braid that goes slack, heat exchange, a pressurise/vent
    hysteresis, ...), the test rig's (a time skew, a load cell's offset) as effect specs — and, for
    a sealed test, its state at zero elongation at the calibrated inflation pressure. What the
    extended prediction was computed from: a time series' extended fit (its baseline moved beside
    the causes); static tables' extended fit with the calibrated unknowns, the same muscle for every
    table; a campaign of time series: the muscle calibrated on all its tests (with the shared cause),
    with no [initial], each test being filled to its own pressure.

    Raises:
        ValueError: for tables whose files declare different muscles.
    """
    if isinstance(d, SeriesCampaign):
        final = d.extended or d.joint
        params, _ = Baseline(d.diagnoses[0].problem.experiment, d.joint.params).model_params(np.array([]))
        effects = []
        if d.extended is not None:
            effect = (catalog or builtin_catalog()).parse(d.extended.effect)
            for p in effect.parameters():
                if p.name in final.params:
                    effect.set(p.name, repr(float(final.params[p.name])))
            effects = [effect]
        params, rig = _extend(params, effects)
        return params, None, rig
    if isinstance(d, TableDiagnosis):
        fit = d.extended
        muscles = [TableModel.params(e, fit.params) for e in d.campaign.experiments]
        for experiment, muscle in zip(d.campaign.experiments[1:], muscles[1:]):
            if muscle_signature(muscle) != muscle_signature(muscles[0]):
                raise ValueError(
                    f"--params-out: {experiment.path} declares another muscle than {d.campaign.experiments[0].path} "
                    "(its [muscle], [bladder], [friction] or [gas] differ): diagnose the table whose muscle you want"
                )
        params, rig = _extend(muscles[0], fit.effects)
        return params, None, rig
    predictor = d.problem.predictor
    params, pressure_Pa = predictor.baseline.model_params(d.extended.baseline_x)
    params, rig = _extend(params, d.extended.effects)
    initial = predictor.initial_state(params, pressure_Pa) if predictor.mode == GasMode.sealed else None
    return params, initial, rig


def write_params(d: Diagnosis | TableDiagnosis | SeriesCampaign, path: str | Path) -> None:
    """Writes the muscle the diagnosis found (:func:`diagnosed_muscle`) as a muscle-parameters
    TOML file (the C++ reader's, include/pamkit/io/params_file.hpp): the calibrated build with
    every named cause, an [initial] section for a sealed test, and the rig's effects in [rig].

    Raises:
        ValueError: for tables that declare different muscles.
    """
    params, initial, rig = diagnosed_muscle(d)
    values = d.joint.params if isinstance(d, SeriesCampaign) else d.extended.params
    if not isinstance(d, SeriesCampaign) and not isinstance(d, TableDiagnosis):
        values = {**d.extended.baseline_params, **d.extended.params}
    fitted = ", ".join(f"{name} = {value:.6g}" for name, value in values.items() if not isinstance(value, str))
    if isinstance(d, SeriesCampaign):
        tests = [diagnosis.problem.experiment for diagnosis in d.diagnoses]
        causes = [d.extended.effect] if d.extended is not None else []
    else:
        tests = d.campaign.experiments if isinstance(d, TableDiagnosis) else [d.problem.experiment]
        causes = [e.name() for e in d.extended.effects]
    named = f" with {', '.join(causes)}" if causes else " (no cause named: the calibrated baseline)"
    comment = f"The muscle `pamkit diagnose {' '.join(str(e.path) for e in tests)}` found{named}: {fitted}."
    if initial is not None:
        comment += (
            "\n[initial] is that test's state at zero elongation; a test at another inflation pressure needs it "
            "removed."
        )
    Path(path).parent.mkdir(parents=True, exist_ok=True)
    write_muscle_params(path, params, initial, comment, rig)
