"""Large experiment files: a plain CSV is read block by block into memory smaller than
the file, and the blocks join into exactly what one reading of the whole file gives."""

import tracemalloc

import numpy as np
import pytest

import pamkit.io.csv_reader as csv_reader
from pamkit.io.columns import si_name
from pamkit.io.guards import ExperimentWarning
from pamkit.io.series import read_series

NAMES = ["time_s", "elongation_m", "force_N", "pressure_kPa", "temperature_C"]


def _table(rng, count):
    """A logger's rows: millisecond stamps, some repeated (merged on reading), five channels."""
    stamps = np.cumsum(rng.choice([0, 1, 1, 1], size=count)) * 1e-3
    return np.column_stack([stamps, rng.uniform(0, 0.05, count), rng.normal(100, 30, (count, 3))])


def _text(table, delimiter=",", decimal=".", line_end="\n"):
    rows = (delimiter.join(f"{v:.10g}".replace(".", decimal) for v in row) for row in table)
    return delimiter.join(NAMES) + line_end + "".join(row + line_end for row in rows)


def test_a_plain_file_reads_in_less_memory_than_its_size(tmp_path, monkeypatch):
    # 200 000 rows of five channels in 10-digit text (about 11 MB, ~57 bytes a row) are 8 MB of
    # numbers (40 bytes a row): read block by block, the peak is the numbers and what one block
    # takes (its bytes, its text, that text with decimal points, numpy's rows: a few copies of
    # it, 16 is generous). A reader holding the file's bytes and text at once would take twice
    # its size before any number.
    block = 1 << 18
    monkeypatch.setattr(csv_reader, "READ_BLOCK_BYTES", block)
    rng = np.random.default_rng(12)
    count = 200_000
    table = np.column_stack([np.arange(count) * 1e-3, rng.uniform(0, 0.05, count), rng.normal(100, 30, (count, 3))])
    path = tmp_path / "big.csv"
    path.write_text(_text(table))
    size = path.stat().st_size
    tracemalloc.start()
    try:
        columns = read_series(path)
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert columns["time_s"].size == count
    numbers = count * len(NAMES) * 8
    # 12.2 MB: about the file's size, where the target allows three times it (docs/benchmarks.md).
    assert peak < numbers + 16 * block, f"peak {peak / 1e6:.1f} MB reading a {size / 1e6:.1f} MB file"


@pytest.mark.parametrize(
    "delimiter, decimal, line_end, bom, tail",
    [
        (",", ".", "\n", "", ()),
        (";", ",", "\r\n", "\ufeff", ()),
        ("\t", ".", "\n", "", (9.999, 0, 1, 2, 3)),  # a whole last row without its line end: kept
        (";", ",", "\r\n", "", (9.999, 0.01)),  # a recording cut mid-row: dropped with a warning
    ],
)
def test_small_blocks_read_as_the_whole_file_does(tmp_path, monkeypatch, delimiter, decimal, line_end, bom, tail):
    # Blocks of 100 bytes end mid-row and split runs of repeated stamps; with the BOM, European
    # separators, CRLF, and a last line without its line end. Quoted names send the same rows
    # to the row-by-row reader: the reference.
    table = _table(np.random.default_rng(3), 3000)
    text = _text(table, delimiter, decimal, line_end) + delimiter.join(str(v).replace(".", decimal) for v in tail)
    plain, quoted = tmp_path / "plain.csv", tmp_path / "quoted.csv"
    plain.write_text(bom + text, newline="")
    quoted.write_text(bom + delimiter.join(f'"{n}"' for n in NAMES) + text[text.index(line_end) :], newline="")
    with pytest.warns(ExperimentWarning) as whole:
        reference = read_series(quoted)
    monkeypatch.setattr(csv_reader, "READ_BLOCK_BYTES", 100)
    with pytest.warns(ExperimentWarning) as in_blocks:
        blocks = read_series(plain)
    assert [str(w.message).replace("plain", "quoted") for w in in_blocks] == [str(w.message) for w in whole]
    assert len(in_blocks) == (2 if len(tail) == 2 else 1)  # the merged stamps, and the cut line
    assert list(blocks) == [si_name(name) for name in NAMES]
    for name in blocks:
        # Merged samples are means: a running mean row by row, one sum in blocks (rounding only).
        np.testing.assert_allclose(blocks[name], reference[name], rtol=1e-13, atol=0)
    assert blocks["time_s"][-1] == (9.999 if len(tail) == 5 else table[-1, 0])
