"""pamkit sweep SPEC.toml -o RESULTS.parquet [--workers N | --scheduler ADDRESS]"""

from __future__ import annotations

import argparse


def add_cluster_options(parser: argparse.ArgumentParser) -> None:
    """--workers and --scheduler, shared by the commands that run on Dask."""
    where = parser.add_mutually_exclusive_group()
    where.add_argument(
        "--workers", type=int, default=None, help="worker processes of the local Dask cluster (default: the cores)"
    )
    where.add_argument(
        "--scheduler",
        metavar="ADDRESS",
        help="run on a running Dask cluster (tcp://host:8786) instead; its workers must see the same files",
    )


def register(subparsers) -> None:
    parser = subparsers.add_parser(
        "sweep",
        help="simulate one experiment over a grid or Latin hypercube of parameters, on Dask",
        description="Reads SPEC.toml ([sweep] base experiment, design; [parameters] each swept with values, "
        "linspace or range), simulates every run on a Dask cluster and writes one row per run: the parameters, "
        "peak force, force range, energy stored over the first stretch, pressure range and gas temperature "
        'swing, and the error of a run that failed ([sweep] device = "exoskeleton": the ankle device\'s torque '
        "share and clutch timing over Winter's gait instead). Rows are kept as runs complete (OUTPUT.partial.jsonl): "
        "after an interruption, the same command resumes. Needs pip install 'pamkit[scale]'.",
    )
    parser.add_argument("spec", help="sweep spec TOML file")
    parser.add_argument("-o", "--output", required=True, help="table to write: .parquet or .csv")
    add_cluster_options(parser)
    parser.add_argument("--quiet", action="store_true", help="no progress on stderr")
    parser.set_defaults(run=run)


def run(arguments: argparse.Namespace) -> int:
    from pamkit.cluster import check_output, client, require, stderr_progress
    from pamkit.sweep import load_spec, sweep

    require("distributed")
    output = check_output(arguments.output)
    spec = load_spec(arguments.spec)
    progress = None if arguments.quiet else stderr_progress
    if progress:
        what = spec.experiment.name if spec.experiment else "the exoskeleton"
        progress(f"sweep: {len(spec.runs)} runs of {what} ({spec.design}: {', '.join(spec.names)})")
    with client(arguments.workers, arguments.scheduler) as connected:
        rows = sweep(spec, output, connected, progress)
    failed = sum(1 for row in rows if row["error"])
    print(f"wrote {output} ({len(rows)} runs, {failed} failed)")
    return 0
