"""`pamkit log` on a simulated board (the real sketch in simavr, through a pty) and `pamkit align`
on synthetic logs with a known offset. Run by ctest as python_firmware (labels firmware, python);
PAMKIT_SIMAVR_HARNESS and PAMKIT_FIRMWARE_ELF come from tests/firmware/CMakeLists.txt."""

from __future__ import annotations

import csv
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest
from fake_board import Board, banner, frames

from pamkit.cli import main
from pamkit.io.experiment import load_experiment

SOURCE_DIR = Path(os.environ.get("PAMKIT_SOURCE_DIR", Path(__file__).resolve().parents[2]))
THESIS = SOURCE_DIR / "data" / "experiments" / "thesis" / "pam1_035kPa_95pct.toml"
HARNESS = os.environ.get("PAMKIT_SIMAVR_HARNESS")
FIRMWARE = os.environ.get("PAMKIT_FIRMWARE_ELF")
# Without avr-gcc or libsimavr, CMake warns that the end-to-end tests are not built, and pytest
# (run with -rs) prints this reason for each skipped test.
needs_simavr = pytest.mark.skipif(not (HARNESS and FIRMWARE), reason="built without avr-gcc or libsimavr")


def write_calibration(path: Path) -> Path:
    # 0.5 V at 0 psi to 4.5 V at 80 psi, as a user would fill in the template
    from pamkit.io.logger import CALIBRATION_TEMPLATE

    assert "measured_V = []" in CALIBRATION_TEMPLATE
    path.write_text(
        CALIBRATION_TEMPLATE.replace("measured_V = []", "measured_V = [0.5, 1.0, 1.5, 2.0, 2.5, 3.0, 3.5, 4.0, 4.5]")
    )
    return path


def start_board(tmp_path: Path, seconds: float, realtime: bool = True) -> tuple[subprocess.Popen, Path, Path]:
    link, summary = tmp_path / "ttyPAMKIT", tmp_path / "summary.txt"
    command = [
        HARNESS,
        "--firmware",
        FIRMWARE,
        "--link",
        str(link),
        "--seconds",
        str(seconds),
        "--summary",
        str(summary),
    ]
    with (tmp_path / "harness.log").open("w") as log:
        board = subprocess.Popen(command + (["--realtime"] if realtime else []), stdout=log, stderr=subprocess.STDOUT)
    deadline = time.monotonic() + 20
    while not link.exists():
        assert time.monotonic() < deadline, "the simulated board did not come up"
        time.sleep(0.01)
    return board, link, summary


def totals(summary: Path) -> dict[str, float]:
    return {k: float(v) for k, v in (line.split("=") for line in summary.read_text().split())}


def log_command(link: Path, output: Path, calibration: Path, *extra: str) -> list[str]:
    return [
        sys.executable,
        "-m",
        "pamkit",
        "log",
        "--port",
        str(link),
        "-o",
        str(output),
        "--calibration",
        str(calibration),
        *extra,
    ]


def read_rows(path: Path) -> list[dict[str, float]]:
    with path.open(newline="") as handle:
        return [{k: float(v) for k, v in row.items()} for row in csv.DictReader(handle)]


