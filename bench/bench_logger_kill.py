"""SIGKILL `pamkit log` many times while a fake 1 kHz board floods its port, and count what each kill
cost (the test tests/firmware/test_logger_kill.py does 30 of these in ctest; this does hundreds).

Each kill: a fresh pty board (tests/firmware/fake_board.py) keeps the port full, `pamkit log
--uncalibrated` reads it into a CSV, and is SIGKILLed at a random moment 0-0.3 s after its first
row reached the file. Then: every line of the file must be whole and row k must be the board's
frame k; the frames the reader took from the port (what the board wrote less what is still
queued in the pty) less the rows in the file is what the kill lost, which must not exceed one
read (READ_BYTES / 16 = 256 frames).

Usage:
    PYTHONPATH=build/python python bench/bench_logger_kill.py [--kills 200] [--seed 14]
Exits 1 if any kill cut a line (other than at a page boundary, see docs/logger.md), put a wrong
row in the file or lost more than one read.
"""

from __future__ import annotations

import argparse
import os
import statistics
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests" / "firmware"))

from fake_board import FRAME_SIZE, kill_runs  # noqa: E402

from pamkit._core.logger import READ_BYTES  # noqa: E402


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--kills", type=int, default=200, help="how many times to kill pamkit log (default: 200)")
    parser.add_argument("--seed", type=int, default=14, help="seed of the kill moments (default: 14)")
    arguments = parser.parse_args()
    window = READ_BYTES // FRAME_SIZE
    page = os.sysconf("SC_PAGE_SIZE")

    def progress(index, run):
        if (index + 1) % 20 == 0:
            print(f"  {index + 1} kills", file=sys.stderr, flush=True)

    start = time.monotonic()
    with tempfile.TemporaryDirectory() as directory:
        runs = kill_runs(arguments.kills, Path(directory), arguments.seed, progress=progress)
    wall = time.monotonic() - start

    cut = [run for run in runs if run.check.cut_lines]
    wrong = [run for run in runs if run.check.wrong_rows]
    tails = [run for run in runs if run.check.unterminated_tail]
    tails_off_page = [run for run in tails if run.file_bytes % page != 0]
    beyond = [run for run in runs if not 0 <= run.lost <= window]
    lost = [run.lost for run in runs]
    rows = [run.rows for run in runs]
    print(f"{len(runs)} SIGKILLs of pamkit log under a flood of 16-byte frames ({wall:.0f} s)")
    print(f"rows on disk per run: median {statistics.median(rows):.0f}, {min(rows)} to {max(rows)}")
    print(f"whole-line check: {len(cut)} runs with a cut line inside the file, {len(wrong)} with a wrong row")
    print(
        f"unterminated last line: {len(tails)} runs ({len(tails) - len(tails_off_page)} at a page boundary, "
        f"{len(tails_off_page)} elsewhere)"
    )
    print(
        f"frames taken from the port and not in the file: median {statistics.median(lost):.0f}, max {max(lost)} "
        f"(window: one read, {window}); 0 in {sum(x == 0 for x in lost)} runs, {window} in "
        f"{sum(x == window for x in lost)}, between in {sum(0 < x < window for x in lost)}, beyond in {len(beyond)}"
    )
    return 1 if cut or wrong or tails_off_page or beyond else 0


if __name__ == "__main__":
    sys.exit(main())
