"""Input that is not a bounded text file: devices, pipes, over-long lines, huge files
are refused with a message naming the file (and line), without hanging or filling memory; and
the rows numpy reads at once equal those the csv module reads one by one."""

import os
import resource
import subprocess
import sys
import textwrap

import numpy as np
import pytest

from pamkit.io.experiment import load_experiment
from pamkit.io.guards import MAX_FILE_BYTES, MAX_LINE_BYTES, ExperimentError, ExperimentWarning
from pamkit.io.series import read_series

# A child that reads more than this has not refused the input: it fails instead of filling the
# machine's memory (data = "/dev/zero" would grow without bound). Importing numpy, scipy and pamkit
# reserves well under it.
CHILD_ADDRESS_SPACE = 3 << 30
CHILD_TIMEOUT_S = 60  # a refused input takes well under a second; a pipe read would block forever


def load_in_child(path):
    """pamkit.load_experiment(path) in a child process with bounded time and memory: its
    exit status and stderr (a hang raises subprocess.TimeoutExpired, failing the test)."""

    def limit_memory():
        resource.setrlimit(resource.RLIMIT_AS, (CHILD_ADDRESS_SPACE, CHILD_ADDRESS_SPACE))

    code = textwrap.dedent(
        f"""
        import sys
        from pamkit.io.experiment import load_experiment
        from pamkit.io.guards import ExperimentError
        try:
            load_experiment({str(path)!r})
        except ExperimentError as error:
            sys.exit(f"refused: {{error}}")
        """
    )
    return subprocess.run(
        [sys.executable, "-c", code],
        capture_output=True,
        text=True,
        timeout=CHILD_TIMEOUT_S,
        preexec_fn=limit_memory,
        env=os.environ.copy(),
    )


def test_dev_zero_as_data_is_refused_at_once(write_experiment, tmp_path):
    path = write_experiment(toml_test_extra="")
    path.write_text(path.read_text().replace('data = "run.csv"', 'data = "/dev/zero"'))
    done = load_in_child(path)
    assert done.returncode == 1 and "refused: /dev/zero: not a regular file" in done.stderr, done.stderr


def test_a_fifo_as_data_is_refused_without_hanging(write_experiment, tmp_path):
    path = write_experiment()
    (tmp_path / "run.csv").unlink()
    os.mkfifo(tmp_path / "run.csv")  # nobody writes into it: opening it to read would block
    done = load_in_child(path)
    assert done.returncode == 1 and "run.csv: not a regular file (a device or a pipe?)" in done.stderr, done.stderr


def test_a_200_kib_cell_is_named_by_its_line(write_experiment):
    cell = "1" * (200 << 10)
    path = write_experiment(csv_text=f"time_s,elongation_m\n0,0\n1,{cell}\n2,0.001\n")
    with pytest.raises(ExperimentError, match=r"run.csv:3: a line of 200 KiB, more than the 64 KiB a line may be"):
        load_experiment(path)


def test_a_line_at_the_limit_is_read_and_one_byte_more_is_not(tmp_path):
    path = tmp_path / "run.csv"
    # Trailing spaces are allowed around a number (float() strips them): a long but valid line.
    row = "1,0.001" + " " * (MAX_LINE_BYTES - len("1,0.001"))
    path.write_text(f"time_s,elongation_m\n0,0\n{row}\n")
    assert list(read_series(path)["time_s"]) == [0, 1]
    path.write_text(f"time_s,elongation_m\n0,0\n{row} \n")
    with pytest.raises(ExperimentError, match=r"run.csv:3: a line of 64 KiB"):
        read_series(path)


def test_a_huge_data_file_is_refused_with_its_size(write_experiment, tmp_path):
    path = write_experiment()
    with open(tmp_path / "run.csv", "r+b") as handle:  # sparse: no disk space, no time
        handle.truncate(300 << 20)
    assert MAX_FILE_BYTES["data"] == 256 << 20  # the limit the message names
    done = load_in_child(path)
    assert done.returncode == 1, done.stderr
    assert "run.csv: 300.0 MiB, more than the 256.0 MiB a data file may be" in done.stderr


def test_a_huge_experiment_file_is_refused_with_its_size(tmp_path):
    path = tmp_path / "run.toml"
    path.write_text("# padding\n" * 200_000)  # 2 000 000 bytes of comments
    with pytest.raises(ExperimentError, match=r"run.toml: 1.9 MiB, more than the 1.0 MiB an? experiment file may be"):
        load_experiment(path)


def _rows(rng, count):
    """A logger's rows: millisecond stamps, some repeated (merged on reading), five channels."""
    stamps = np.cumsum(rng.choice([0, 1, 1, 1], size=count)) * 1e-3
    return np.column_stack([stamps, rng.uniform(0, 0.05, count), rng.normal(100, 30, (count, 3))])


@pytest.mark.parametrize("delimiter, decimal", [(",", "."), (";", ","), ("\t", ".")])
def test_rows_read_at_once_equal_rows_read_one_by_one(tmp_path, delimiter, decimal):
    # Quoted names make the reader go row by row (numpy's reader does not unquote); the same
    # numbers unquoted are read at once. Both must give the same columns and the same warning.
    names = ["time_s", "elongation_m", "force_N", "pressure_kPa", "temperature_C"]
    table = _rows(np.random.default_rng(14), 2000)
    body = "".join(delimiter.join(f"{v:.9g}".replace(".", decimal) for v in row) + "\n" for row in table)
    plain, quoted = tmp_path / "plain.csv", tmp_path / "quoted.csv"
    plain.write_text(delimiter.join(names) + "\n" + body)
    quoted.write_text(delimiter.join(f'"{n}"' for n in names) + "\n" + body)
    with pytest.warns(ExperimentWarning) as at_once:
        fast = read_series(plain)
    with pytest.warns(ExperimentWarning) as one_by_one:
        slow = read_series(quoted)
    assert [str(w.message).replace("plain", "quoted") for w in at_once] == [str(w.message) for w in one_by_one]
    assert "row(s) repeat the time stamp" in str(at_once[0].message)
    for name in fast:
        # A merged sample is a mean: a running mean row by row, one sum at once; they differ
        # by rounding only (a few units in the last place of values up to ~200).
        np.testing.assert_allclose(fast[name], slow[name], rtol=1e-13, atol=0)
    assert fast["time_s"].size < table.shape[0]  # rows were merged


def test_plain_rows_never_go_row_by_row(tmp_path, monkeypatch):
    # The row-by-row parser is what made 10^6 rows take tens of seconds: a plain file, CRLF or
    # not, must not use it, but for the last line when that has no line end (it may be cut).
    import pamkit.io.csv_reader as csv_reader

    parsed_alone = []
    parse_row = csv_reader._parse_row
    monkeypatch.setattr(csv_reader, "_parse_row", lambda *a: parsed_alone.append(a[1]) or parse_row(*a))
    path = tmp_path / "run.csv"
    rows = "".join(f"{i * 1e-3:.3f},{i * 1e-6:.6f}\n" for i in range(1000))
    for text, alone in ((rows, []), (rows.replace("\n", "\r\n"), []), (rows.rstrip("\n"), [1001])):
        parsed_alone.clear()
        path.write_text("time_s,elongation_m\n" + text, newline="")
        assert read_series(path)["time_s"].size == 1000
        assert parsed_alone == alone  # line numbers parsed one by one
