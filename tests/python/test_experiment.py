"""Experiment files: what is read, that every bad input names the file, line and column, and
that what the one writer writes reads back as written."""

import numpy as np
import pytest

try:
    import tomllib
except ModuleNotFoundError:  # Python < 3.11
    import tomli as tomllib

import pamkit
from pamkit import Construction
from pamkit.io.experiment import load_experiment
from pamkit.io.guards import ExperimentError, ExperimentWarning
from pamkit.io.series import read_series
from pamkit.io.writers import write_experiment


def test_reads_build_test_and_series(write_experiment):
    experiment = load_experiment(write_experiment())
    assert experiment.build.length_m == 0.225
    assert experiment.inflation_gauge_pressure_Pa == 236.63e3  # the file's 236.63 kPa, in Pa
    assert experiment.gas_params.ambient_temperature_K == pytest.approx(296.0)  # 22.85 °C, table C.4
    assert experiment.gas == pamkit.GasMode.sealed
    np.testing.assert_array_equal(experiment.elongation_m, [0, 0.0025, 0.005])
    assert experiment.measured() == []


def test_optional_sections_set_model_fields(write_experiment):
    path = write_experiment(
        sections='[gas]\nprocess = "heat_transfer"\nheat_transfer_time_constant_s = 3.0\n'
        "[friction]\nsharpness_s_per_m = 100.0\n"
    )
    experiment = load_experiment(path)
    assert experiment.gas_params.process.name == "heat_transfer"
    assert experiment.gas_params.heat_transfer_time_constant_s == 3.0
    assert experiment.friction.sharpness_s_per_m == 100.0


@pytest.mark.parametrize(
    "kwargs, expected",
    [
        ({"muscle_extra": "fiber_angle = 3"}, "unknown key [muscle] fiber_angle"),
        ({"toml_test_extra": "speed = 1"}, "unknown key [test] speed"),
        ({"sections": "[model]\nx = 1\n"}, "unknown section [model]"),
        ({"muscle_extra": "", "toml_test_extra": 'gas = "open"'}, "[test] gas = 'open'"),
        ({"sections": '[gas]\nprocess = "magic"\n'}, "[gas] process = 'magic'"),
        ({"sections": "[friction]\nsharpness_s_per_m = -1\n"}, "FrictionParams.sharpness_s_per_m = -1"),
    ],
)
def test_bad_keys_and_values_are_named(write_experiment, kwargs, expected):
    with pytest.raises(ExperimentError, match=None) as error:
        load_experiment(write_experiment(**kwargs))
    assert expected in str(error.value)
    assert "run.toml" in str(error.value)


def test_bad_build_names_the_field(write_experiment, tmp_path):
    path = write_experiment()
    path.write_text(path.read_text().replace("fiber_count = 216", "fiber_count = 0"))
    with pytest.raises(ExperimentError, match=r"run.toml: \[muscle\] MuscleBuild.fiber_count = 0"):
        load_experiment(path)


def test_missing_required_key(write_experiment):
    path = write_experiment()
    path.write_text(path.read_text().replace("ambient_temperature_C = 22.85\n", ""))
    with pytest.raises(ExperimentError, match=r"missing key \[test\] ambient_temperature_C"):
        load_experiment(path)


@pytest.mark.parametrize(
    "csv_text, expected",
    [
        ("time_s,elongation_m\n0,0\n1,inf\n", r"run.csv:3: column 2 \(elongation_m\) = 'inf' is not finite"),
        ("time_s,elongation_m\n0,0\n1,abc\n", r"run.csv:3: column 2 \(elongation_m\) = 'abc' is not a number"),
        ("time_s,elongation_m\n0,0\n2,0.001\n1.5,0.002\n", r"run.csv:4: column 1 \(time_s\) = 1.5 does not increase"),
        ("time_s,force_N\n0,0\n1,1\n", r"run.csv:1: required column 'elongation_m' is missing"),
        ("time_s,elongation_m,force_lbf\n0,0,1\n1,1,1\n", r"run.csv:1: column 3 'force_lbf' is not a known channel"),
        ("time_s,elongation_m\n0,0\n1\n", r"run.csv:3: 1 values, the header has 2"),
        ("time_s,elongation_m\n0,0\n", r"needs at least 2 data rows"),
        ("", r"empty file"),
    ],
)
def test_bad_csv_names_line_and_column(write_experiment, csv_text, expected):
    with pytest.raises(ExperimentError, match=expected):
        load_experiment(write_experiment(csv_text=csv_text))


def test_supplied_test_needs_pressure(write_experiment):
    with pytest.raises(ExperimentError, match="supplied.*pressure_kPa"):
        load_experiment(write_experiment(toml_test_extra='gas = "supplied"'))


def test_missing_data_file(write_experiment, tmp_path):
    path = write_experiment()
    (tmp_path / "run.csv").unlink()
    with pytest.raises(ExperimentError, match="no such data file"):
        load_experiment(path)


