"""pamkit synth --effect NAME[:key=value,...] --seed N -o DIR"""

from __future__ import annotations

import argparse


def register(subparsers) -> None:
    parser = subparsers.add_parser(
        "synth",
        help="write a synthetic bench test with one effect hidden in it",
        description="Writes DIR/experiment.toml and DIR/experiment.csv: a random bench protocol (inflation "
        "35-276 kPa, stretch to 80-95 % of the free contraction, 2.5-50 mm/s, 5-10 cycles) simulated with the "
        "effect at a random realistic strength (unless given) and read by the tensile machine and the Arduino "
        "logger. What was hidden goes to DIR/manifest.json, which diagnosis must not read.",
    )
    parser.add_argument(
        "--effect",
        required=True,
        metavar="NAME[:key=value,...]",
        help="a catalog effect (see `pamkit effects`), or 'none'; keys not given are drawn",
    )
    parser.add_argument("--seed", required=True, type=int, help="seed of every random draw (>= 0)")
    parser.add_argument("-o", "--output", required=True, metavar="DIR", help="directory to write into")
    parser.set_defaults(run=run)


def run(arguments: argparse.Namespace) -> int:
    from pamkit.synth.dataset import synthesize

    files = synthesize(arguments.effect, arguments.seed, arguments.output)
    print(f"wrote {files.experiment}, {files.data} (the experiment) and {files.manifest} (the hidden truth)")
    return 0
