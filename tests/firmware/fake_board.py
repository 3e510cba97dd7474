"""A fake logger board on a pseudo-terminal, and the SIGKILL test of `pamkit log` built on it.

The board writes the sketch's wire format (firmware/pamkit_logger/pamkit_frame.h: a banner line,
then 16-byte frames with a CRC-16/CCITT-FALSE) into the master side of a pty, whose slave
`pamkit log` reads like a USB serial port. Frame k has seq k mod 65536 and device time k ms (a
1 kHz board), so that every row of the CSV can be checked against the frame it came from.

The kill test (`kill_runs`) floods the port: the board keeps the pty full, so every read the
reader does takes a whole READ_BYTES (256 frames), as when the USB link delivers a backlog at
once - the worst case for a kill, since the reader is then always formatting or writing rows.
It SIGKILLs `pamkit log` at a random moment, then counts what the reader took from the port:
the bytes the board wrote, less those still queued in the pty (read back through a second
descriptor on the slave that this process holds open and never reads before the kill). The
CSV must then hold, as whole lines, exactly the frames 0..rows-1, and rows must be at least the
frames taken from the port less one read's worth (the documented window, docs/logger.md).

Used by tests/firmware/test_logger_kill.py (a few dozen kills in ctest) and
bench/bench_logger_kill.py (hundreds).
"""

from __future__ import annotations

import binascii
import os
import random
import select
import signal
import struct
import subprocess
import sys
import threading
import time
import tty
from dataclasses import dataclass, field
from pathlib import Path

FRAME_SIZE = 16  # pamkit_frame.h PAMKIT_FRAME_SIZE
BANNER_FORMAT = (  # pamkit_frame.h PAMKIT_BANNER_FORMAT, with the values of a 1 kHz, 1 Mbaud board
    "#pamkit-logger version={version} frame={frame} board=mega2560 rate_hz=1000 period_us=1000"
    " oversample=1 baud=1000000 vref_mV=5000 a0=pressure a1=tmp36"
)


def crc16(data: bytes) -> int:
    """CRC-16/CCITT-FALSE (pamkit_frame.h): binascii's CRC-CCITT with the initial value 0xFFFF."""
    return binascii.crc_hqx(data, 0xFFFF)


def banner(frame_version: int = 1, firmware_version: str = "1.0.0") -> bytes:
    """The board's start-up line, with its CRC."""
    text = BANNER_FORMAT.format(version=firmware_version, frame=frame_version)
    return f"{text} crc={crc16(text.encode()):04X}\r\n".encode()


def counts(k: int) -> tuple[int, int]:
    """The 10-bit conversions frame k carries on A0 and A1 (any values would do; these vary)."""
    return (k * 7) % 1024, 150 + k % 100


def frame(k: int) -> bytes:
    """Frame k of the stream: seq k mod 65536, time k ms (wrapping like micros()), oversample 1."""
    a0, a1 = counts(k)
    body = struct.pack("<HIHHBB", k % 65536, (k * 1000) % 2**32, a0, a1, 1, 0)
    return b"\xa5\x5a" + body + struct.pack("<H", crc16(body))


def frames(count: int) -> bytes:
    return b"".join(frame(k) for k in range(count))


class Board:
    """A pty whose master this object writes from a thread. `path` is the slave for the reader;
    `queue_fd` is a second descriptor on the slave, kept for reading back what was not consumed."""

    def __init__(self, stream: bytes):
        self.master, self.queue_fd = os.openpty()
        tty.setraw(self.queue_fd)  # raw like a serial port: no echo, no line editing
        self.path = os.ttyname(self.queue_fd)
        os.set_blocking(self.master, False)
        self.stream = stream
        self.written = 0
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._write, daemon=True)

    def _write(self) -> None:
        while self.written < len(self.stream) and not self._stop.is_set():
            if not select.select([], [self.master], [], 0.05)[1]:
                continue
            try:
                self.written += os.write(self.master, self.stream[self.written : self.written + 65536])
            except BlockingIOError:
                pass

    def start(self) -> None:
        self._thread.start()

    def stop(self) -> None:
        self._stop.set()
        self._thread.join()

    def drain_queue(self, quiet_s: float = 0.5) -> int:
        """Reads what is still queued for the slave; returns its size. The kernel moves bytes from
        the pty's buffer to the line discipline's in the background, so read until nothing came
        for `quiet_s`: far longer than that work takes, even on a loaded machine."""
        os.set_blocking(self.queue_fd, False)
        remaining = 0
        while select.select([self.queue_fd], [], [], quiet_s)[0]:
            try:
                chunk = os.read(self.queue_fd, 65536)
            except BlockingIOError:
                continue
            if not chunk:
                break
            remaining += len(chunk)
        return remaining

    def close(self) -> None:
        if self._thread.is_alive():
            self.stop()
        os.close(self.master)
        os.close(self.queue_fd)