def test_every_thesis_experiment_loads(thesis_dir):
    paths = sorted(thesis_dir.glob("pam*.toml"))
    assert len(paths) == 15  # 6 low-pressure tests (table 3.5) + 3 x 3 high-pressure (tables C.1-C.3)
    for path in paths:
        experiment = load_experiment(path)
        # Protocol of section 3.2.1: 10 cycles at 2.5 mm/s, so 20 ramps of max / speed seconds.
        top = experiment.elongation_m.max()
        assert experiment.time_s[-1] == pytest.approx(20 * top / 2.5e-3, rel=1e-9)


def test_read_series_keeps_measured_channels(tmp_path):
    path = tmp_path / "m.csv"
    path.write_text("time_s,elongation_m,force_N,pressure_kPa,temperature_C\n0,0,1,2,3\n1,0.1,4,5,6\n")
    columns = read_series(path)
    # The file's units are a person's; what is read is SI, each channel converted once here.
    assert list(columns) == ["time_s", "elongation_m", "force_N", "gauge_pressure_Pa", "temperature_K"]
    np.testing.assert_array_equal(columns["gauge_pressure_Pa"], [2e3, 5e3])
    np.testing.assert_array_equal(columns["temperature_K"], [3 + 273.15, 6 + 273.15])


def _commercial(tmp_path, muscle="", sections="", test_extra=""):
    (tmp_path / "map.csv").write_text("length_m,pressure_kPa,force_N\n0.25,100,50\n0.24,100,20\n")
    path = tmp_path / "map.toml"
    path.write_text(
        "[muscle]\nlength_m = 0.25\ndiameter_m = 0.01\nbladder_diameter_m = 0.0097\nbladder_thickness_m = 0.0005\n"
        f"fiber_thickness_m = 0.0\ncone_generator_m = 0.0\nend_diameter_m = 0.005\n{muscle}\n"
        f'{sections}\n[test]\nkind = "isometric_map"\ndata = "map.csv"\n{test_extra}'
    )
    return path


def test_a_datasheet_braid_angle_becomes_fiber_revolutions(tmp_path):
    import math

    experiment = load_experiment(_commercial(tmp_path, "braid_angle_deg = 21.0"))
    # Flat ends: tan(theta) = pi n D / L over the whole deflated length.
    assert experiment.build.fiber_revolutions == pytest.approx(0.25 * math.tan(math.radians(21)) / (math.pi * 0.01))
    assert experiment.is_table and experiment.kind == "isometric_map"
    assert set(experiment.columns) == {"length_m", "gauge_pressure_Pa", "force_N"}
    with pytest.raises(ExperimentError, match="both braid_angle_deg and fiber_revolutions"):
        load_experiment(_commercial(tmp_path, "braid_angle_deg = 21.0\nfiber_revolutions = 1.0"))
    with pytest.raises(ExperimentError, match="between 0 and 90"):
        load_experiment(_commercial(tmp_path, "braid_angle_deg = 95.0"))


def test_the_construction_is_read_by_name_and_a_sleeve_by_default(tmp_path):
    # Festo's fibres are in the membrane: `construction = "embedded"`; a file that says nothing is
    # the thesis's bladder in a braided sleeve. Any other name is refused, naming the key and the
    # names it takes.
    assert load_experiment(_commercial(tmp_path, "braid_angle_deg = 21.0")).build.construction == Construction.sleeve
    embedded = load_experiment(_commercial(tmp_path, 'braid_angle_deg = 21.0\nconstruction = "embedded"'))
    assert embedded.build.construction == Construction.embedded
    with pytest.raises(
        ExperimentError, match="map.toml: \\[muscle\\] construction = 'woven' must be one of sleeve, embedded"
    ):
        load_experiment(_commercial(tmp_path, 'braid_angle_deg = 21.0\nconstruction = "woven"'))
    with pytest.raises(ExperimentError, match="construction = \\['embedded'\\] must be one of"):
        load_experiment(_commercial(tmp_path, 'braid_angle_deg = 21.0\nconstruction = ["embedded"]'))


@pytest.mark.parametrize(
    "sections, message",
    [
        ('[bladder]\nlaw = "mooney"', "law = 'mooney' must be one of thesis, neo_hookean, none"),
        ('[bladder]\nlaw = "neo_hookean"', "needs shear_modulus_Pa"),
        ('[bladder]\nlaw = "thesis"\nshear_modulus_Pa = 1e6', "belongs to law = 'neo_hookean'"),
        ("[calibrate]\nfiber_colour = [1, 2]", "fiber_colour: not a field pamkit can calibrate"),
        ("[calibrate]\nbraid_angle_deg = [30, 20]", "needs finite lower < upper"),
        ("[calibrate]\nbraid_angle_deg = 20", "must be \\[lower, upper\\]"),
        ("[calibrate]\nlength_m = [0.001, 0.3]", "leaves the allowed"),
        ("[calibrate]\nbladder.shear_modulus_Pa = [1e4, 1e7]", "needs \\[bladder\\] law = 'neo_hookean'"),
    ],
)
def test_bladder_and_calibrate_tables_name_what_is_wrong(tmp_path, sections, message):
    with pytest.raises(ExperimentError, match=message):
        load_experiment(_commercial(tmp_path, "braid_angle_deg = 21.0", sections))