@needs_simavr
def test_log_records_every_frame_of_a_simulated_board(tmp_path):
    # Independent of the machine's load: `pamkit log` runs until every frame the board sent is in
    # its file, however long a loaded machine takes, and is then stopped as a user stops it.
    calibration = write_calibration(tmp_path / "cal.toml")
    board, link, summary = start_board(tmp_path, seconds=4.0)
    output = tmp_path / "log.csv"
    process = subprocess.Popen(
        log_command(link, output, calibration),
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        env={**os.environ, "PYTHONUNBUFFERED": "1"},
    )
    deadline = time.monotonic() + 120  # a bound for a reader that stopped, not a time to meet
    while not summary.exists() and time.monotonic() < deadline:  # the board has sent its last frame
        time.sleep(0.05)
    frames = totals(summary)["frames"]
    while (not output.exists() or len(output.read_text().splitlines()) < frames + 1) and time.monotonic() < deadline:
        time.sleep(0.05)
    process.send_signal(signal.SIGINT)
    stdout, stderr = process.communicate(timeout=60)
    assert process.returncode == 0, stderr
    assert board.wait(timeout=60) == 0
    rows = read_rows(output)
    assert frames >= 395  # 4 s at 100 Hz, less the start-up
    assert len(rows) == frames
    assert [row["seq"] for row in rows] == list(range(len(rows)))
    assert f"interrupted; wrote {len(rows)} rows" in stdout
    assert "checksum errors 0" in stdout and "gaps 0 (0 frames lost" in stdout
    assert "board: pamkit logger 1.0.0, 100 Hz, 16x oversampling, 115200 baud" in stderr
    # calibrated: kPa from the fitted line (0.5 V = 0 psi, 0.05 V/psi), TMP36 from (V - 0.5) / 0.01
    for row in rows[:50]:
        assert row["pressure_kPa"] == pytest.approx((row["pressure_V"] - 0.5) / 0.05 * 6.894757293168361, abs=2e-4)
        assert row["temperature_C"] == pytest.approx((row["temperature_V"] - 0.5) / 0.01, abs=1e-3)


@needs_simavr
@pytest.mark.parametrize("how", [signal.SIGINT, signal.SIGKILL], ids=["ctrl-c", "killed"])
def test_log_keeps_what_arrived_when_stopped(tmp_path, how):
    calibration = write_calibration(tmp_path / "cal.toml")
    board, link, _ = start_board(tmp_path, seconds=30.0)
    output = tmp_path / "log.csv"
    process = subprocess.Popen(
        log_command(link, output, calibration), stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True
    )
    deadline = time.monotonic() + 30
    while (
        not output.exists() or len(output.read_text().splitlines()) < 151
    ) and time.monotonic() < deadline:  # header + 150 rows
        time.sleep(0.05)
    process.send_signal(how)
    stdout, _ = process.communicate(timeout=20)
    board.kill()
    board.wait()
    rows = read_rows(output)  # every line complete: rows are flushed whole, after each read
    assert len(rows) >= 150
    assert [row["seq"] for row in rows] == list(range(len(rows)))
    if how == signal.SIGINT:
        assert process.returncode == 0
        assert f"interrupted; wrote {len(rows)} rows" in stdout


# --- pamkit log: refusals and failures, each one line (a fake board on a pty, fake_board.py) ------


def run_log(capsys, *arguments: str) -> tuple[int, str, str]:
    status = main(["log", *arguments])
    captured = capsys.readouterr()
    return status, captured.out, captured.err


def test_log_refuses_to_overwrite_without_force(tmp_path, capsys):
    output = tmp_path / "run.csv"
    output.write_text("an earlier recording\n")
    status, _, err = run_log(capsys, "--port", str(tmp_path / "tty"), "-o", str(output), "--uncalibrated")
    assert status == 2
    assert err == f"pamkit log: error: {output}: exists already; give --force to replace it, or another -o\n"
    assert output.read_text() == "an earlier recording\n"

    board = Board(banner() + frames(50))
    try:
        board.start()
        status, out, err = run_log(
            capsys, "--port", board.path, "-o", str(output), "--uncalibrated", "--force", "--duration", "1"
        )
    finally:
        board.close()
    assert status == 0, err
    assert "wrote 50 rows" in out
    assert [row["seq"] for row in read_rows(output)] == list(range(50))


def test_log_into_a_missing_folder_says_so(tmp_path, capsys):
    output = tmp_path / "no such folder" / "run.csv"
    status, _, err = run_log(capsys, "--port", str(tmp_path / "tty"), "-o", str(output), "--uncalibrated")
    assert status == 2
    assert err == f"pamkit log: error: {output}: the folder {output.parent} does not exist\n"


def test_log_fails_when_the_port_never_opens(tmp_path, capsys):
    output = tmp_path / "run.csv"
    port = tmp_path / "ttyNOPE"
    status, _, err = run_log(capsys, "--port", str(port), "-o", str(output), "--uncalibrated", "--duration", "0.5")
    assert status == 2
    assert err.count("\n") == 1 and "Traceback" not in err
    assert err.startswith(f"pamkit log: error: nothing recorded: the port {port} never opened (")
    assert not output.exists()  # it held the header only: a second attempt needs no --force


