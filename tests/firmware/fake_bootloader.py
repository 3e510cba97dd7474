"""A fake Arduino Mega 2560 bootloader on a pseudo-terminal, for testing `pamkit flash` without a board.

It answers avrdude's `-c wiring` programmer as the Mega's bootloader (the Arduino core's
bootloaders/stk500v2/stk500boot.c) does, in the STK500v2 protocol of Atmel's application note
AVR068: a message is 0x1B, a sequence number, a 2-byte big-endian body size, the token 0x0E, the
body, and the XOR of all bytes before it; each answer repeats the command byte and the sequence
number. It keeps a 256 KiB flash that starts erased (0xFF), so that avrdude's verification pass
reads back what it wrote, and the test can compare that flash with the .hex it uploaded.

Debian 12's avrdude (7.1) has no `dryrun` programmer (7.2 added it); this stands in for it, and
goes further: avrdude's real wiring code path, serial framing and read-back verification run.
"""

from __future__ import annotations

import os
import select
import threading
import tty

FLASH_BYTES = 256 * 1024  # ATmega2560
MESSAGE_START, TOKEN = 0x1B, 0x0E
STATUS_CMD_OK, STATUS_CMD_FAILED = 0x00, 0xC0
CMD_SIGN_ON, CMD_SET_PARAMETER, CMD_GET_PARAMETER = 0x01, 0x02, 0x03
CMD_LOAD_ADDRESS = 0x06
CMD_ENTER_PROGMODE_ISP, CMD_LEAVE_PROGMODE_ISP, CMD_CHIP_ERASE_ISP = 0x10, 0x11, 0x12
CMD_PROGRAM_FLASH_ISP, CMD_READ_FLASH_ISP = 0x13, 0x14
CMD_READ_FUSE_ISP, CMD_READ_LOCK_ISP, CMD_READ_SIGNATURE_ISP, CMD_READ_OSCCAL_ISP = 0x18, 0x1A, 0x1B, 0x1C
CMD_SPI_MULTI = 0x1D
# stk500boot.c's answers to CMD_GET_PARAMETER: hardware 15, software 2.10, target at 5.0 V.
PARAMETERS = {0x90: 0x0F, 0x91: 0x02, 0x92: 0x0A, 0x94: 50}
# An Arduino Mega's fuses and lock bits as shipped (the core's boards.txt: mega.bootloader.*).
FUSES = {(0x50, 0x00): 0xFF, (0x58, 0x08): 0xD8, (0x50, 0x08): 0xFD, (0x58, 0x00): 0xCF}
ATMEGA2560_SIGNATURE = bytes([0x1E, 0x98, 0x01])


class FakeBootloader:
    """Serves one avrdude session after another on the slave side of a pty (`port`) until stop()."""

    def __init__(self, signature: bytes = ATMEGA2560_SIGNATURE) -> None:
        self.signature = signature
        self.flash = bytearray(b"\xff" * FLASH_BYTES)
        self.commands: list[int] = []  # every command byte received, in order
        self._address = 0  # byte address of the next flash read or write
        self._master, self._slave = os.openpty()
        tty.setraw(self._slave)
        self.port = os.ttyname(self._slave)
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._serve, daemon=True)

    def __enter__(self) -> FakeBootloader:
        self._thread.start()
        return self

    def __exit__(self, *exc) -> None:
        self._stop.set()
        self._thread.join(timeout=5)
        os.close(self._master)
        os.close(self._slave)

    def _serve(self) -> None:
        pending = bytearray()
        while not self._stop.is_set():
            if not select.select([self._master], [], [], 0.05)[0]:
                continue
            try:
                pending += os.read(self._master, 4096)
            except OSError:  # the slave was closed between two avrdude sessions
                continue
            while True:
                start = pending.find(MESSAGE_START)
                if start < 0:
                    pending.clear()
                    break
                del pending[:start]
                if len(pending) < 5:
                    break
                size = pending[2] << 8 | pending[3]
                if len(pending) < 6 + size:
                    break
                message = bytes(pending[: 6 + size])
                del pending[: 6 + size]
                if xor_of(message[:-1]) == message[-1] and message[4] == TOKEN:
                    os.write(self._master, frame(message[1], self._answer(message[5 : 5 + size])))

    def _answer(self, body: bytes) -> bytes:
        command = body[0]
        self.commands.append(command)
        if command == CMD_SIGN_ON:
            return bytes([command, STATUS_CMD_OK, 8]) + b"AVRISP_2"
        if command == CMD_GET_PARAMETER:
            return bytes([command, STATUS_CMD_OK, PARAMETERS.get(body[1], 0)])
        if command in (CMD_SET_PARAMETER, CMD_ENTER_PROGMODE_ISP, CMD_LEAVE_PROGMODE_ISP, CMD_CHIP_ERASE_ISP):
            return bytes([command, STATUS_CMD_OK])
        if command == CMD_LOAD_ADDRESS:  # a word address; bit 31 asks for the extended (> 128 KiB) range
            self._address = 2 * (int.from_bytes(body[1:5], "big") & 0x7FFFFFFF)
            return bytes([command, STATUS_CMD_OK])
        if command == CMD_PROGRAM_FLASH_ISP:
            count = body[1] << 8 | body[2]
            self.flash[self._address : self._address + count] = body[10 : 10 + count]
            self._address += count
            return bytes([command, STATUS_CMD_OK])
        if command == CMD_READ_FLASH_ISP:
            count = body[1] << 8 | body[2]
            data = bytes(self.flash[self._address : self._address + count])
            self._address += count
            return bytes([command, STATUS_CMD_OK]) + data + bytes([STATUS_CMD_OK])
        if command in (CMD_READ_SIGNATURE_ISP, CMD_READ_FUSE_ISP, CMD_READ_LOCK_ISP, CMD_READ_OSCCAL_ISP):
            return bytes([command, STATUS_CMD_OK, self._isp_read(body[2:6]), STATUS_CMD_OK])
        if command == CMD_SPI_MULTI:  # one 4-byte ISP instruction; the value comes back in its last byte
            receive_count, receive_start, instruction = body[2], body[3], body[4:8]
            shifted_out = bytes([0, instruction[0], instruction[1], self._isp_read(instruction)])
            return bytes([command, STATUS_CMD_OK]) + shifted_out[receive_start : receive_start + receive_count] + b"\0"
        return bytes([command, STATUS_CMD_FAILED])

    def _isp_read(self, instruction: bytes) -> int:
        """The byte an ISP read instruction (ATmega2560 data sheet, serial programming set) returns."""
        if instruction[0] == 0x30:  # read signature byte instruction[2]
            return self.signature[instruction[2] % 3]
        return FUSES.get((instruction[0], instruction[1]), 0xFF)


def xor_of(data: bytes) -> int:
    checksum = 0
    for byte in data:
        checksum ^= byte
    return checksum


def frame(sequence: int, body: bytes) -> bytes:
    message = bytes([MESSAGE_START, sequence, len(body) >> 8, len(body) & 0xFF, TOKEN]) + body
    return message + bytes([xor_of(message)])