def test_a_table_names_its_missing_column_and_its_kind(tmp_path):
    path = _commercial(tmp_path, "braid_angle_deg = 21.0")
    (tmp_path / "map.csv").write_text("length_m,pressure_kPa\n0.25,100\n0.24,100\n")
    with pytest.raises(ExperimentError, match="map.csv:1: required column 'force_N' is missing"):
        load_experiment(path)
    path.write_text(path.read_text().replace('kind = "isometric_map"', 'kind = "isobaric"'))
    with pytest.raises(ExperimentError, match="kind = 'isobaric' must be one of"):
        load_experiment(path)


def test_repeated_time_stamps_are_merged_with_a_warning(tmp_path):
    # A logger whose millisecond clock repeats a stamp: one sample, the mean of the rows.
    path = tmp_path / "run.csv"
    path.write_text("time_s,elongation_m,force_N\n0,0,1\n0.001,0.001,2\n0.001,0.003,4\n0.002,0.004,5\n")
    with pytest.warns(ExperimentWarning, match=r"run.csv:4: 1 row\(s\) repeat the time stamp"):
        columns = read_series(path)
    assert list(columns["time_s"]) == [0, 0.001, 0.002]
    assert columns["elongation_m"][1] == pytest.approx(0.002) and columns["force_N"][1] == pytest.approx(3.0)


def test_a_cut_last_line_is_dropped_with_a_warning_and_a_whole_one_kept(tmp_path):
    path = tmp_path / "run.csv"
    path.write_text("time_s,elongation_m\n0,0\n1,0.001\n2,0.002\n3,")  # the recording stopped mid-line
    with pytest.warns(ExperimentWarning, match=r"run.csv:5: the last line is cut off"):
        columns = read_series(path)
    assert list(columns["time_s"]) == [0, 1, 2]
    path.write_text("time_s,elongation_m\n0,0\n1,0.001\n2,0.002")  # no final line end, but whole
    assert list(read_series(path)["time_s"]) == [0, 1, 2]
    path.write_text("time_s,elongation_m\n0,0\n1,x\n2,0.002\n")  # inside the file it is an error
    with pytest.raises(ExperimentError, match="run.csv:3: column 2"):
        read_series(path)


def test_spreadsheet_exports_load_a_bom_semicolons_and_decimal_commas(tmp_path):
    path = tmp_path / "run.csv"
    path.write_bytes("\ufefftime_s,elongation_m\n0,0\n1,0.001\n".encode())  # Excel's UTF-8 with BOM
    assert list(read_series(path)["time_s"]) == [0, 1]
    path.write_text("time_s;elongation_m;force_N\n0;0;1,5\n1;0,001;2,25\n")  # a European export
    columns = read_series(path)
    assert list(columns["force_N"]) == [1.5, 2.25] and columns["elongation_m"][1] == 0.001
    path.write_text("time_s;elongation_m\n0;0\n1;abc\n")
    with pytest.raises(ExperimentError, match=r"run.csv:3: column 2 \(elongation_m\) = 'abc' is not a number"):
        read_series(path)


def reads_as(path, plain: str, *texts: str) -> None:
    """Each of `texts`, written to `path`, reads as the plain CSV `plain` does: the same columns,
    the same values."""
    path.write_text(plain)
    expected = read_series(path)
    for text in texts:
        path.write_text(text)
        columns = read_series(path)
        assert list(columns) == list(expected), repr(text)
        for name in expected:
            np.testing.assert_array_equal(columns[name], expected[name], err_msg=repr(text))


def refuses(path, text: str, message: str) -> None:
    """`text`, written to `path`, is refused with an error matching `message`."""
    path.write_text(text)
    with pytest.raises(ExperimentError, match=message):
        read_series(path)


def test_a_trailing_delimiter_on_every_line_is_an_empty_column_left_unread(tmp_path):
    # A spreadsheet saved with an empty last column: every line ends in a delimiter, the header
    # too. The column has no name and holds nothing, so it is left out; one that holds a value
    # is refused, naming its line and column.
    path = tmp_path / "run.csv"
    reads_as(
        path,
        "time_s,elongation_m,force_N\n0,0,1\n1,0.001,2\n",
        "time_s,elongation_m,force_N,\n0,0,1,\n1,0.001,2,\n",
        "time_s;elongation_m;;force_N\n0;0;;1\n1;0,001;;2\n",
    )
    refuses(
        path,
        "time_s,elongation_m,force_N,\n0,0,1,\n1,0.001,2,7\n",
        r"run.csv:3: column 4 has no name in the header but holds '7'",
    )