@pytest.mark.parametrize(
    "stream,reason",
    [
        (b"", "opened but sent nothing"),
        (b"\x00\x13 line noise at another baud rate \xff" * 20, "sent 720 bytes but no frame"),
    ],
    ids=["silent", "noise"],
)
def test_log_fails_when_nothing_is_recorded(tmp_path, capsys, stream, reason):
    output = tmp_path / "run.csv"
    board = Board(stream)
    try:
        board.start()
        status, _, err = run_log(capsys, "--port", board.path, "-o", str(output), "--uncalibrated", "--duration", "0.5")
    finally:
        board.close()
    assert status == 2
    assert err.count("\n") == 1 and "Traceback" not in err
    assert err.startswith(f"pamkit log: error: nothing recorded: {board.path} {reason}")
    assert not output.exists()


def test_log_stops_with_one_line_on_a_newer_frame_format(tmp_path, capsys):
    output = tmp_path / "run.csv"
    board = Board(banner() + frames(20) + banner(frame_version=2, firmware_version="2.0.0") + frames(20))
    try:
        board.start()
        status, _, err = run_log(capsys, "--port", board.path, "-o", str(output), "--uncalibrated", "--duration", "5")
    finally:
        board.close()
    assert status == 2
    assert "Traceback" not in err
    message = err.splitlines()[-1]
    assert message == (
        f"pamkit log: error: logger on {board.path}: the board sends frame format 2 (firmware 2.0.0), this reader "
        "knows format 1: update pamkit, or flash the sketch that comes with this pamkit "
        f"(the 20 rows before it are in {output})"
    )
    assert [row["seq"] for row in read_rows(output)] == list(range(20))


def test_log_on_a_full_disk_stops_with_one_line_and_leaves_whole_lines(tmp_path):
    # A file size limit (RLIMIT_FSIZE; Python ignores SIGXFSZ, so write() fails with EFBIG) makes
    # the write that crosses it a partial one, as a full disk does.
    import resource

    limit = 10_000  # bytes: a few hundred rows, inside the board's 2000 frames
    output = tmp_path / "run.csv"
    board = Board(banner() + frames(2000))
    try:
        board.start()
        result = subprocess.run(
            log_command(Path(board.path), output, tmp_path / "unused.toml", "--uncalibrated", "--duration", "3"),
            capture_output=True,
            text=True,
            timeout=60,
            preexec_fn=lambda: resource.setrlimit(resource.RLIMIT_FSIZE, (limit, limit)),
        )
    finally:
        board.close()
    assert result.returncode == 2
    data = output.read_bytes()
    assert len(data) <= limit and data.endswith(b"\n")  # cut back to its last whole line
    rows = read_rows(output)
    assert 0 < len(rows) and [row["seq"] for row in rows] == list(range(len(rows)))
    assert result.stderr.splitlines()[-1] == (
        f"pamkit log: error: logger: writing {output} failed: File too large; the file ends at its last whole "
        f"line (the {len(rows)} rows before it are in {output})"
    )


# --- align --------------------------------------------------------------------------------------


