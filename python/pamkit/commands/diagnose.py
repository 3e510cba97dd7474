"""pamkit diagnose EXPERIMENT.toml [MORE.toml ...] [--json REPORT.json] [--plot REPORT.png]"""

from __future__ import annotations

import argparse
import sys


def register(subparsers) -> None:
    parser = subparsers.add_parser(
        "diagnose",
        help="find what the simulation gets wrong in measured data, name the cause, measure the gain",
        description="Calibrates the model on some cycles, fits every catalog effect, scores each on held-out "
        "cycles and names a cause only when its gain is significant.",
    )
    parser.add_argument(
        "experiment",
        nargs="+",
        help="experiment TOML file (with its CSV of measured channels), or a campaign TOML ([campaign] tests = "
        "[...]); several tests of one muscle form a campaign: static tables share their [calibrate] unknowns, "
        "time series are each held out in turn and a cause must carry from the others to every one",
    )
    parser.add_argument("--json", help="write the report as JSON")
    parser.add_argument("--plot", help="write the report as a PNG figure")
    parser.add_argument("--threads", type=int, default=None, help="fits in parallel (default: all cores)")
    parser.add_argument("--quiet", action="store_true", help="no progress on stderr")
    parser.set_defaults(run=run)


def run(arguments: argparse.Namespace) -> int:
    from pamkit.diagnose import diagnose, verdict
    from pamkit.diagnose.report import write

    def progress(message: str) -> None:
        if not arguments.quiet:
            print(f"  {message}", file=sys.stderr, flush=True)

    d = diagnose(arguments.experiment, progress=progress, threads=arguments.threads)
    if arguments.json or arguments.plot:
        progress(f"writing {' and '.join(p for p in (arguments.json, arguments.plot) if p)}")
    write(d, arguments.json, arguments.plot)
    print(verdict(d))
    for path in (arguments.json, arguments.plot):
        if path:
            print(f"wrote {path}")
    return 0