def test_a_line_of_units_under_the_names_completes_them(tmp_path):
    # A logger's header in two lines, names over units: each name takes its unit ("Time" over "s"
    # reads as time_s, "Elongation" over "(mm)" as elongation_mm), and the line is no data row;
    # errors still name the file's own lines. Under pamkit's own names the line may repeat their
    # units; a unit that is not the name's keeps the line as data, and its error says so.
    path = tmp_path / "run.csv"
    reads_as(
        path,
        "time_s,elongation_m,force_N,pressure_kPa\n0,0,1,150\n1,0.001,2,160\n",
        "Time,Elongation,Force,Pressure\ns,mm,N,bar\n0,0,1,1.5\n1,1,2,1.6\n",
        "# logger 3\nTime;Elongation;Force;Pressure\n(s);(mm);(N);(kPa)\n0;0;1;150\n1;1;2;160\n",
        "time_s,elongation_m,force_N,pressure_kPa\ns,m,N,kPa\n0,0,1,150\n1,0.001,2,160\n",
    )
    refuses(
        path,
        "Time,Elongation,Force\ns,mm,N\n0,0,1\n1,abc,2\n",
        r"run.csv:4: column 2 \(Elongation \[mm\]\) = 'abc' is not a number",
    )
    refuses(
        path,
        "time_s,elongation_m,pressure_kPa\ns,m,bar\n0,0,1\n1,0.001,1\n",
        r"run.csv:2: column 1 \(time_s\) = 's' is not a number",
    )
    # [test] ignore_columns names a column as the file's names row does, without its unit.
    path.write_text("Time,Valve,Elongation\ns,V,mm\n0,1,0\n1,0,1\n")
    assert list(read_series(path, ignore=("Valve",))) == ["time_s", "elongation_m"]


def test_comment_lines_are_skipped_and_lines_keep_their_numbers(tmp_path):
    # A logger's or a rig's notes: "#" lines before the header and between rows, in a file numpy
    # reads in blocks (comments only above the header) and one read row by row.
    path = tmp_path / "run.csv"
    reads_as(
        path,
        "time_s,elongation_m,force_N\n0,0,1\n1,0.001,2\n2,0.002,3\n",
        "# rig B, 2026-11-27\n\n# operator JS\ntime_s,elongation_m,force_N\n0,0,1\n1,0.001,2\n2,0.002,3\n",
        "\ufeff# rig B\ntime_s,elongation_m,force_N\n0,0,1\n# valve opened\n1,0.001,2\n  # a note\n2,0.002,3\n",
        '# rig B\ntime_s;elongation_m;force_N\n0;0;1\n"1";0,001;2\n2;0,002;3\n',
    )
    # Errors name the file's own lines: the header's, a row's, after comments.
    refuses(
        path,
        "# rig B\n# operator JS\ntime_s,elongation_m,force_lbf\n0,0,1\n1,0.001,2\n",
        r"run.csv:3: column 3 'force_lbf' is not a known channel",
    )
    refuses(
        path,
        "# rig B\ntime_s,elongation_m\n0,0\n# valve opened\n1,abc\n",
        r"run.csv:5: column 2 \(elongation_m\) = 'abc' is not a number",
    )
    refuses(
        path,
        "# rig B\ntime_s,elongation_m\n0,0\n2,0.001\n1,0.002\n",
        r"run.csv:5: column 1 \(time_s\) = 1.0 does not increase",
    )  # read in blocks
    refuses(path, "# only a note\n", "empty file, expected a header row")


def test_a_table_reads_its_rows_in_order_and_drops_what_its_kind_does_not_use(tmp_path):
    # A logger beside an isometric map adds time and temperature: the time orders the rows (the
    # pressurise/vent branches follow them), the temperature is not the map's and is said so.
    path = _commercial(tmp_path, "braid_angle_deg = 21.0")
    plain = load_experiment(path).columns
    (tmp_path / "map.csv").write_text(
        "time_s,length_m,pressure_kPa,force_N,temperature_C\n0,0.25,100,50,21.5\n12,0.24,100,20,21.6\n"
    )
    with pytest.warns(ExperimentWarning, match=r"map.csv:1: temperature_C is not used by this isometric_map test"):
        columns = load_experiment(path).columns
    assert list(columns) == list(plain)
    for name in plain:
        np.testing.assert_array_equal(columns[name], plain[name])
    (tmp_path / "map.csv").write_text("Length [mm],Pressure (kPa),Force [N]\n250,100,50\n240,100,20\n")
    for name, values in load_experiment(path).columns.items():  # headed as a spreadsheet heads them
        np.testing.assert_allclose(values, plain[name], rtol=1e-15, err_msg=name)
    (tmp_path / "map.csv").write_text("time_s,length_m,pressure_kPa,force_N\n12,0.25,100,50\n0,0.24,100,20\n")
    with pytest.raises(ExperimentError, match=r"map.csv:3: column 1 \(time_s\) = 0.0 does not increase"):
        load_experiment(path)
    (tmp_path / "map.csv").write_text("length_m,pressure_kPa,force_N,valve\n0.25,100,50,1\n0.24,100,20,0\n")
    with pytest.raises(ExperimentError, match=r"map.csv:1: column 4 'valve' is not a known channel"):
        load_experiment(path)  # not pamkit's: a misspelt channel must not pass unread