@dataclass
class CsvCheck:
    rows: int = 0
    cut_lines: list[str] = field(default_factory=list)  # lines that are not a whole row, with where
    unterminated_tail: bytes = b""  # bytes after the last newline
    wrong_rows: list[str] = field(default_factory=list)  # whole rows that are not frame k for row k


UNCALIBRATED_HEADER = b"time_s,temperature_C,pressure_V,temperature_V,boot,seq"


def check_csv(path: Path) -> CsvCheck:
    """Every line of an uncalibrated `pamkit log` CSV whole, and row k the board's frame k."""
    data = path.read_bytes()
    check = CsvCheck()
    body, newline, tail = data.rpartition(b"\n")
    if not newline:
        body, tail = b"", data
    check.unterminated_tail = tail
    lines = body.split(b"\n") if newline else []
    if not lines or lines[0] != UNCALIBRATED_HEADER:
        check.cut_lines.append(f"line 1: header {lines[0] if lines else b''!r}")
        return check
    for number, line in enumerate(lines[1:], start=2):
        k = number - 2
        cells = line.split(b",")
        try:
            time_s, _, pressure_V, _, boot, seq = (float(cell) for cell in cells)
        except ValueError:
            check.cut_lines.append(f"line {number}: {line!r}")
            continue
        # device time k ms, 0 at the first row; A0's counts through the 5 V reference, to the
        # 6 decimals written; boot 0
        expected_V = counts(k)[0] * 5.0 / 1024
        if seq != k % 65536 or abs(time_s - k * 1e-3) > 1e-6 or abs(pressure_V - expected_V) > 1e-6 or boot != 0:
            check.wrong_rows.append(f"line {number}: {line!r} is not frame {k}")
        check.rows += 1
    return check


@dataclass
class KillRun:
    delay_s: float  # from the first row on disk to the kill
    taken: int  # whole frames the reader took from the port
    rows: int  # whole rows in the CSV
    file_bytes: int  # the CSV's length
    check: CsvCheck

    @property
    def lost(self) -> int:
        """Frames taken from the port and not in the file."""
        return self.taken - self.rows


def log_command(port: str, output: Path, *extra: str) -> list[str]:
    return [sys.executable, "-m", "pamkit", "log", "--port", port, "-o", str(output), "--uncalibrated", *extra]


def kill_once(stream: bytes, output: Path, delay_s: float, extra: tuple[str, ...] = ()) -> KillRun:
    """Floods a fresh board with `stream`, starts `pamkit log`, kills it `delay_s` after its first row
    reached the file, and accounts for every frame."""
    board = Board(stream)
    try:
        board.start()
        process = subprocess.Popen(
            log_command(board.path, output, *extra), stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL
        )
        try:
            deadline = time.monotonic() + 30
            while not output.exists() or output.stat().st_size <= len(UNCALIBRATED_HEADER) + 1:
                if time.monotonic() > deadline or process.poll() is not None:
                    raise RuntimeError(f"pamkit log wrote no row within 30 s (exit status {process.poll()})")
                time.sleep(0.002)
            time.sleep(delay_s)
        finally:
            process.send_signal(signal.SIGKILL)
            process.wait()
        board.stop()
        queued = board.drain_queue()
        taken_bytes = board.written - queued - len(banner())
        check = check_csv(output)
        return KillRun(delay_s, taken_bytes // FRAME_SIZE, check.rows, output.stat().st_size, check)
    finally:
        board.close()


def kill_runs(
    count: int, directory: Path, seed: int, max_delay_s: float = 0.3, frames_per_run: int = 1 << 19, progress=None
) -> list[KillRun]:
    """`count` kills at delays drawn uniformly from [0, max_delay_s] after the first row."""
    stream = banner() + frames(frames_per_run)
    rng = random.Random(seed)
    runs = []
    for index in range(count):
        output = directory / f"kill_{index:04d}.csv"
        runs.append(kill_once(stream, output, rng.uniform(0.0, max_delay_s)))
        output.unlink()
        if progress:
            progress(index, runs[-1])
    return runs
