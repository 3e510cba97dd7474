"""pamkit flash --port PORT [--build-dir DIR | --hex FILE] [--dry-run]"""

from __future__ import annotations

import argparse
import shlex
import shutil
import subprocess
from pathlib import Path

# The Arduino Mega 2560 as the Arduino IDE uploads to it (the core's boards.txt: mega.upload.protocol
# = wiring, mega.upload.speed = 115200): its bootloader speaks STK500v2 ("wiring"); -D skips the
# chip erase, which that bootloader does not implement (it erases each page as it writes it).
AVRDUDE_BOARD = ["-p", "atmega2560", "-c", "wiring", "-b", "115200", "-D"]
FIRMWARE_TARGET = "firmware_pamkit_logger"  # firmware/CMakeLists.txt: the sketch as it ships


class FlashError(ValueError):
    """A port, tool or build that stops the upload; the message says which and what to do."""


def register(subparsers) -> None:
    parser = subparsers.add_parser(
        "flash",
        help="build the logger sketch and upload it to an Arduino Mega 2560",
        description="Builds firmware/pamkit_logger in a configured CMake build folder (or takes a .hex) and "
        "uploads it with avrdude through the Mega's bootloader.",
    )
    parser.add_argument("--port", required=True, help="the board's serial port: /dev/serial/by-id/..., /dev/ttyACM0")
    parser.add_argument(
        "--build-dir",
        default="build",
        metavar="DIR",
        help="the project's CMake build folder, where the sketch is built (default: ./build)",
    )
    parser.add_argument("--hex", metavar="FILE", help="upload this Intel HEX file instead of building the sketch")
    parser.add_argument("--dry-run", action="store_true", help="build and print the avrdude command, but do not upload")
    parser.set_defaults(run=run)


def run(arguments: argparse.Namespace) -> int:
    if not arguments.dry_run and not (arguments.port and Path(arguments.port).exists()):
        raise FlashError(f"no serial port {arguments.port!r}: plug the board in; `pamkit log --list` lists the ports")
    avrdude = shutil.which("avrdude")
    if avrdude is None:
        raise FlashError("avrdude is not on PATH (Debian: apt install avrdude)")
    if arguments.hex:
        hex_file = Path(arguments.hex)
        if not hex_file.is_file():
            raise FlashError(f"{hex_file}: no such .hex file")
    else:
        hex_file = build_sketch(Path(arguments.build_dir))

    command = [avrdude, *AVRDUDE_BOARD, "-P", arguments.port, "-U", f"flash:w:{hex_file}:i"]
    print(shlex.join(command), flush=True)
    if arguments.dry_run:
        print("dry run: nothing uploaded")
        return 0
    if subprocess.run(command, check=False).returncode != 0:
        raise FlashError(
            f"avrdude could not upload {hex_file} to {arguments.port} (its messages are above): is the board "
            "an Arduino Mega 2560 on that port, and is no other program (pamkit log, a serial monitor) using it?"
        )
    print(f"flashed {hex_file} to {arguments.port}")
    return 0


def build_sketch(build_dir: Path) -> Path:
    """Brings the sketch's .hex up to date in the CMake build folder and returns its path."""
    cache = read_cmake_cache(build_dir)
    if cache.get("PAMKIT_BUILD_FIRMWARE", "OFF").upper() not in ("ON", "TRUE", "1", "YES"):
        raise FlashError(
            f"{build_dir} does not build the firmware (PAMKIT_BUILD_FIRMWARE is off): install avr-gcc and the "
            f"Arduino core (Debian: apt install gcc-avr avr-libc arduino-core-avr) and configure again "
            f"(cmake -S . -B {build_dir} -DPAMKIT_BUILD_FIRMWARE=ON)"
        )
    cmake = shutil.which("cmake")
    if cmake is None:
        raise FlashError("cmake is not on PATH (Debian: apt install cmake); or give --hex FILE")
    print(f"building the sketch: cmake --build {build_dir} --target {FIRMWARE_TARGET}", flush=True)
    if subprocess.run([cmake, "--build", str(build_dir), "--target", FIRMWARE_TARGET], check=False).returncode != 0:
        raise FlashError(f"the sketch failed to build in {build_dir} (the compiler's messages are above)")
    hex_file = Path(cache.get("PAMKIT_FIRMWARE_DIR", build_dir / "firmware")) / "pamkit_logger.hex"
    if not hex_file.is_file():
        raise FlashError(f"the build finished but {hex_file} is missing: is {build_dir} a build of pamkit?")
    return hex_file


def read_cmake_cache(build_dir: Path) -> dict[str, str]:
    """The NAME:TYPE=VALUE entries of build_dir/CMakeCache.txt, as NAME -> VALUE."""
    path = build_dir / "CMakeCache.txt"
    if not path.is_file():
        raise FlashError(
            f"{build_dir} is not a CMake build folder (no CMakeCache.txt): configure one from the source tree "
            f"(cmake -S . -B {build_dir} -G Ninja), or give --build-dir DIR or --hex FILE"
        )
    entries = {}
    for line in path.read_text(encoding="utf-8", errors="replace").splitlines():
        if line and not line.startswith(("#", "//")) and "=" in line and ":" in line.split("=", 1)[0]:
            name_and_type, value = line.split("=", 1)
            entries[name_and_type.split(":", 1)[0]] = value
    return entries