def synthetic_logs(tmp_path: Path, offset_s: float, seed: int) -> tuple[Path, Path]:
    """A thesis bench test (PAM 1, 35 kPa, 10 cycles at 2.5 mm/s) simulated by pamkit, recorded by
    a tensile machine at 10 Hz (mm, N) and by the logger at 100 Hz, whose clock reads
    machine time + offset_s. Both with noise; the logger's pressure quantised like the ADC."""
    from pamkit.simulation import simulate_experiment

    truth = simulate_experiment(load_experiment(THESIS))
    rng = np.random.default_rng(seed)
    t = truth["time_s"]
    machine = tmp_path / "machine.csv"
    with machine.open("w", newline="") as handle:
        writer = csv.writer(handle)
        writer.writerow(["Instron export"])  # a preamble line, as Bluehill writes
        writer.writerow(["Time", "Extension", "Load"])
        writer.writerow(["(s)", "(mm)", "(N)"])
        for i in range(t.size):
            writer.writerow(
                [
                    f"{t[i]:.2f}",
                    f"{truth['elongation_m'][i] * 1e3:.4f}",
                    f"{truth['force_N'][i] + rng.normal(0, 0.2):.3f}",
                ]
            )
    # the logger runs from 20 s before the machine to 10 s after (cut to what overlaps for a
    # negative offset), 100 Hz, on its own clock
    machine_time = np.arange(-20.0, t[-1] + 10.0, 0.01)
    step_kPa = 5.0 / 1024 / 0.05 * 6.894757293168361 / 16  # one count of 16x oversampling
    # the logger writes kPa and °C: the truth's Pa and K, as it reads them
    pressure = np.interp(machine_time, t, truth["gauge_pressure_Pa"] / 1e3) + rng.normal(0, 0.3, machine_time.size)
    pressure = np.round(pressure / step_kPa) * step_kPa
    temperature = np.interp(machine_time, t, truth["temperature_K"] - 273.15) + rng.normal(0, 0.05, machine_time.size)
    logger_time = machine_time + offset_s
    keep = logger_time >= 0
    logger = tmp_path / "logger.csv"
    with logger.open("w", newline="") as handle:
        writer = csv.writer(handle)
        writer.writerow(["time_s", "pressure_kPa", "temperature_C", "pressure_V", "temperature_V", "boot", "seq"])
        for k, (tl, p, c) in enumerate(zip(logger_time[keep], pressure[keep], temperature[keep])):
            writer.writerow([f"{tl - logger_time[keep][0]:.6f}", f"{p:.4f}", f"{c:.3f}", "0", "0", "0", k % 65536])
    # the logger's file starts at its first row: shift the true offset accordingly
    return logger, machine, float(offset_s - logger_time[keep][0])


@pytest.mark.parametrize("offset_s,seed", [(27.345, 1), (4.71, 2)])
def test_align_recovers_a_known_offset_within_one_sample(tmp_path, capsys, offset_s, seed):
    logger, machine, true_offset = synthetic_logs(tmp_path, offset_s, seed)
    output = tmp_path / "aligned.toml"
    assert main(["align", str(logger), str(machine), "-o", str(output), "--muscle", str(THESIS)]) == 0
    printed = capsys.readouterr().out
    found = float(printed.split("logger time = machine time ")[1].split(" s")[0].replace(" ", ""))
    assert abs(found - true_offset) <= 0.01, printed  # one logger sample (100 Hz)
    assert "r = 0.9" in printed

    experiment = load_experiment(output)
    assert set(experiment.measured()) == {"force_N", "gauge_pressure_Pa", "temperature_K"}
    # the thesis test was inflated to 35 kPa; the logger's second before the first stretch says so
    # (100 samples with 0.3 kPa noise: the mean is good to 0.1 kPa)
    assert experiment.inflation_gauge_pressure_Pa == pytest.approx(35e3, abs=100.0)
    assert experiment.gas_params.ambient_temperature_K == pytest.approx(22.85 + 273.15, abs=0.05)
    assert experiment.elongation_m[0] == 0.0
    assert "before the first stretch" in output.read_text()


def test_align_reads_a_zwick_testxpert_export(tmp_path, capsys):
    # The same machine record as testXpert writes it on a German Windows: a metadata block,
    # ';', decimal commas, the load in kN, Windows-1252; the offset found is the same.
    logger, machine, true_offset = synthetic_logs(tmp_path, 4.71, 2)
    rows = list(csv.reader(machine.read_text().splitlines()[3:]))
    zwick = tmp_path / "zwick.csv"
    lines = ["Prüfer;M. Muster", "Probe;PAM1", "", "Prüfzeit;Standardweg;Standardkraft", "s;mm;kN"]
    lines += [f"{t};{e};{float(f) / 1e3:.6f}".replace(".", ",") for t, e, f in rows]
    zwick.write_bytes(("\r\n".join(lines) + "\r\n").encode("cp1252"))
    output = tmp_path / "aligned.toml"
    assert main(["align", str(logger), str(zwick), "-o", str(output), "--muscle", str(THESIS)]) == 0
    printed = capsys.readouterr().out
    found = float(printed.split("logger time = machine time ")[1].split(" s")[0].replace(" ", ""))
    assert abs(found - true_offset) <= 0.01, printed  # one logger sample (100 Hz)
    from pamkit.io.logger import read_machine_csv

    # kN converted: the two records agree to the 1e-6 kN (1e-3 N) testXpert's copy was printed to.
    both = read_machine_csv(zwick), read_machine_csv(machine)
    np.testing.assert_allclose(both[0]["force_N"], both[1]["force_N"], rtol=0, atol=0.5e-3 + 1e-12)
    np.testing.assert_array_equal(both[0]["extension_m"], both[1]["extension_m"])


