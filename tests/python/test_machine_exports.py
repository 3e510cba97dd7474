"""Tensile machines' exports (Instron Bluehill, ZwickRoell testXpert) read as experiment data and
by `pamkit align`: units converted, every bad header or unit named by file, line and column."""

import re

import numpy as np
import pytest

from pamkit.io.experiment import load_experiment
from pamkit.io.guards import ExperimentError, ExperimentWarning
from pamkit.io.logger import LoggerError, read_machine_csv
from pamkit.io.machine import read_machine_export
from pamkit.io.series import read_series


@pytest.fixture
def machines_dir(thesis_dir):
    return thesis_dir.parent / "machines"


def test_both_sample_exports_load_as_the_same_test(machines_dir):
    instron = load_experiment(machines_dir / "instron_bluehill.toml")
    zwick = load_experiment(machines_dir / "zwick_testxpert.toml")
    assert set(instron.columns) == set(zwick.columns) == {"time_s", "elongation_m", "force_N"}
    # The two files hold one test: 81 samples, 0.1 s apart, 0 -> 10 mm -> 0 at 2.5 mm/s.
    np.testing.assert_allclose(instron.time_s, np.arange(81) * 0.1, atol=1e-12)
    expected_m = 2.5e-3 * np.minimum(instron.time_s, 8 - instron.time_s)
    np.testing.assert_allclose(instron.elongation_m, expected_m, atol=1e-12)
    np.testing.assert_allclose(zwick.elongation_m, expected_m, atol=1e-12)
    np.testing.assert_allclose(zwick.time_s, instron.time_s, atol=1e-12)
    # Bluehill prints the load to 1e-5 N, testXpert to 1e-7 kN = 1e-4 N: they agree to half of each.
    np.testing.assert_allclose(zwick.columns["force_N"], instron.columns["force_N"], rtol=0, atol=0.5e-4 + 0.5e-5)


def test_formats_are_recognised_from_their_headers(machines_dir):
    zwick_bytes = (machines_dir / "zwick_testxpert.csv").read_bytes()
    assert b"Pr\xfcfzeit" in zwick_bytes  # written as testXpert does on Windows: Windows-1252, not UTF-8
    assert b";" in zwick_bytes and b"0,100" in zwick_bytes  # semicolons, decimal commas
    assert read_machine_export(machines_dir / "zwick_testxpert.csv").format == "zwick_testxpert"
    assert read_machine_export(machines_dir / "instron_bluehill.csv").format == "instron_bluehill"


@pytest.mark.parametrize(
    "units, factors",
    [
        ('"(s)","(mm)","(N)"', (1.0, 1e-3, 1.0)),
        ('"(ms)","(µm)","(kN)"', (1e-3, 1e-6, 1e3)),
        ("[min],[cm],[lbf]", (60.0, 1e-2, 4.4482216152605)),  # 1 lbf = 4.4482216152605 N exactly (NIST)
        ("s,in,kgf", (1.0, 0.0254, 9.80665)),  # 1 in = 25.4 mm, 1 kgf = 9.80665 N, both exact by definition
        ("h,m,daN", (3600.0, 1.0, 10.0)),
    ],
)
def test_units_row_converts_to_si(tmp_path, units, factors):
    path = tmp_path / "export.csv"
    path.write_text(f'"Specimen","1"\nTime,Extension,Load\n{units}\n1,2,3\n2,4,6\n')
    columns = read_machine_export(path).columns
    np.testing.assert_array_equal(columns["time_s"], np.array([1.0, 2.0]) * factors[0])
    np.testing.assert_array_equal(columns["extension_m"], np.array([2.0, 4.0]) * factors[1])
    np.testing.assert_array_equal(columns["force_N"], np.array([3.0, 6.0]) * factors[2])


def test_german_tab_export_with_columns_in_testxperts_order(tmp_path):
    path = tmp_path / "zwick.txt"
    path.write_bytes(
        'Prüfer\tM.\n\nStandardkraft\tStandardweg\tPrüfzeit\n"N"\t"mm"\t"s"\n1,5\t0,25\t0,1\n2,5\t0,5\t0,2\n'.encode(
            "cp1252"
        )
    )
    export = read_machine_export(path)
    assert export.format == "zwick_testxpert"
    np.testing.assert_array_equal(export.columns["force_N"], [1.5, 2.5])
    np.testing.assert_array_equal(export.columns["extension_m"], [0.25e-3, 0.5e-3])
    np.testing.assert_array_equal(export.columns["time_s"], [0.1, 0.2])


