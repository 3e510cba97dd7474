"""No traceback, ever: random bytes, random TOML, random CSV and mutated valid files
thrown at load_experiment and simulate fail, when they fail, with an ExperimentError (or another
ValueError) whose message is one line naming the file.

Deterministic (derandomize: the same cases on every run, so CI does not flip) and bounded: four
properties of MAX_EXAMPLES cases each (600 cases: 6 s on an idle 2-core machine, 17 s on a busy one), every case
under DEADLINE_MS (a case that takes longer fails the test: a slow path is a bug here too).
"""

from __future__ import annotations

import json
import re
import tempfile
import warnings
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import pamkit
from pamkit.io.guards import ExperimentError, ExperimentWarning
from pamkit.io.schema import TEST_KEYS

MAX_EXAMPLES = 150
DEADLINE_MS = 5000
FUZZ = settings(
    max_examples=MAX_EXAMPLES,
    deadline=DEADLINE_MS,
    derandomize=True,
    database=None,
    suppress_health_check=[HealthCheck.too_slow],  # each case writes files: slow by hypothesis's measure
)

MUSCLE = (
    "[muscle]\nlength_m = 0.223\ndiameter_m = 0.02\nbladder_diameter_m = 0.01545\nbladder_thickness_m = 0.000254\n"
    "fiber_count = 216\nfiber_revolutions = 2\nfiber_thickness_m = 0.000254\nend_diameter_m = 0.013\n"
    "cone_generator_m = 0.0095\n"
)
TEST = (
    '[test]\ninflation_pressure_kPa = 35.0\nambient_temperature_C = 22.85\ninitial_length_m = 0.185\ndata = "run.csv"\n'
)
VALID_TOML = MUSCLE + TEST
VALID_CSV = "time_s,elongation_m,force_N\n0,0,1.5\n0.5,0.00125,2.5\n1,0.0025,3.1\n1.5,0.00125,2.4\n2,0,1.4\n"
CHANNELS = ("time_s", "elongation_m", "force_N", "pressure_kPa", "temperature_C", "length_m", "contraction_m")
MACHINE_NAMES = ("Time", "Extension", "Load", "Prüfzeit", "Standardweg", "Standardkraft", "Dehnung", "Zeit (s)")
UNITS = ("(s)", "(mm)", "(N)", "s", "mm", "kN", "furlong", "", "%", "[ms]")


# A message starts with the file it is about (an absolute path: the TOML's, or one it names), then
# maybe the line: "/tmp/x/run.csv:3: column 2 ...".
NAMES_A_FILE = re.compile(r"^/[^\n]*?(:\d+)?: ")


def attempt(directory: Path, toml: bytes | str, csv: bytes | str | None = None) -> None:
    """Writes the experiment (run.toml, run.csv) into `directory` and loads and simulates it;
    every error and warning must be pamkit's, one line, naming a file."""
    toml_path = directory / "run.toml"
    (directory / "loop").symlink_to("loop")  # a symbolic link to itself, for FILE_NAMES
    for path, content in ((toml_path, toml), (directory / "run.csv", csv)):
        if content is not None:
            path.write_bytes(content if isinstance(content, bytes) else content.encode("utf-8", "surrogatepass"))
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        try:
            experiment = pamkit.load_experiment(toml_path)
            frame = pamkit.simulate(experiment)
            assert len(frame) == len(next(iter(experiment.columns.values())))
        except ValueError as error:  # ExperimentError is one
            message = str(error)
            assert "\n" not in message, f"{type(error).__name__} of several lines: {message!r}"
            assert NAMES_A_FILE.match(message), f"{type(error).__name__} names no file: {message!r}"
    for warning in caught:
        assert issubclass(warning.category, ExperimentWarning), f"{warning.category.__name__}: {warning.message}"
        assert "\n" not in str(warning.message) and NAMES_A_FILE.match(str(warning.message)), str(warning.message)


def fresh_directory():
    return tempfile.TemporaryDirectory(prefix="pamkit-fuzz-")


@FUZZ
@given(st.binary(max_size=2000), st.one_of(st.none(), st.binary(max_size=2000)))
def test_random_bytes(toml, csv):
    with fresh_directory() as directory:
        attempt(Path(directory), toml, csv if csv is not None else VALID_CSV)


