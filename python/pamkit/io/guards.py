"""What pamkit reads is checked before it is parsed: a regular file of a bounded size, lines of a
bounded length, UTF-8 text, valid TOML; and the errors that name where a file is wrong.

Every module that reads a file a person hands over (an experiment, its data, a machine's
export, a sweep spec) reads it through here, so that no reader can be pointed at a device or a
runaway file and grow without bound.
"""

from __future__ import annotations

import math
import os
import warnings
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

import numpy as np

try:
    import tomllib
except ModuleNotFoundError:  # Python < 3.11
    import tomli as tomllib


class ExperimentError(ValueError):
    """An experiment file or its data cannot be used; the message says where."""


class ExperimentWarning(UserWarning):
    """Data that can be used after a stated repair (a cut last line dropped, repeated time stamps
    merged, rows missing a value left out); the message says where and what was done."""


@contextmanager
def experiment_warnings_kept(kept: list[str]) -> Iterator[None]:
    """Appends to `kept` the message of every ExperimentWarning raised inside, then raises each
    warning again as it was raised, also when what is inside fails (a report keeps what reading
    the data repaired; a person still sees it)."""
    raised: list[warnings.WarningMessage] = []
    try:
        with warnings.catch_warnings(record=True) as raised:
            warnings.simplefilter("always")
            yield
    finally:
        for warning in raised:
            if issubclass(warning.category, ExperimentWarning):
                kept.append(str(warning.message))
            warnings.warn_explicit(warning.message, warning.category, warning.filename, warning.lineno)


# What a file pamkit reads may hold: a path to a device (data = "/dev/zero") would otherwise be
# read until memory runs out. A measured row of five channels is about 45 bytes: 10^6 rows, a
# 17-minute test at 1 kHz, are 45 MB, and 256 MiB holds about 6 M rows (1.6 h at 1 kHz). A plain
# file is read in blocks into less memory than its size (its numbers: 8 bytes for ~11 of text);
# one read row by row (quoted cells, blank lines, an error to name) peaks at about 4 bytes of
# memory per byte of file (its bytes, its text, the rows), so the largest file allowed still
# reads within about 1 GB. An experiment TOML or a sweep spec is a few kilobytes. No line pamkit
# writes or reads reaches 1 KiB (a header of every channel is 56 bytes); 64 KiB is far beyond
# any real one and below the csv module's 128 KiB cell limit, so an over-long line is named,
# not a csv error.
MAX_FILE_BYTES = {"experiment": 1 << 20, "sweep spec": 1 << 20, "data": 256 << 20}
MAX_LINE_BYTES = 64 << 10


def fail(path: Path, message: str) -> ExperimentError:
    """The error for `message` about the file `path`."""
    return ExperimentError(f"{path}: {message}")


def number(path: Path, where: str, value) -> float:
    """A TOML value that must be a finite number, as a float; `where` names it ("[test] load_N").

    Raises:
        ExperimentError: naming the file, `where` and the value.
    """
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise fail(path, f"{where} = {value!r} must be a number")
    if not math.isfinite(value):
        raise fail(path, f"{where} = {value!r} must be finite")
    return float(value)


def check_keys(path: Path, section: str, table, known) -> None:
    """Raises an ExperimentError naming the file, the first key of [section] `table` not in
    `known`, and the keys known (in `known`'s order)."""
    for key in table:
        if key not in known:
            raise fail(path, f"unknown key [{section}] {key} (known: {', '.join(known)})")


def read_toml(path: Path, what: str) -> dict:
    """The document of a TOML file, read through :func:`read_text` (MAX_FILE_BYTES[what]).

    Raises:
        ExperimentError: for a file that cannot be read (see read_text) or is not valid TOML.
    """
    try:
        return tomllib.loads(read_text(path, what))
    except tomllib.TOMLDecodeError as error:
        raise fail(path, f"not valid TOML: {error}") from None


def named_file(path: Path, where: str, name) -> Path:
    """The absolute path of a file that the TOML file `path` names at `where` ("[test] data"),
    relative to it.

    Raises:
        ExperimentError: for a name that is not a string or holds a control character: a NUL no
            file system takes (os calls raise a bare ValueError), a line end that would split
            every message naming the file.
    """
    if not isinstance(name, str):
        raise fail(path, f"{where} = {name!r} must be a file name")
    if any(ord(character) < 0x20 or ord(character) == 0x7F for character in name):
        raise fail(path, f"{where} = {name!r} holds a control character: not a file name")
    try:
        return (path.parent / name).resolve()
    except (RuntimeError, OSError):
        # A symbolic link loop (RuntimeError before Python 3.13, OSError since): keep the path
        # as written, and let reading it say what it is.
        return Path(os.path.abspath(path.parent / name))


