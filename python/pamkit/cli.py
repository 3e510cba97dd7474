"""The ``pamkit`` command line.

    pamkit simulate EXPERIMENT.toml -o OUT.csv [--plot OUT.png]
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from pamkit.experiment import ExperimentError, load_experiment, write_series


def _simulate(arguments: argparse.Namespace) -> int:
    from pamkit.simulate import simulate_experiment

    experiment = load_experiment(arguments.experiment)
    predicted = simulate_experiment(experiment)
    write_series(arguments.output, predicted)
    print(f"wrote {arguments.output} ({len(predicted['time_s'])} samples: time_s, elongation_m, force_N, "
          "pressure_kPa, temperature_C, length_m, gas_volume_m3, braid_angle_rad)")
    if arguments.plot:
        from pamkit.plots import plot_simulation

        measured = {name: values for name, values in experiment.columns.items()} if experiment.measured() else None
        title = experiment.description or Path(arguments.experiment).stem
        plot_simulation(arguments.plot, predicted, measured, title=title)
        print(f"wrote {arguments.plot}")
    return 0


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(prog="pamkit", description="Simulate and test pneumatic artificial muscles.")
    commands = parser.add_subparsers(dest="command", required=True)
    simulate = commands.add_parser(
        "simulate",
        help="predict force, pressure and temperature for an experiment",
        description="Drives the muscle model with the experiment's time_s and elongation_m and writes the "
        "predicted force_N, pressure_kPa (gauge) and temperature_C.",
    )
    simulate.add_argument("experiment", help="experiment TOML file")
    simulate.add_argument("-o", "--output", required=True, help="CSV file to write")
    simulate.add_argument("--plot", help="also write a PNG figure of the prediction (and of the data, if measured)")
    simulate.set_defaults(run=_simulate)
    return parser


def main(argv: list[str] | None = None) -> int:
    arguments = build_parser().parse_args(argv)
    try:
        return arguments.run(arguments)
    except (ExperimentError, ValueError) as error:
        print(f"pamkit {arguments.command}: error: {error}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