BAD_EXPORTS = [
    # (file text, the message: file, line, column and what is wrong)
    (
        "Prüfzeit;Standardweg;Standardkraft\ns;furlong;N\n0;0;1\n1;1;2\n",
        r"export.csv:2: column 2 'Standardweg': unknown unit 'furlong' for extension \(known: m, mm",
    ),
    (
        '"Time","Extension","Load"\n"(s)","(mm)","(lb)"\n"0","0","1"\n',
        r"export.csv:2: column 3 'Load': unknown unit 'lb'",
    ),
    ("Time,Extension,Load\n0,0,1\n1,1,2\n", r"export.csv:1: column 1 'Time' has no unit"),
    ('"Time","Extension","Load"\n"(s)","(mm)","(N)"\n"0","0","1"\n"1","0,5.0","2"\n', r"export.csv:4: column 2 "),
    ("Time;Extension;Load\ns;mm;N\n0;0;1\n1;0,5;x\n", r"export.csv:4: column 3 \(load\) = 'x' is not a number"),
    ("Time;Extension;Load\ns;mm;N\n0;0;1\n0;0,5;2\n", r"export.csv:4: column 1 \(time\) = '0' does not increase"),
    ("Time;Extension;Load\ns;mm;N\n0;0;1\n", r"export.csv: needs at least 2 samples"),
]


@pytest.mark.parametrize("text, message", BAD_EXPORTS)
def test_a_bad_export_is_named_by_file_line_and_column(tmp_path, write_experiment, text, message):
    toml = write_experiment()
    (tmp_path / "export.csv").write_text(text)
    toml.write_text(toml.read_text().replace('data = "run.csv"', 'data = "export.csv"'))
    with pytest.raises(ExperimentError, match=message):
        load_experiment(toml)
    with pytest.raises(LoggerError, match=message):  # pamkit align reads it with the same reader
        read_machine_csv(tmp_path / "export.csv")


def test_a_header_that_is_neither_pamkits_nor_a_machines_names_its_first_column(tmp_path, write_experiment):
    # Time and extension, no load: not an export; pamkit's own header check names what is unknown,
    # each name completed by the line of units under it ("Time" over "s" is time_s).
    toml = write_experiment(csv_text="Time;Extension\ns;mm\n0;0\n1;1\n")
    with pytest.raises(ExperimentError, match=r"run.csv:1: column 2 'Extension \[mm\]' is not a known channel"):
        load_experiment(toml)
    with pytest.raises(ExperimentError, match=r"run.csv: no row naming time, extension .* and load"):
        read_machine_export(toml.parent / "run.csv")


def test_align_reads_a_zwick_export(machines_dir):
    # `pamkit align` reads the machine's file with read_machine_csv: the same columns as an experiment.
    machine = read_machine_csv(machines_dir / "zwick_testxpert.csv")
    experiment = load_experiment(machines_dir / "zwick_testxpert.toml")
    np.testing.assert_array_equal(machine["time_s"], experiment.time_s)
    np.testing.assert_array_equal(machine["extension_m"], experiment.elongation_m)
    np.testing.assert_array_equal(machine["force_N"], experiment.columns["force_N"])


def test_pamkits_channels_headed_as_a_spreadsheet_heads_them_are_all_read(tmp_path):
    # "Time (s)", "Pressure [kPa]", "Temperature (°C)": pamkit's CSV with its units in brackets is
    # pamkit's CSV, every channel read (such a file was taken for a machine's export, which reads
    # time, extension and load, and its pressure and temperature were lost without a word). A
    # machine's own export with a logger's pressure beside it says what it leaves unread.
    plain = tmp_path / "plain.csv"
    plain.write_text("time_s,elongation_m,force_N,pressure_kPa,temperature_C\n0,0,1,150,20\n1,0.002,9,160,20.5\n")
    spelled = tmp_path / "spelled.csv"
    spelled.write_text(
        "Time (s),Elongation [mm],FORCE_N,Pressure (bar),Temperature (°C)\n0,0,1,1.5,20\n1,2,9,1.6,20.5\n"
    )
    expected, columns = read_series(plain), read_series(spelled)
    assert list(columns) == list(expected)
    for name in expected:
        np.testing.assert_allclose(columns[name], expected[name], rtol=1e-15, err_msg=name)
    export = tmp_path / "export.csv"
    for pressure in ("Pressure (kPa)", "Pressure (bar)", "absolute_pressure_kPa"):
        export.write_text(f"Time (s),Extension (mm),Load (N),{pressure}\n0,0,1,150\n1,2,9,160\n")
        with pytest.warns(
            ExperimentWarning, match=rf"export.csv:1: read as a tensile machine's export.*{re.escape(repr(pressure))}"
        ):
            columns = read_series(export)
        assert list(columns) == ["time_s", "elongation_m", "force_N"]
    # A logger's pressure named over its unit, as the machine's channels are: said too.
    export.write_text("Time,Extension,Load,Pressure\ns,mm,N,kPa\n0,0,1,150\n1,2,9,160\n")
    with pytest.warns(
        ExperimentWarning, match=r"export.csv:1: read as a tensile machine's export.*'Pressure' not read"
    ):
        assert list(read_series(export)) == ["time_s", "elongation_m", "force_N"]