def read_text(path: Path, what: str, decode=None) -> str:
    """A file's text (UTF-8, a spreadsheet's byte-order mark dropped, or as `decode(raw)` says),
    or an ExperimentError that says why it cannot be read: missing, a folder, not a regular
    file, larger than MAX_FILE_BYTES[what] (its size named), a line over MAX_LINE_BYTES (its
    number named), not UTF-8 (with the line)."""
    limit = checked_size(path, what)
    try:
        with path.open("rb") as handle:
            raw = handle.read(limit + 1)  # a file that grows while read (or lies about its size) stops here
    except OSError as error:
        raise ExperimentError(f"{path}: cannot be read: {error.strerror}") from None
    if len(raw) > limit:
        raise ExperimentError(f"{path}: more than the {size_text(limit)} a {what} file may be")
    check_line_lengths(path, raw)
    if decode is not None:
        return decode(raw)
    try:
        return raw.decode("utf-8-sig")
    except UnicodeDecodeError as error:
        line = raw[: error.start].count(b"\n") + 1
        raise ExperimentError(f"{path}:{line}: byte 0x{raw[error.start]:02x} is not UTF-8 text") from None


def checked_size(path: Path, what: str) -> int:
    """MAX_FILE_BYTES[what], once `path` is a regular file no larger; else an ExperimentError that
    says what it is: missing, a link to nothing, a folder, a device or pipe, too large (its size)."""
    if path.is_symlink() and not path.exists():
        raise ExperimentError(f"{path}: a symbolic link to nothing (or to itself): give the {what} file itself")
    if not path.exists():
        raise ExperimentError(f"{path}: no such {what} file")
    if path.is_dir():
        raise ExperimentError(f"{path}: is a folder; give the {what} file itself")
    if not path.is_file():
        raise ExperimentError(f"{path}: not a regular file (a device or a pipe?): give the {what} file itself")
    limit = MAX_FILE_BYTES[what]
    try:
        size = path.stat().st_size
    except OSError as error:
        raise ExperimentError(f"{path}: cannot be read: {error.strerror}") from None
    if size > limit:
        raise ExperimentError(f"{path}: {size_text(size)}, more than the {size_text(limit)} a {what} file may be")
    return limit


def size_text(count: int) -> str:
    """A byte count as a message gives it: MiB from one MiB on, else KiB."""
    return f"{count / (1 << 20):.1f} MiB" if count >= 1 << 20 else f"{count / 1024:.0f} KiB"


def has_long_line(raw: bytes) -> bool:
    """Whether a line of `raw` (whole lines) is longer than MAX_LINE_BYTES."""
    if len(raw) <= MAX_LINE_BYTES:
        return False
    codes = np.frombuffer(raw, dtype=np.uint8)
    ends = np.concatenate([[-1], np.flatnonzero((codes == ord("\n")) | (codes == ord("\r"))), [len(raw)]])
    return bool((np.diff(ends) - 1 > MAX_LINE_BYTES).any())


def check_line_lengths(path: Path, raw: bytes) -> None:
    """Raises ExperimentError naming the first line longer than MAX_LINE_BYTES (line ends: LF,
    CR LF or a bare CR), scanning 16 MiB at a time so the scan's arrays stay small."""
    if len(raw) <= MAX_LINE_BYTES:
        return
    chunk = 16 << 20
    ends = [np.array([-1])]
    for start in range(0, len(raw), chunk):
        block = np.frombuffer(raw, dtype=np.uint8, count=min(chunk, len(raw) - start), offset=start)
        ends.append(np.flatnonzero((block == ord("\n")) | (block == ord("\r"))) + start)
    ends.append(np.array([len(raw)]))
    bounds = np.concatenate(ends)
    long_lines = np.flatnonzero(np.diff(bounds) - 1 > MAX_LINE_BYTES)
    if long_lines.size:
        first = int(long_lines[0])
        begins = int(bounds[first]) + 1
        length = int(bounds[first + 1]) - begins
        line = raw.count(b"\n", 0, begins) + 1
        raise ExperimentError(
            f"{path}:{line}: a line of {size_text(length)}, more than the "
            f"{size_text(MAX_LINE_BYTES)} a line may be (is this the right file?)"
        )


def ends_unterminated(path: Path) -> bool:
    """Whether the file's last byte is not a line end."""
    with path.open("rb") as handle:
        handle.seek(0, 2)
        if handle.tell() == 0:
            return False
        handle.seek(-1, 2)
        return handle.read(1) not in (b"\n", b"\r")
