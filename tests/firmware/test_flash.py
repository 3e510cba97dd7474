"""`pamkit flash`: the sketch built in the project's build folder and uploaded with avrdude to a fake
Mega 2560 bootloader on a pty (fake_bootloader.py), and the one-line errors for what stops it. Run by
ctest as python_flash (labels firmware, python); PAMKIT_BUILD_DIR and PAMKIT_AVR_OBJCOPY come from
tests/firmware/CMakeLists.txt, which registers the test only where avrdude and avr-gcc are found."""

from __future__ import annotations

import os
import subprocess
from pathlib import Path

from fake_bootloader import FLASH_BYTES, FakeBootloader

from pamkit.cli import EXIT_BAD_INPUT, main

BUILD_DIR = Path(os.environ["PAMKIT_BUILD_DIR"])
HEX = BUILD_DIR / "firmware" / "pamkit_logger.hex"
NO_PORT = "/dev/pamkit-test-no-such-port"


def flash_image(hex_file: Path, tmp_path: Path) -> bytes:
    """The bytes the .hex puts in flash from address 0, as avr-objcopy (binutils) reads the file."""
    binary = tmp_path / "image.bin"
    subprocess.run(
        [os.environ["PAMKIT_AVR_OBJCOPY"], "-I", "ihex", "-O", "binary", str(hex_file), str(binary)], check=True
    )
    return binary.read_bytes()


def single_error_line(stderr: str) -> str:
    lines = stderr.strip().splitlines()
    assert len(lines) == 1, stderr
    assert lines[0].startswith("pamkit flash: error: "), stderr
    return lines[0]


def test_flash_builds_the_sketch_and_uploads_it(tmp_path, capfd):
    with FakeBootloader() as board:
        assert main(["flash", "--port", board.port, "--build-dir", str(BUILD_DIR)]) == 0
    out, err = capfd.readouterr()
    image = flash_image(HEX, tmp_path)
    # avrdude wrote the whole sketch and read it back equal (its verification pass), ...
    assert f"{len(image)} bytes of flash verified" in err, err
    assert f"flashed {HEX} to {board.port}" in out
    # ... and the bootloader's flash holds the .hex and nothing else: erased (0xFF) above it.
    assert bytes(board.flash[: len(image)]) == image
    assert board.flash[len(image) :] == b"\xff" * (FLASH_BYTES - len(image))


def test_dry_run_builds_and_prints_the_command_without_a_board(capfd):
    assert main(["flash", "--port", NO_PORT, "--build-dir", str(BUILD_DIR), "--dry-run"]) == 0
    out, _ = capfd.readouterr()
    assert f"-P {NO_PORT} -U flash:w:{HEX}:i" in out
    assert "-p atmega2560 -c wiring -b 115200 -D" in out
    assert "dry run: nothing uploaded" in out


def test_another_board_is_refused_and_nothing_is_written(capfd):
    atmega328p = bytes([0x1E, 0x95, 0x0F])  # an Uno on the port
    with FakeBootloader(signature=atmega328p) as board:
        assert main(["flash", "--port", board.port, "--hex", str(HEX)]) == EXIT_BAD_INPUT
    _, err = capfd.readouterr()
    assert "expected signature for ATmega2560 is 1E 98 01" in err, err
    assert err.strip().splitlines()[-1].startswith(f"pamkit flash: error: avrdude could not upload {HEX}")
    assert board.flash == b"\xff" * FLASH_BYTES


def test_missing_port(capfd):
    assert main(["flash", "--port", NO_PORT, "--hex", str(HEX)]) == EXIT_BAD_INPUT
    assert f"no serial port '{NO_PORT}'" in single_error_line(capfd.readouterr().err)
    assert main(["flash", "--port", "", "--hex", str(HEX)]) == EXIT_BAD_INPUT  # "" would be the current folder
    assert "no serial port ''" in single_error_line(capfd.readouterr().err)


def test_missing_avrdude(tmp_path, capfd, monkeypatch):
    monkeypatch.setenv("PATH", str(tmp_path))  # nothing on PATH
    port = tmp_path / "ttyACM0"
    port.touch()
    assert main(["flash", "--port", str(port), "--hex", str(HEX)]) == EXIT_BAD_INPUT
    assert "avrdude is not on PATH (Debian: apt install avrdude)" in single_error_line(capfd.readouterr().err)


def test_not_a_build_folder(tmp_path, capfd):
    assert main(["flash", "--port", NO_PORT, "--build-dir", str(tmp_path), "--dry-run"]) == EXIT_BAD_INPUT
    assert "is not a CMake build folder" in single_error_line(capfd.readouterr().err)


def test_a_sketch_that_does_not_compile(tmp_path, capfd):
    # A build folder whose firmware target compiles a sketch with a syntax error with avr-g++, as a
    # user's edit of pamkit_logger.ino would: the compiler's message shows, then one line.
    source = tmp_path / "project"
    source.mkdir()
    (source / "broken.ino.cpp").write_text("void setup() { this is not C++ }\n")
    (source / "CMakeLists.txt").write_text(
        "cmake_minimum_required(VERSION 3.18)\nproject(broken LANGUAGES NONE)\n"
        'set(PAMKIT_BUILD_FIRMWARE ON CACHE BOOL "")\n'
        "find_program(AVR_GXX avr-g++ REQUIRED)\n"
        "add_custom_target(firmware_pamkit_logger COMMAND ${AVR_GXX} -mmcu=atmega2560 -c "
        "${CMAKE_SOURCE_DIR}/broken.ino.cpp -o broken.o)\n"
    )
    build = tmp_path / "build"
    subprocess.run(["cmake", "-S", str(source), "-B", str(build)], check=True, capture_output=True)
    assert main(["flash", "--port", NO_PORT, "--build-dir", str(build), "--dry-run"]) == EXIT_BAD_INPUT
    out, err = capfd.readouterr()
    assert "broken.ino.cpp:1" in out + err  # the compiler's own message, with file and line
    assert err.strip().splitlines()[-1] == (
        f"pamkit flash: error: the sketch failed to build in {build} (the compiler's messages are above)"
    )