def test_columns_in_other_units_are_read_in_pamkits(tmp_path):
    # A lab's files in millimetres, bar, kN, psi and milliseconds: the same SI columns as the file
    # in pamkit's units (1 bar = 100 kPa, 1 psi = 6.894757 kPa: units.hpp).
    path = tmp_path / "run.csv"
    path.write_text("time_s,elongation_m,force_N,pressure_kPa\n0,0,10,150\n0.5,0.002,250,165\n")
    expected = read_series(path)
    for header, rows in (
        ("time_ms,elongation_mm,force_kN,pressure_bar", "0,0,0.01,1.5\n500,2,0.25,1.65\n"),
        ("time_s,elongation_m,force_N,pressure_MPa", "0,0,10,0.15\n0.5,0.002,250,0.165\n"),
        ('"time_s";"elongation_mm";"force_N";"pressure_bar"', "0;0;10;1,5\n0,5;2;250;1,65\n"),  # row by row
    ):
        path.write_text(f"{header}\n{rows}")
        columns = read_series(path)
        assert list(columns) == list(expected)
        for name in expected:
            np.testing.assert_allclose(columns[name], expected[name], rtol=1e-15, err_msg=f"{header}: {name}")
    path.write_text("time_s,elongation_m,pressure_psi\n0,0,20\n1,0.001,21\n")
    np.testing.assert_allclose(read_series(path)["gauge_pressure_Pa"], [137895.14586336722, 144789.90315653558])
    # An isotonic test's contraction in millimetres, from the deflated length.
    (tmp_path / "iso.csv").write_text("pressure_bar,contraction_mm\n2,10\n4,30\n")
    iso = tmp_path / "iso.toml"
    iso.write_text(
        _commercial(tmp_path, "braid_angle_deg = 21.0")
        .read_text()
        .replace('"isometric_map"', '"isotonic"')
        .replace('data = "map.csv"', 'data = "iso.csv"\nload_N = 100')
    )
    columns = load_experiment(iso).columns
    np.testing.assert_allclose(columns["length_m"], [0.24, 0.22])
    np.testing.assert_allclose(columns["gauge_pressure_Pa"], [2e5, 4e5])


@pytest.mark.parametrize(
    "header, message",
    [
        ("time_s,elongation_m,elongation_mm", r"run.csv:1: columns 'elongation_m' and 'elongation_mm' both give"),
        ("time_s,elongation_mm,elongation_mm", r"run.csv:1: column 'elongation_mm' appears twice"),
        (
            "time_s,elongation_m,force_lbf",
            r"column 3 'force_lbf' is not a known channel .*or in other units: .*force_kN",
        ),
    ],
)
def test_a_column_in_another_unit_is_named_where_it_clashes_or_is_unknown(tmp_path, header, message):
    path = tmp_path / "run.csv"
    path.write_text(f"{header}\n0,0,0\n1,0.001,0.001\n")
    with pytest.raises(ExperimentError, match=message):
        read_series(path)


def test_values_in_another_unit_than_the_column_names_are_refused(tmp_path):
    # Pascals under a kPa name in an isotonic test (as in a time series): a muscle at 575 MPa
    # would be diagnosed as it stands. 2000 kPa: the highest inflation pressure a file may declare.
    iso = _commercial(tmp_path, "braid_angle_deg = 21.0")
    iso.write_text(
        iso.read_text().replace('"isometric_map"', '"isotonic"').replace('"map.csv"', '"iso.csv"\nload_N = 9')
    )
    (tmp_path / "iso.csv").write_text("pressure_kPa,length_m\n150000,0.24\n575000,0.22\n")
    with pytest.raises(
        ExperimentError,
        match=r"iso.csv:2: column 1 \(pressure_kPa\) = 150000 is outside \[-101, 2000\]: "
        r"is it in pascals or psi\? \(a file may give pressure_kPa as pressure_bar",
    ):
        load_experiment(iso)
    (tmp_path / "iso.csv").write_text("pressure_bar,length_m\n150,0.24\n165,0.22\n")  # kPa under a bar name
    with pytest.raises(ExperimentError, match=r"iso.csv:2: column 1 \(pressure_kPa\) = 15000 is outside"):
        load_experiment(iso)
    # Metres under a millimetre name: a 0.25 mm muscle, against the 250 mm [muscle] declares.
    map_toml = _commercial(tmp_path, "braid_angle_deg = 21.0")
    (tmp_path / "map.csv").write_text("length_mm,pressure_kPa,force_N\n0.25,100,50\n0.24,100,20\n")
    with pytest.raises(ExperimentError, match=r"map.csv: the muscle's length spans 0.00024 to 0.00025 m, outside"):
        load_experiment(map_toml)
    (tmp_path / "map.csv").write_text("length_mm,pressure_kPa,force_N\n250,100,50\n240,100,20\n")
    np.testing.assert_allclose(load_experiment(map_toml).columns["length_m"], [0.25, 0.24])


def test_what_is_not_a_readable_text_file_is_named(tmp_path, write_experiment):
    with pytest.raises(ExperimentError, match="is a folder; give the data file itself"):
        read_series(tmp_path)
    (tmp_path / "bad.csv").write_bytes(b"time_s,elongation_m\n0,0\n1,\xff\n")
    with pytest.raises(ExperimentError, match=r"bad.csv:3: byte 0xff is not UTF-8 text"):
        read_series(tmp_path / "bad.csv")
    loop = tmp_path / "loop.csv"
    loop.symlink_to(loop)
    with pytest.raises(ExperimentError, match="loop.csv"):
        read_series(loop)
    with pytest.raises(ExperimentError, match="is a folder; give the experiment file itself"):
        load_experiment(tmp_path)


