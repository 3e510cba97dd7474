"""`pamkit log` SIGKILLed at random moments while a fake 1 kHz board floods its port (fake_board.py):
no line is ever cut, and the file holds every frame the reader took from the port but those of
its last read (docs/logger.md, "What a kill or a power cut can lose"). ctest runs 30 kills
(PAMKIT_LOGGER_KILLS), alone (label timing: the flood that puts kills inside the window needs the
machine's cores); bench/bench_logger_kill.py runs hundreds and prints the distribution."""

from __future__ import annotations

import os

from fake_board import FRAME_SIZE, kill_runs

from pamkit._core.logger import READ_BYTES

KILLS = int(os.environ.get("PAMKIT_LOGGER_KILLS", "30"))
PAGE_BYTES = os.sysconf("SC_PAGE_SIZE")


def test_sigkill_under_burst_load_cuts_no_line_and_loses_at_most_one_read(tmp_path):
    window = READ_BYTES // FRAME_SIZE  # 256 frames: one read of the port
    runs = kill_runs(KILLS, tmp_path, seed=14)
    for index, run in enumerate(runs):
        where = f"kill {index} ({run.delay_s:.3f} s after the first row)"
        assert run.check.rows > 0, where
        assert not run.check.cut_lines, where
        assert not run.check.wrong_rows, where
        # Linux checks for a fatal signal before copying each page of a write(), so SIGKILL can cut
        # a write short at a page boundary: the only way the file may end inside a line, which
        # the readers drop (test_logger_cli.py). Anywhere else the tail is a stdio-style cut.
        if run.check.unterminated_tail:
            assert run.file_bytes % PAGE_BYTES == 0, f"{where}: cut line {run.check.unterminated_tail!r}"
        assert 0 <= run.lost <= window, f"{where}: {run.lost} frames taken from the port are not in the file"
    # The kills reached the window: some landed after a read and before its rows were written.
    assert any(run.lost > 0 for run in runs)
