"""A folder of experiments diagnosed one by one, each its own Dask task, one row per file
(`pamkit diagnose --batch DIR -o RESULTS.parquet`).

A row gives the file, its kind, the cause diagnosis named, the gain and held-out RMSE of the
named model per channel (gain_force_N, heldout_rmse_force_N, ...), how many warnings the report
carries, the seconds it took, and `error`: the message of a file that could not be diagnosed
(its other columns empty). A campaign TOML in the folder is diagnosed as a campaign: its row
gives its cause (per-channel numbers belong to its tests).
"""

from __future__ import annotations

import time
import warnings
from pathlib import Path

from pamkit._core import Error, SolverError
from pamkit.cluster import check_output, run_all, work_key
from pamkit.diagnosis.engine import diagnose
from pamkit.diagnosis.report import to_json
from pamkit.io.guards import ExperimentWarning


def batch_files(directory: str | Path) -> list[Path]:
    """The experiment TOMLs in `directory` (not its subfolders), in name order.

    Raises:
        ValueError: when the folder does not exist or holds no TOML file.
    """
    directory = Path(directory)
    if not directory.is_dir():
        raise ValueError(f"--batch {directory}: not a folder")
    files = sorted(directory.glob("*.toml"))
    if not files:
        raise ValueError(f"--batch {directory}: no experiment TOML file in it")
    return files


def summary_row(path: Path, report: dict) -> dict:
    """The batch's row of one diagnosis report (report.py's to_json)."""
    row = {"test": str(path), "kind": report.get("kind", "series"), "cause": report["cause"], "error": None}
    if row["kind"] == "campaign":
        row["warnings"] = sum(len(test["warnings"]) for test in report["per_test"])
        return row
    extended = report["extended"]
    heldout = extended.get("heldout_rmse", extended["rmse"])  # a table's; a series' rmse is held out
    for channel, gain in report["gain"].items():
        row[f"gain_{channel}"] = gain
        row[f"heldout_rmse_{channel}"] = heldout[channel]
    row["warnings"] = len(report["warnings"])
    return row


def diagnose_file(path: str | Path) -> dict:
    """One file's row; a file that cannot be read or diagnosed gives its message in `error`. The
    warnings Python raises are counted with the report's, but those of reading the data
    (ExperimentWarning: repaired data), which the report holds already."""
    path = Path(path)
    started = time.perf_counter()
    with warnings.catch_warnings(record=True) as raised:
        warnings.simplefilter("always")
        try:
            row = summary_row(path, to_json(diagnose(path, threads=1)))
        except (ValueError, SolverError, Error) as error:  # the file's problem, kept in its row
            row = {"test": str(path), "error": str(error)}
    if "warnings" in row:
        row["warnings"] += sum(not issubclass(w.category, ExperimentWarning) for w in raised)
    row["seconds"] = time.perf_counter() - started
    return row


def diagnose_chunk(paths: list[str]) -> list[dict]:
    """The rows of several files (one Dask task)."""
    return [diagnose_file(path) for path in paths]


def diagnose_batch(directory: str | Path, output: str | Path, client, progress=None) -> list[dict]:
    """Diagnoses every experiment TOML in `directory` on the Dask `client`, each file its own
    task, writes the rows to `output` (.parquet or .csv) and returns them in file order. Rows are
    journaled as they complete: after a crash the same call resumes."""
    output = check_output(output)
    files = [str(path.resolve()) for path in batch_files(directory)]
    return run_all(
        diagnose_chunk,
        files,
        row_key="test",
        item_key=lambda path: path,
        output=output,
        work=work_key({"diagnose": files}),
        connected=client,
        label="diagnose",
        progress=progress,
        chunk_size=1,
    )
