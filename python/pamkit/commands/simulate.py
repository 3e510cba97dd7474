"""pamkit simulate EXPERIMENT.toml [--effect NAME[:key=value,...]]... [--params PARAMS.toml] -o OUT.csv
[--plot OUT.png]"""

from __future__ import annotations

import argparse
from pathlib import Path

from pamkit._core import GasMode
from pamkit.io.columns import SERIES_COLUMNS, file_name, value_from_si
from pamkit.io.experiment import load_experiment
from pamkit.io.writers import SeriesWriter, write_series


def register(subparsers) -> None:
    parser = subparsers.add_parser(
        "simulate",
        help="predict force, pressure and temperature for an experiment",
        description="Drives the muscle model with the experiment's time_s and elongation_m and writes the "
        "predicted force_N, pressure_kPa (gauge) and temperature_C. A sealed time series is written as it is "
        "integrated, so a long test's prediction never stands in memory whole; with --plot, or an effect on the "
        "measured channels (sensor_lag, time_skew, ...), it is simulated whole first.",
    )
    parser.add_argument("experiment", help="experiment TOML file")
    parser.add_argument(
        "--effect",
        action="append",
        default=[],
        metavar="NAME[:key=value,...]",
        help="extend the model with a catalog effect (repeatable); see `pamkit effects`",
    )
    parser.add_argument(
        "--params",
        metavar="PARAMS.toml",
        help="simulate the muscle of a muscle-parameters file (C++ field names, e.g. from `pamkit diagnose "
        "--params-out`) instead of the experiment's [muscle], [bladder], [friction] and [gas]; a sealed time series "
        "starts from the file's [initial] state when it has one, and the file's [rig] effects (the test rig's "
        "fixture and instruments a diagnosis found) are applied as --effect would",
    )
    parser.add_argument("-o", "--output", required=True, help="CSV file to write")
    parser.add_argument("--plot", help="also write a PNG figure of the prediction (and of the data, if measured)")
    parser.set_defaults(run=run)


def run(arguments: argparse.Namespace) -> int:
    from pamkit.effects import parse_effects
    from pamkit.simulation import simulate_experiment, simulate_streamed, why_not_streamed

    effects = parse_effects(arguments.effect)
    experiment = load_experiment(arguments.experiment)
    params = initial = None
    if arguments.params is not None:
        from pamkit._core import read_muscle_params_file

        calibrated = read_muscle_params_file(arguments.params)
        params = calibrated.params
        effects += parse_effects(calibrated.rig_effects)
        if calibrated.initial is not None and experiment.gas == GasMode.sealed and not experiment.is_table:
            initial = calibrated.initial
            starts_kPa = value_from_si("gauge_pressure_Pa", initial.gauge_pressure_Pa)
            declared_kPa = value_from_si("gauge_pressure_Pa", experiment.inflation_gauge_pressure_Pa)
            print(
                f"starting from {arguments.params} [initial]: {initial.length_m:.6g} m at {starts_kPa:.6g} kPa "
                f"(the experiment declares {declared_kPa:.6g} kPa)"
            )
    if not arguments.plot and why_not_streamed(experiment, effects) is None:
        # Written block by block as it is integrated: a long test's prediction never stands in
        # memory whole. A figure needs it whole, and so do the tests why_not_streamed names.
        with SeriesWriter(arguments.output, SERIES_COLUMNS) as writer:
            simulate_streamed(experiment, writer.write, params=params, effects=effects, initial=initial)
        print(f"wrote {arguments.output} ({writer.rows} samples: {', '.join(map(file_name, SERIES_COLUMNS))})")
        return 0
    predicted = simulate_experiment(experiment, params=params, effects=effects, initial=initial)
    write_series(arguments.output, predicted)
    rows = len(next(iter(predicted.values())))
    print(
        f"wrote {arguments.output} ({rows} {'rows' if experiment.is_table else 'samples'}: "
        f"{', '.join(map(file_name, predicted))})"
    )
    if arguments.plot and experiment.is_table:
        from pamkit.plots import plot_table

        plot_table(
            arguments.plot, experiment, predicted, title=experiment.description or Path(arguments.experiment).stem
        )
        print(f"wrote {arguments.plot}")
    elif arguments.plot:
        from pamkit.plots import plot_simulation, plot_supplied

        measured = experiment.columns if experiment.measured() else None
        title = experiment.description or Path(arguments.experiment).stem
        if effects:
            title += "\nwith " + ", ".join(repr(effect) for effect in effects)
        plotter = plot_supplied if experiment.gas == GasMode.supplied else plot_simulation
        plotter(arguments.plot, predicted, measured, title=title)
        print(f"wrote {arguments.plot}")
    return 0
