"""pamkit diagnose EXPERIMENT.toml [MORE.toml ...] [--json REPORT.json] [--plot REPORT.png] [--params-out PARAMS.toml]
                [--next-test NEXT.toml]
pamkit diagnose --batch DIR -o RESULTS.parquet [--workers N | --scheduler ADDRESS]"""

from __future__ import annotations

import argparse
import sys

from pamkit.commands.sweep import add_cluster_options


def register(subparsers) -> None:
    parser = subparsers.add_parser(
        "diagnose",
        help="find what the simulation gets wrong in measured data, name the cause, measure the gain",
        description="Calibrates the model on some cycles, fits every catalog effect, scores each on held-out "
        "cycles and names a cause only when its gain is significant.",
    )
    parser.add_argument(
        "experiment",
        nargs="*",
        help="experiment TOML file (with its CSV of measured channels), or a campaign TOML ([campaign] tests = "
        "[...]); several tests of one muscle form a campaign: static tables share their [calibrate] unknowns, "
        "time series are each held out in turn and a cause must carry from the others to every one",
    )
    parser.add_argument("--json", help="write the report as JSON")
    parser.add_argument("--plot", help="write the report as a PNG figure")
    parser.add_argument(
        "--params-out",
        metavar="PARAMS.toml",
        help="write the muscle the diagnosis found as a muscle-parameters file under the C++ field names: the "
        "calibrated build with every named cause (physical causes as its parameters, the test rig's as [rig] "
        "effects; one time series; static tables of one muscle; a campaign of time series: the muscle calibrated "
        "on all its tests): what `pamkit simulate --params` and the C++ pamkit::read_muscle_params load",
    )
    parser.add_argument(
        "--next-test",
        metavar="NEXT.toml",
        help="where the report asks for another test (to tell a tie apart, confirm a close cause, check for an "
        "instrument's error), write it as an experiment file to run: this test's sections with [test] changed, "
        "the motion to run (NEXT.csv, which the lab's data then replace) and what each explanation predicts it "
        "will measure (NEXT.predictions.csv); one time series",
    )
    parser.add_argument("--threads", type=int, default=None, help="fits in parallel (default: all cores)")
    batch = parser.add_argument_group(
        "batch", "diagnose every experiment TOML of a folder on its own, each a Dask task (pip install 'pamkit[scale]')"
    )
    batch.add_argument("--batch", metavar="DIR", help="the folder: one row per file (cause, gain, held-out RMSE, ...)")
    batch.add_argument("-o", "--output", help="with --batch: the table to write, .parquet or .csv")
    add_cluster_options(batch)
    parser.add_argument("--quiet", action="store_true", help="no progress on stderr")
    parser.set_defaults(run=run)


def run(arguments: argparse.Namespace) -> int:
    from pamkit.diagnosis import diagnose, verdict
    from pamkit.diagnosis.params_out import write_params
    from pamkit.diagnosis.report import write
    from pamkit.diagnosis.series.next_test import write_next_test

    def progress(message: str) -> None:
        if not arguments.quiet:
            print(f"  {message}", file=sys.stderr, flush=True)

    if arguments.batch is not None:
        return run_batch(arguments, progress)
    if not arguments.experiment:
        raise ValueError("name the experiment TOML files to diagnose, or a folder of them with --batch DIR")
    for option in ("output", "workers", "scheduler"):
        if getattr(arguments, option) is not None:
            raise ValueError(f"--{option} belongs to --batch")

    d = diagnose(arguments.experiment, progress=progress, threads=arguments.threads)
    outputs = [p for p in (arguments.json, arguments.plot, arguments.params_out) if p]
    if outputs:
        progress(f"writing {' and '.join(outputs)}")
    write(d, arguments.json, arguments.plot)
    if arguments.params_out:
        write_params(d, arguments.params_out)
    print(verdict(d))
    for path in outputs:
        print(f"wrote {path}")
    if arguments.next_test:
        try:
            written = write_next_test(d, arguments.next_test)
        except ValueError as why:  # the diagnosis stands; only the test it would ask for is missing
            print(f"--next-test: nothing written: {why}", file=sys.stderr)
        else:
            for path in written:
                print(f"wrote {path}")
            if d.separation.variant.zero_reading:
                print(
                    "the zero run: record the test's channels with the muscle vented and unloaded, save them beside "
                    f'{d.problem.experiment.path.name} and name them in its [test] (zero = "zero.csv"), then '
                    "diagnose it again"
                )
    return 0


def run_batch(arguments: argparse.Namespace, progress) -> int:
    from pamkit.cluster import check_output, client, require
    from pamkit.diagnosis.batch import batch_files, diagnose_batch

    if arguments.experiment:
        raise ValueError("--batch DIR diagnoses the folder's files: name no experiment besides it")
    for option in ("json", "plot", "threads", "params_out", "next_test"):
        if getattr(arguments, option) is not None:
            flag = option.replace("_", "-")
            raise ValueError(
                f"--{flag} does not apply to --batch (one row per test; each diagnosis runs on one thread)"
            )
    if arguments.output is None:
        raise ValueError("--batch needs -o RESULTS.parquet (or .csv)")
    require("distributed")
    output = check_output(arguments.output)
    progress(f"diagnose: {len(batch_files(arguments.batch))} experiments in {arguments.batch}")
    with client(arguments.workers, arguments.scheduler) as connected:
        rows = diagnose_batch(arguments.batch, output, connected, progress)
    failed = sum(1 for row in rows if row["error"])
    print(f"wrote {output} ({len(rows)} tests, {failed} failed)")
    return 0
