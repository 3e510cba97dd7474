"""Many independent runs on Dask, each finished row kept as soon as it arrives.

`pamkit sweep` and `pamkit diagnose --batch` hand this module a list of chunks (each a few runs)
and a function that turns a chunk into rows. The chunks run on a ``dask.distributed`` cluster: a
LocalCluster of worker processes by default (one thread each: diagnosis holds the GIL in its
Python parts), or a running scheduler given by its address. Rows are appended to a journal
(OUTPUT.partial.jsonl, flushed per chunk) as chunks complete, so a driver that dies keeps what is
done; the same command run again reads the journal and submits only the runs it lacks. The table
(Parquet or CSV, by the output's extension) is written at the end, in run order, and the
journal removed.

Dask is an optional dependency (``pip install 'pamkit[scale]'``): it is imported here only.
"""

from __future__ import annotations

import contextlib
import csv
import hashlib
import json
import logging
import math
import os
import sys
import time
from collections.abc import Callable, Iterator, Sequence
from pathlib import Path

SCALE_EXTRA_HINT = "pip install 'pamkit[scale]'"
OUTPUT_FORMATS = (".parquet", ".csv")
# Chunks per worker: enough that the workers finish together and the progress moves, few enough
# that Dask's per-task cost (about a millisecond, tens on a loaded machine) stays small against a
# chunk's runs. A run in Python costs a millisecond or more: 256 of them, a quarter second or more.
CHUNKS_PER_WORKER = 4
MAX_CHUNK = 256
PROGRESS_INTERVAL_S = 1.0


class ScaleUnavailable(ValueError):
    """Dask (or pyarrow, for Parquet) is not installed; the message says how to install it."""


def require(module: str) -> None:
    """Imports `module` or raises ScaleUnavailable with the one line that fixes it."""
    try:
        __import__(module)
    except ImportError:
        raise ScaleUnavailable(f"{module} is not installed: {SCALE_EXTRA_HINT}") from None


def check_output(path: str | Path) -> Path:
    """The output table's path, checked before any run starts: .parquet or .csv, in a folder that exists."""
    path = Path(path)
    if path.suffix not in OUTPUT_FORMATS:
        raise ValueError(f"{path}: the output must end in {' or '.join(OUTPUT_FORMATS)}")
    if not path.parent.is_dir():
        raise ValueError(f"{path}: the folder {path.parent} does not exist")
    if path.suffix == ".parquet":
        require("pyarrow")
    return path