def test_a_datasheet_build_gets_its_other_dimensions_scaled_with_its_diameter(tmp_path):
    # A 10 mm muscle given by length, diameter and braid angle alone: PAM 2's defaults (table
    # C.4, a 20 mm braid) halved, so that the bladder and end caps fit inside the braid.
    (tmp_path / "map.csv").write_text("length_m,pressure_kPa,force_N\n0.25,100,50\n0.24,100,20\n")
    path = tmp_path / "map.toml"
    path.write_text(
        "[muscle]\nlength_m = 0.25\ndiameter_m = 0.01\nbraid_angle_deg = 21.0\n"
        '[test]\nkind = "isometric_map"\ndata = "map.csv"\n'
    )
    build = load_experiment(path).build
    thesis = pamkit.MuscleBuild()
    assert build.bladder_diameter_m == pytest.approx(thesis.bladder_diameter_m / 2)
    assert build.end_diameter_m == pytest.approx(thesis.end_diameter_m / 2)
    assert build.cone_generator_m == pytest.approx(thesis.cone_generator_m / 2)
    assert build.bladder_thickness_m == pytest.approx(thesis.bladder_thickness_m / 2)
    assert build.fiber_count == thesis.fiber_count  # a count, not a length


def test_an_offset_run_zeroes_the_load_cell_and_the_transducer(write_experiment, tmp_path):
    # [test] zero = "offset.csv": a run with no air whose means zero the sensors.
    path = write_experiment(
        csv_text="time_s,elongation_m,force_N,pressure_kPa,temperature_C\n0,0,25,245,23\n1,0.001,30,250,23\n",
        toml_test_extra='zero = "offset.csv"',
    )
    (tmp_path / "offset.csv").write_text(
        "time_s,elongation_m,force_N,pressure_kPa,temperature_C\n0,0,19,8,22\n1,0,21,10,22\n"
    )
    experiment = load_experiment(path)
    assert list(experiment.columns["force_N"]) == [5.0, 10.0]  # 20 N of preload and tare taken off
    # The transducer's 9 kPa at atmosphere taken off the file's 245 and 250 kPa, in Pa.
    assert list(experiment.columns["gauge_pressure_Pa"]) == [236e3, 241e3]
    assert list(experiment.columns["temperature_K"]) == [23.0 + 273.15, 23.0 + 273.15]
    assert experiment.zeroed == {"force_N": 20.0, "gauge_pressure_Pa": 9e3}
    (tmp_path / "offset.csv").write_text("time_s,elongation_m\n0,0\n1,0\n")
    with pytest.raises(ExperimentError, match="has none of the channels it could zero"):
        load_experiment(path)


def test_a_zero_runs_glitch_is_left_out_of_its_mean(write_experiment, tmp_path):
    # A zero run of 200 samples, the load cell's noise 0.5 N around 20 N and the transducer's
    # ADC toggling between two counts: a stray read of 170 N would move the force's mean by
    # 0.75 N. Left out (it stands hundreds of times the noise off the median), the offset is the
    # clean run's mean; the two counts are no glitch; the warning is kept with the experiment.
    rng = np.random.default_rng(3)
    force = 20.0 + rng.normal(0.0, 0.5, 200)
    pressure = np.where(rng.random(200) < 0.7, 9.0, 9.5)  # kPa, two counts
    glitched = force.copy()
    glitched[120] += 150.0
    rows = "".join(f"{k * 0.05:.2f},0,{f:.6f},{p},22\n" for k, (f, p) in enumerate(zip(glitched, pressure)))
    (tmp_path / "offset.csv").write_text("time_s,elongation_m,force_N,pressure_kPa,temperature_C\n" + rows)
    path = write_experiment(
        csv_text="time_s,elongation_m,force_N,pressure_kPa,temperature_C\n0,0,25,245,23\n1,0.001,30,250,23\n",
        toml_test_extra='zero = "offset.csv"',
    )
    with pytest.warns(ExperimentWarning, match=r"1 sample\(s\) of force_N stand over 12 times the run's noise"):
        experiment = load_experiment(path)
    assert experiment.zeroed["force_N"] == pytest.approx(float(np.mean(np.round(np.delete(force, 120), 6))))
    assert experiment.zeroed["gauge_pressure_Pa"] == pytest.approx(1e3 * float(np.mean(pressure)))
    assert len(experiment.data_warnings) == 1 and "offset.csv" in experiment.data_warnings[0]


# --- the one writer -------------------------------------------------------------------------------