# Values of the keys that name files ([test] data and zero).
FILE_NAMES = st.sampled_from(
    [
        '"run.csv"',
        '"missing.csv"',
        '"."',
        '""',
        '"/dev/null"',
        '"run.toml"',
        '"a\\u0000b"',
        '"../"',
        '"/"',
        '"\\n"',
        '"loop"',
    ]
)
FILE_KEYS = ("data", "zero")
# TOML values as text: numbers, strings, booleans, dates, arrays and inline tables, some not TOML at all.
SCALARS = st.one_of(
    st.integers(-(10**20), 10**20).map(str),
    st.floats(allow_nan=True, allow_infinity=True).map(repr),
    st.sampled_from(["nan", "-inf", "+inf", "0", "-0.0", "1e308", "1e-320", "true", "false", "1979-05-27", "07:32:00"]),
    st.text(max_size=20).map(lambda s: json.dumps(s, ensure_ascii=False)),
    FILE_NAMES,
    st.sampled_from(['"sealed"', '"supplied"', '"isotonic"', '"isometric_map"', '"free_inflation"', '"neo_hookean"']),
    st.text(max_size=8),  # not a TOML value
)
# Numbers of the size a file holds: they pass TOML and reach the model's ranges and the solver.
NEAR_VALID = st.one_of(st.floats(-0.01, 1.0).map(repr), st.floats(0, 1000).map(repr), st.integers(0, 500).map(str))
VALUES = st.recursive(
    SCALARS,
    lambda inner: st.one_of(
        st.lists(inner, max_size=3).map(lambda items: "[" + ", ".join(items) + "]"),
        st.lists(st.tuples(st.sampled_from(["law", "a", "x"]), inner), max_size=2).map(
            lambda pairs: "{" + ", ".join(f"{k} = {v}" for k, v in pairs) + "}"
        ),
    ),
    max_leaves=4,
)
SECTION_KEYS = {
    "muscle": tuple(pamkit.MuscleBuild.fields()) + ("braid_angle_deg",),
    "test": tuple(TEST_KEYS),
    "friction": tuple(pamkit.FrictionParams.fields()),
    "gas": tuple(pamkit.GasParams.fields()) + ("process",),
    "bladder": ("law", "shear_modulus_Pa"),
    "calibrate": tuple(pamkit.MuscleBuild.fields()) + ("load_N", "braid_angle_deg", "bladder"),
}


def valid_sections() -> dict[str, dict[str, str]]:
    """VALID_TOML as {section: {key: value as TOML text}}."""
    sections: dict[str, dict[str, str]] = {}
    for line in VALID_TOML.splitlines():
        if line.startswith("["):
            current = sections.setdefault(line.strip("[]"), {})
        elif "=" in line:
            key, value = (part.strip() for part in line.split("=", 1))
            current[key] = value
    return sections


@st.composite
def toml_documents(draw):
    """The valid experiment with some keys set to random values (the file's own keys, other
    keys of its sections, unknown ones), some removed, some sections added; now and then a
    section or key written twice (a TOML error)."""
    sections = valid_sections()
    for _ in range(draw(st.integers(0, 3))):
        section = draw(st.sampled_from(sorted(SECTION_KEYS)))
        table = sections.setdefault(section, {})
        key = draw(st.sampled_from(SECTION_KEYS[section] + ("other",)))
        if key in table and draw(st.integers(0, 4)) == 4:
            del table[key]
        else:
            table[key] = draw(st.one_of(FILE_NAMES, VALUES) if key in FILE_KEYS else st.one_of(NEAR_VALID, VALUES))
    if draw(st.booleans()):  # a file name that is no file, or no name
        sections["test"][draw(st.sampled_from(FILE_KEYS))] = draw(FILE_NAMES)
    lines = []
    for section, table in sections.items():
        lines.append(f"[{section}]")
        lines += [f"{key} = {value}" for key, value in table.items()]
    if draw(st.integers(0, 9)) == 9:  # rarely: hypothesis draws the low end often
        lines += lines[: draw(st.integers(1, len(lines)))]
    return "\n".join(lines) + "\n"


@FUZZ
@given(toml_documents())
def test_random_toml(toml):
    with fresh_directory() as directory:
        attempt(Path(directory), toml, VALID_CSV)


CELLS = st.one_of(
    st.floats(allow_nan=True, allow_infinity=True, width=32).map(repr),
    st.floats(-1, 1).map(lambda x: f"{x:.4f}".replace(".", ",")),
    st.integers(-5, 5).map(str),
    st.sampled_from(["", " ", "nan", "inf", "1e400", '"1.5"', '"', "abc", "0x10", "1_0", "١٢"]),
    st.text(max_size=6),
)


@st.composite
def csv_texts(draw):
    """Pamkit CSVs and machine exports with random headers, cells, delimiters and line ends."""
    delimiter = draw(st.sampled_from([",", ";", "\t"]))
    if draw(st.booleans()):
        names = draw(st.lists(st.sampled_from(CHANNELS + ("junk",)), min_size=1, max_size=5))
        header = [delimiter.join(names)]
    else:
        names = draw(st.lists(st.sampled_from(MACHINE_NAMES), min_size=1, max_size=4))
        header = draw(st.lists(st.text(max_size=15), max_size=3)) + [delimiter.join(names)]
        if draw(st.booleans()):
            header.append(delimiter.join(draw(st.sampled_from(UNITS)) for _ in names))
    rows = draw(st.lists(st.lists(CELLS, min_size=len(names) - 1, max_size=len(names) + 1), max_size=12))
    end = draw(st.sampled_from(["\n", "\r\n", "\r"]))
    text = end.join(header + [delimiter.join(row) for row in rows])
    text += draw(st.sampled_from([end, ""]))
    return draw(st.sampled_from(["", "\ufeff"])) + text