def chunked(items: Sequence, workers: int, size: int | None = None, largest: int = MAX_CHUNK) -> list[list]:
    """`items` cut into consecutive chunks of `size`, by default about CHUNKS_PER_WORKER per worker
    and at most `largest`."""
    if size is None:
        size = max(1, min(largest, len(items) // max(1, workers * CHUNKS_PER_WORKER)))
    return [list(items[start : start + size]) for start in range(0, len(items), size)]


@contextlib.contextmanager
def client(workers: int | None = None, scheduler: str | None = None) -> Iterator:
    """A ``distributed.Client``: on the scheduler at `scheduler` (tcp://host:port), else on a
    LocalCluster of `workers` processes (default: the cores) with one thread each."""
    require("distributed")
    from distributed import Client, LocalCluster  # optional (pamkit[scale]): imported where a cluster runs

    if scheduler:
        with Client(scheduler) as connected:
            yield connected
        return
    if workers is not None and workers < 1:
        raise ValueError(f"--workers {workers}: needs at least 1")
    # The dashboard on a free port (on 8787 a second cluster would warn that the port is taken);
    # worker logs below ERROR are noise on a command line.
    cluster = LocalCluster(
        n_workers=workers or os.cpu_count() or 1,
        threads_per_worker=1,
        processes=True,
        dashboard_address=":0",
        silence_logs=logging.ERROR,
    )
    with cluster, Client(cluster) as connected:
        yield connected


def worker_count(connected) -> int:
    """Threads the cluster runs tasks on (at least 1, for a scheduler whose workers have not joined yet)."""
    return max(1, sum(connected.nthreads().values()))


class Journal:
    """The rows done so far, one JSON object a line in OUTPUT.partial.jsonl after a first line
    naming the work (`key`); a line cut by a crash is ignored."""

    def __init__(self, output: Path, key: str):
        self.path = output.with_name(output.name + ".partial.jsonl")
        self.key = key
        self.rows: list[dict] = []
        if self.path.exists():
            lines = self.path.read_text().splitlines()
            header = json.loads(lines[0]) if lines else {}
            if header.get("work") != key:
                raise ValueError(
                    f"{self.path}: partial results of other work (another spec or folder): "
                    "delete it, or write to another output"
                )
            for line in lines[1:]:
                with contextlib.suppress(json.JSONDecodeError):  # the last line, cut by a crash
                    self.rows.append(json.loads(line))
            self._file = self.path.open("a")
        else:
            self._file = self.path.open("w")
            self._file.write(json.dumps({"work": key}) + "\n")
            self._file.flush()

    def append(self, rows: list[dict]) -> None:
        for row in rows:
            self._file.write(json.dumps(row) + "\n")
        self._file.flush()
        os.fsync(self._file.fileno())
        self.rows.extend(rows)

    def close(self) -> None:
        self._file.close()


def work_key(description) -> str:
    """A digest of what the runs are (JSON-able), so a journal is resumed only by the same work."""
    return hashlib.sha256(json.dumps(description, sort_keys=True, default=str).encode()).hexdigest()[:16]


def run_all(
    function: Callable[[list], list[dict]],
    items: Sequence,
    row_key: str,
    item_key: Callable,
    output: Path,
    work: str,
    connected,
    label: str,
    progress: Callable[[str], None] | None = None,
    chunk_size: int | None = None,
    largest_chunk: int = MAX_CHUNK,
) -> list[dict]:
    """Runs `function` on chunks of `items` (of `chunk_size`, by default sized by chunked, at most
    `largest_chunk` items) on the cluster and returns every row, sorted by `row_key`;
    `item_key(item)` is the row_key value of the row an item gives. Rows already in the output's
    journal are not run again. The table is written to `output` at the end."""
    journal = Journal(output, work)
    try:
        done = {row[row_key] for row in journal.rows}
        todo = [item for item in items if item_key(item) not in done]
        if done and progress:
            progress(f"{label}: resuming from {journal.path}: {len(done)} of {len(items)} done")
        chunks = chunked(todo, worker_count(connected), chunk_size, largest_chunk)
        _run_chunks(function, chunks, journal, len(items), connected, label, progress)
    except BaseException:  # interrupted, or a bug in a run: say what is kept, then let it go on
        if progress:
            progress(f"{label}: {len(journal.rows)} of {len(items)} kept in {journal.path}; the same command resumes")
        raise
    finally:
        journal.close()
    rows = sorted(journal.rows, key=lambda row: row[row_key])
    write_rows(output, rows)
    journal.path.unlink()
    return rows


def _run_chunks(function, chunks, journal: Journal, total: int, connected, label: str, progress) -> None:
    from distributed import as_completed  # optional (pamkit[scale]): imported where a cluster runs

    started = time.perf_counter()
    last_shown = -math.inf
    futures = [connected.submit(function, chunk, pure=False) for chunk in chunks]
    for future in as_completed(futures):
        journal.append(future.result())
        future.release()
        now = time.perf_counter()
        finished = len(journal.rows) == total
        if progress and (finished or now - last_shown >= PROGRESS_INTERVAL_S):
            failed = sum(1 for row in journal.rows if row.get("error"))
            progress(f"{label}: {len(journal.rows)}/{total} done, {failed} failed, {now - started:.1f} s")
            last_shown = now


def write_rows(path: Path, rows: list[dict]) -> None:
    """The rows as a table, columns in first-seen order, a value a row lacks left empty (null)."""
    columns = list(dict.fromkeys(name for row in rows for name in row))
    if path.suffix == ".csv":
        with path.open("w", newline="") as file:
            writer = csv.DictWriter(file, fieldnames=columns, restval="")
            writer.writeheader()
            writer.writerows({k: "" if v is None else v for k, v in row.items()} for row in rows)
        return
    import pyarrow as pa
    import pyarrow.parquet as pq

    def column(name: str):
        values = [row.get(name) for row in rows]
        # A column empty in every row is a text one (`error` when every run succeeded): typed
        # so, tables of several sweeps concatenate.
        return pa.array(values, type=pa.string()) if all(v is None for v in values) else pa.array(values)

    pq.write_table(pa.table({name: column(name) for name in columns}), path)


def read_rows(path: str | Path) -> list[dict]:
    """A table written by write_rows, back as rows (Parquet: the values as written; CSV: text)."""
    path = Path(path)
    if path.suffix == ".csv":
        with path.open(newline="") as file:
            return list(csv.DictReader(file))
    import pyarrow.parquet as pq

    return pq.read_table(path).to_pylist()


def stderr_progress(message: str) -> None:
    print(f"  {message}", file=sys.stderr, flush=True)