def test_a_written_experiment_reads_back_as_written(tmp_path):
    build = pamkit.MuscleBuild(length_m=0.2256, diameter_m=0.01991)
    columns = {"time_s": np.array([0.0, 0.1, 0.2]), "elongation_m": np.array([0.0, 1e-4, 2e-4])}
    test = {"description": "a test", "inflation_pressure_kPa": 150.82, "ambient_temperature_C": 20.3}
    data = write_experiment(tmp_path / "run.toml", {"muscle": build.to_dict(), "test": test}, columns, ["made here"])
    assert data == tmp_path / "run.csv"
    experiment = load_experiment(tmp_path / "run.toml")
    assert experiment.build.to_dict() == build.to_dict()  # every field, bit for bit (repr round-trips)
    # In SI, as the reader converts them: 150.82 kPa and 20.3 °C.
    assert experiment.inflation_gauge_pressure_Pa == 150.82e3
    assert experiment.gas_params.ambient_temperature_K == 20.3 + 273.15
    np.testing.assert_array_equal(experiment.elongation_m, columns["elongation_m"])
    text = (tmp_path / "run.toml").read_text()
    # The layout: comments, [muscle], [test] ending with the data line; whole numbers as integers.
    assert text.startswith("# made here\n\n[muscle]\nlength_m = 0.2256\n")
    assert "fiber_count = 216\n" in text
    assert text.endswith('ambient_temperature_C = 20.3\ndata = "run.csv"\n')


def test_the_writer_escapes_what_toml_must_and_keeps_types(tmp_path):
    odd = 'quote " backslash \\ newline \n tab \t bell \x07 delete \x7f µ°'
    sections = {
        "muscle": {"length_m": 0.225, "fiber_count": 216, "a key with spaces": 1e-300},
        "gas": {"process": odd},
        "test": {"force_range_N": [-5, 1500.5], "description": odd, "data": "run.csv"},
    }
    write_experiment(tmp_path / "run.toml", sections)
    document = tomllib.loads((tmp_path / "run.toml").read_text(encoding="utf-8"))  # a strict reader accepts it
    assert document == sections
    assert isinstance(document["muscle"]["fiber_count"], int)


@pytest.mark.parametrize(
    ("sections", "message"),
    [
        ({"musle": {}, "test": {"data": "x.csv"}}, r"section \[musle\]"),
        ({"test": {"inflation_pressure": 1.0, "data": "x.csv"}}, r"\[test\] inflation_pressure"),
        ({"test": {"inflation_pressure_kPa": float("nan"), "data": "x.csv"}}, r"\[test\] inflation_pressure_kPa = nan"),
        ({"gas": {"process": {"nested": 1}}, "test": {"data": "x.csv"}}, r"\[gas\] process"),
        ({"test": {"inflation_pressure_kPa": 1.0}}, "names its data"),
    ],
)
def test_the_writer_refuses_what_the_reader_would_and_names_it(tmp_path, sections, message):
    with pytest.raises(ValueError, match=message):
        write_experiment(tmp_path / "run.toml", sections)
    assert not (tmp_path / "run.toml").exists()


def test_a_series_written_in_blocks_is_every_row_once_in_csvs_format(tmp_path, monkeypatch):
    # write_series formats WRITE_BLOCK_ROWS rows at a time (a 2-million-row simulation's text never
    # whole in memory); across block ends the file is the csv module's: CRLF, "%.10g", each row once.
    import pamkit.io.writers as writers

    monkeypatch.setattr(writers, "WRITE_BLOCK_ROWS", 4)
    time = np.arange(10) * 0.1
    elongation = np.linspace(0.0, 0.05, 10)
    force = np.pi * np.arange(10) - 7.0
    path = tmp_path / "series.csv"
    writers.write_series(path, {"time_s": time, "elongation_m": elongation, "force_N": force})
    expected = "time_s,elongation_m,force_N\r\n" + "".join(
        f"{t:.10g},{x:.10g},{f:.10g}\r\n" for t, x, f in zip(time, elongation, force)
    )
    assert path.read_bytes() == expected.encode()
    assert np.allclose(read_series(path)["force_N"], force, rtol=1e-9)


def test_columns_named_in_ignore_columns_are_left_unread_and_errors_keep_the_files_column_numbers(
    write_experiment, tmp_path
):
    # A logger's note and valve state between the channels: refused until named in
    # [test] ignore_columns, then left out; a bad value still names its own column in the file.
    path = write_experiment(csv_text="time_s,elongation_m,force_N\n0,0,1\n1,0.001,2\n2,0.002,3\n")
    plain = load_experiment(path).columns
    (tmp_path / "run.csv").write_text(
        "time_s,note,elongation_m,valve,force_N\n0,start,0,1,1\n1,,0.001,1,2\n2,stop,0.002,0,3\n"
    )
    with pytest.raises(ExperimentError, match=r"column 2 'note' is not a known channel.*\[test\] ignore_columns"):
        load_experiment(path)
    path = write_experiment(
        csv_text=(tmp_path / "run.csv").read_text(), toml_test_extra='ignore_columns = ["note", "valve"]'
    )
    columns = load_experiment(path).columns
    assert list(columns) == list(plain)
    for name in plain:
        np.testing.assert_array_equal(columns[name], plain[name])
    (tmp_path / "run.csv").write_text("time_s,note,elongation_m,valve,force_N\n0,a,0,1,1\n1,b,0.001,1,x\n")
    with pytest.raises(ExperimentError, match=r"run.csv:3: column 5 \(force_N\) = 'x' is not a number"):
        load_experiment(path)
    path = write_experiment(toml_test_extra='ignore_columns = "note"')
    with pytest.raises(ExperimentError, match=r"ignore_columns = 'note' must be a list of column names"):
        load_experiment(path)
    # A table the same way.
    table = _commercial(tmp_path, "braid_angle_deg = 21.0", test_extra='ignore_columns = ["operator"]')
    expected = load_experiment(table).columns
    (tmp_path / "map.csv").write_text("length_m,operator,pressure_kPa,force_N\n0.25,JS,100,50\n0.24,JS,100,20\n")
    for name, values in load_experiment(table).columns.items():
        np.testing.assert_array_equal(values, expected[name])