@FUZZ
@given(csv_texts(), st.sampled_from(["", 'gas = "supplied"\n', 'kind = "isotonic"\nload_N = 20\n']))
def test_random_csv(csv, test_extra):
    with fresh_directory() as directory:
        toml = VALID_TOML.replace("[test]\n", "[test]\n" + test_extra)
        if "kind" in test_extra:
            toml = toml.replace("initial_length_m = 0.185\n", "")
        attempt(Path(directory), toml, csv)


@st.composite
def mutations(draw, original: bytes):
    """`original` with a few bytes deleted, inserted or replaced."""
    data = bytearray(original)
    for _ in range(draw(st.integers(1, 8))):
        position = draw(st.integers(0, len(data)))
        action = draw(st.sampled_from(["delete", "insert", "replace"]))
        byte = draw(st.integers(0, 255))
        if action == "delete" and position < len(data):
            del data[position]
        elif action == "insert":
            data.insert(position, byte)
        elif position < len(data):
            data[position] = byte
    return bytes(data)


MACHINE_EXPORT = '"Sample I.D.","x"\n"Time","Extension","Load"\n"(s)","(mm)","(N)"\n"0","0","1"\n"1","0.5","2"\n'


@FUZZ
@given(
    st.sampled_from(["toml", "csv", "machine"]).flatmap(
        lambda which: st.tuples(
            st.just(which),
            mutations({"toml": VALID_TOML, "csv": VALID_CSV, "machine": MACHINE_EXPORT}[which].encode()),
        )
    )
)
def test_mutated_valid_files(case):
    which, mutated = case
    with fresh_directory() as directory:
        if which == "toml":
            attempt(Path(directory), mutated, VALID_CSV)
        else:
            attempt(Path(directory), VALID_TOML, mutated)


def test_the_valid_files_load_and_simulate(tmp_path):
    # The fuzzed files start from these: they must work, or every mutation would fail for nothing.
    for csv in (VALID_CSV, MACHINE_EXPORT):
        (tmp_path / "run.toml").write_text(VALID_TOML)
        (tmp_path / "run.csv").write_text(csv)
        frame = pamkit.simulate(tmp_path / "run.toml")
        assert len(frame) == (5 if csv == VALID_CSV else 2)


# Bugs found by these generators or while writing them, kept as plain cases. Before its fix each
# raised something other than a one-line ExperimentError: csv.Error (a bare CR line end),
# ValueError('embedded null byte') naming no file, RuntimeError('Symlink loop'), a message split
# by a line end (in a file name, in a quoted header), TypeError (a list or a number where a name
# or a table belongs).
REGRESSIONS = [
    (VALID_TOML.replace("[test]\n", '[test]\nkind = "isotonic"\nload_N = 20\n'), "pressure_kPa,length_m\r1,0.2\r"),
    (VALID_TOML, "Time;Extension\rs;mm\r0;0\r"),
    (VALID_TOML.replace('data = "run.csv"', 'data = "a\\u0000b"'), VALID_CSV),
    (VALID_TOML.replace('data = "run.csv"', 'data = "run.csv"\nzero = "a\\u0000b"'), VALID_CSV),
    (VALID_TOML.replace('data = "run.csv"', 'data = "loop"'), VALID_CSV),
    (VALID_TOML.replace('data = "run.csv"', 'data = "run\\n.csv"'), VALID_CSV),  # found by test_random_toml
    (VALID_TOML + "[gas]\nprocess = []\n", VALID_CSV),  # found by test_random_toml: TypeError, unhashable list
    ("muscle = 1\n" + TEST, VALID_CSV),  # its neighbour, by reading: TypeError from dict(1)
    (VALID_TOML, '"' + VALID_CSV),  # found by a longer run of test_mutated_valid_files: a header of 6 lines
    (VALID_TOML.replace('data = "run.csv"', 'data = "run.csv"\nzero = "loop"'), VALID_CSV),
]


@pytest.mark.parametrize("toml, csv", REGRESSIONS)
def test_found_cases_fail_with_an_experiment_error(tmp_path, toml, csv):
    (tmp_path / "run.toml").write_text(toml)
    (tmp_path / "run.csv").write_text(csv, newline="")
    (tmp_path / "loop").symlink_to("loop")
    with pytest.raises(ExperimentError) as caught:
        pamkit.load_experiment(tmp_path / "run.toml")
    assert NAMES_A_FILE.match(str(caught.value)) and "\n" not in str(caught.value), str(caught.value)