def test_a_cut_last_line_is_dropped_with_a_warning_not_read_as_a_row(tmp_path, capsys):
    from pamkit.io.logger import LoggerWarning, read_logger_csv

    logger, machine, _ = synthetic_logs(tmp_path, 4.71, 2)
    whole = read_logger_csv(logger)
    text = logger.read_text()
    last = text.splitlines()[-1].split(",")
    # the next row as a kill could leave it: its seq cut after the first digit, every cell a number
    cut = ",".join([f"{float(last[0]) + 0.01:.6f}", *last[1:6], str(int(last[6]) + 1)[:1]])
    logger.write_text(text + cut)
    line = text.count("\n") + 1
    with pytest.warns(LoggerWarning, match=rf"logger.csv:{line}: the last line has no line end") as caught:
        data = read_logger_csv(logger)
    assert repr(cut[:60]) in str(caught[0].message)
    for name, values in whole.items():
        np.testing.assert_array_equal(data[name], values)

    output = tmp_path / "aligned.toml"
    assert main(["align", str(logger), str(machine), "-o", str(output), "--muscle", str(THESIS)]) == 0
    printed = capsys.readouterr().out
    assert f"warning: {logger}:{line}: the last line has no line end" in printed


def test_aligned_experiment_is_accepted_by_simulate(tmp_path):
    logger, machine, _ = synthetic_logs(tmp_path, 12.5, 3)
    output = tmp_path / "aligned.toml"
    assert (
        main(
            [
                "align",
                str(logger),
                str(machine),
                "-o",
                str(output),
                "--muscle",
                str(THESIS),
                "--initial-length-m",
                "0.185",
            ]
        )
        == 0
    )
    predicted = tmp_path / "predicted.csv"
    assert main(["simulate", str(output), "-o", str(predicted)]) == 0
    rows = read_rows(predicted)
    assert len(rows) > 2000 and max(row["force_N"] for row in rows) > 50


def test_align_and_calibration_errors_name_the_problem(tmp_path, capsys):
    from pamkit.io.logger import CALIBRATION_TEMPLATE, LoggerError, load_calibration, read_machine_csv

    template = tmp_path / "cal.toml"
    template.write_text(CALIBRATION_TEMPLATE)
    with pytest.raises(LoggerError, match=r"cal.toml: \[pressure\] measured_V is empty"):
        load_calibration(template)
    template.write_text(CALIBRATION_TEMPLATE.replace("measured_V = []", "measured_V = [1, 2]"))
    with pytest.raises(LoggerError, match="9 applied pressures but 2 measured voltages"):
        load_calibration(template)
    machine = tmp_path / "machine.csv"
    machine.write_text("Time (s),Extension (furlong),Load (N)\n0,0,0\n1,1,1\n")
    with pytest.raises(LoggerError, match=r"machine.csv:1: column 2 'Extension \(furlong\)': unknown unit 'furlong'"):
        read_machine_csv(machine)
    machine.write_text("Time (s),Extension (mm),Load (kN)\n0,0,0\n1,abc,1\n")
    with pytest.raises(LoggerError, match=r"machine.csv:3: column 2 \(extension\) = 'abc' is not a number"):
        read_machine_csv(machine)
    assert (
        main(
            [
                "log",
                "--port",
                "/dev/nonexistent",
                "-o",
                str(tmp_path / "x.csv"),
                "--calibration",
                str(tmp_path / "missing.toml"),
            ]
        )
        == 2
    )
    assert "no such calibration file" in capsys.readouterr().err
