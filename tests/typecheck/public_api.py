"""What a user's code does with pamkit's public Python API, checked by mypy (scripts/typecheck.sh)
against the package's annotations and the compiled core's stubs: a call the API does not accept,
or a result used as it is not, is a type error here. Never run: mypy reads it."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd

import pamkit
from pamkit.reference import data_columns, experiment_keys
from pamkit.templates import template


def first_hour(folder: Path) -> str:
    experiment: pamkit.Experiment = pamkit.load_experiment(folder / "experiment.toml")
    frame: pd.DataFrame = pamkit.simulate(experiment, effects=["heat_transfer:time_constant_s=2"])
    by_path: pd.DataFrame = pamkit.simulate(str(folder / "experiment.toml"))
    measured: pd.DataFrame = experiment.to_frame()
    inflation_Pa: float = experiment.inflation_gauge_pressure_Pa
    room_K: float = experiment.gas_params.ambient_temperature_K
    sealed: bool = experiment.gas == pamkit.GasMode.sealed
    again = pamkit.Experiment.from_frame(measured, folder / "again.toml", {"muscle": {}, "test": {}})
    report: pamkit.Report = pamkit.diagnose(again, threads=2, seed=1)
    campaign: pamkit.Report = pamkit.diagnose([folder / "a.toml", folder / "b.toml"])
    candidates: pd.DataFrame = report.candidates
    causes: pd.DataFrame = report.causes
    summary: pd.DataFrame = report.channels_summary
    written: Path = report.plot(folder / "report.png")
    text: str = report.to_json(folder / "report.json")
    read = pamkit.Report.read_json(folder / "report.json")
    document: dict[str, object] = read.to_dict()
    del frame, by_path, campaign, candidates, causes, summary, written, text, document, inflation_Pa, room_K, sealed
    return report.verdict() + report.cause + report.kind + ", ".join(report.channels)


def compiled_core() -> float:
    params = pamkit.MuscleParams(gas=pamkit.GasParams(process=pamkit.GasProcess.heat_transfer))
    model = pamkit.MuscleModel(params, pamkit.InitialState(length_m=0.167, gauge_pressure_Pa=236.63e3))
    result = pamkit.Simulator().run(model, pamkit.thesis_protocol(max_elongation_m=0.0523))
    forces: np.ndarray = result.force_N
    muscle = pamkit.read_muscle_params("calibrated.toml")
    pamkit.write_muscle_params("copy.toml", muscle)
    return float(forces.max()) + len(pamkit.__version__)


def files(folder: Path) -> int:
    data: Path = pamkit.write_experiment(
        folder / "map.toml",
        {"muscle": {"length_m": 0.25}, "test": {"kind": "isometric_map"}},
        {"length_m": np.array([0.25]), "gauge_pressure_Pa": np.array([100e3]), "force_N": np.array([10.0])},
    )
    keys = [key.name for key in experiment_keys() if key.section == "test"]
    columns = [f"{column.name} ({column.si_name} [{column.si_unit}])" for column in data_columns("isotonic")]
    return len(template("isotonic")) + len(keys) + len(columns) + len(str(data))