def test_a_tables_length_may_come_as_a_contraction_in_per_cent_of_the_deflated_length(tmp_path):
    # A datasheet's axis: force against contraction in per cent of the nominal length. A map and
    # an isotonic test read it as the muscle's length, deflated length x (1 - contraction / 100).
    path = _commercial(tmp_path, "braid_angle_deg = 21.0")  # [muscle] length_m = 0.25
    (tmp_path / "map.csv").write_text("Contraction [%],pressure_kPa,force_N\n0,100,50\n4,100,20\n")
    np.testing.assert_allclose(load_experiment(path).columns["length_m"], [0.25, 0.24], rtol=1e-15)
    (tmp_path / "iso.csv").write_text("pressure_kPa,contraction_percent\n200,4\n400,12\n")
    iso = tmp_path / "iso.toml"
    iso.write_text(
        path.read_text()
        .replace('"isometric_map"', '"isotonic"')
        .replace('data = "map.csv"', 'data = "iso.csv"\nload_N = 100')
    )
    np.testing.assert_allclose(load_experiment(iso).columns["length_m"], [0.24, 0.22], rtol=1e-15)
    # A fraction where per cent belongs is said; two measures at once are refused.
    (tmp_path / "iso.csv").write_text("pressure_kPa,contraction_percent\n200,0.04\n400,0.12\n")
    with pytest.warns(ExperimentWarning, match="contraction_percent stays within 1 %"):
        load_experiment(iso)
    (tmp_path / "iso.csv").write_text("pressure_kPa,length_m,contraction_percent\n200,0.24,4\n400,0.22,12\n")
    with pytest.raises(ExperimentError, match=r"iso.csv:1: this isotonic test gives the muscle's length as one of"):
        load_experiment(iso)


def test_a_load_cell_that_reads_tension_as_negative_is_said(tmp_path):
    # A muscle pulls; a map whose force pushes to -50 N and never pulls is a load cell read the
    # other way round (5 times harder push than pull, beyond 20 N: PUSH_OVER_PULL, PUSH_NOTICED_N).
    path = _commercial(tmp_path, "braid_angle_deg = 21.0")
    (tmp_path / "map.csv").write_text("length_m,pressure_kPa,force_N\n0.25,100,-50\n0.24,100,-20\n0.24,0,0.5\n")
    with pytest.warns(ExperimentWarning, match=r"force_N pushes down to -50 N and pulls at most 0.5 N"):
        load_experiment(path)
    (tmp_path / "map.csv").write_text("length_m,pressure_kPa,force_N\n0.25,100,50\n0.24,100,20\n0.24,0,-0.5\n")
    load_experiment(path)  # tension positive: nothing to say (a warning would fail the test)


def test_an_absolute_pressure_is_read_as_the_gauge_one_above_the_declared_atmosphere(write_experiment, tmp_path):
    # An MPX5700AP on an Arduino reads absolute pressure: named so, it is the gauge pressure plus
    # the atmosphere ([gas] atmospheric_pressure_Pa, 101 kPa by default: table C.4), in a series and a table.
    path = write_experiment(csv_text="time_s,elongation_m,pressure_kPa\n0,0,150\n1,0.001,160\n")
    gauge = load_experiment(path).columns["gauge_pressure_Pa"]
    path = write_experiment(csv_text="time_s,elongation_m,absolute_pressure_kPa\n0,0,251\n1,0.001,261\n")
    np.testing.assert_allclose(load_experiment(path).columns["gauge_pressure_Pa"], gauge, rtol=1e-12)
    path = write_experiment(
        csv_text="time_s,elongation_m,Absolute pressure [bar]\n0,0,2.4\n1,0.001,2.5\n",
        sections="[gas]\natmospheric_pressure_Pa = 90000.0\n",
    )
    np.testing.assert_allclose(load_experiment(path).columns["gauge_pressure_Pa"], gauge, rtol=1e-12)
    path = write_experiment(csv_text="time_s,elongation_m,pressure_kPa,absolute_pressure_kPa\n0,0,150,251\n1,0,1,2\n")
    with pytest.raises(ExperimentError, match=r"run.csv:1: the pressure is given twice"):
        load_experiment(path)
    table = _commercial(tmp_path, "braid_angle_deg = 21.0")
    expected = load_experiment(table).columns
    (tmp_path / "map.csv").write_text("length_m,absolute_pressure_kPa,force_N\n0.25,201,50\n0.24,201,20\n")
    for name, values in load_experiment(table).columns.items():
        np.testing.assert_allclose(values, expected[name], rtol=1e-12, err_msg=name)
