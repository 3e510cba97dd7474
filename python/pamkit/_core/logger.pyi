"""
The Arduino Mega logger's host side (firmware/pamkit_logger).
"""
from __future__ import annotations
import collections.abc
import numpy
import numpy.typing
import typing
__all__: list[str] = ['ADC_FULL_SCALE', 'FIRMWARE_VERSION', 'FRAME_SIZE', 'FRAME_VERSION', 'LoggerCalibration', 'READ_BYTES', 'Reader', 'fit_pressure', 'list_ports']
class LoggerCalibration:
    """
    Counts to volts (ADC reference), volts to gauge kPa (61CP fit) and to degC (TMP36).
    """
    @staticmethod
    def fields() -> dict:
        """
        Field names mapped to their unit, allowed range and meaning.
        """
    def __init__(self, **kwargs) -> None:
        """
        Keyword construction; fields not given keep their documented defaults.
        """
    def __repr__(self) -> str:
        ...
    def pressure_kPa(self, volts: typing.Annotated[numpy.typing.ArrayLike, numpy.float64]) -> typing.Any:
        """
        gauge pressure [kPa] for the transducer's V; float or array
        """
    def temperature_C(self, volts: typing.Annotated[numpy.typing.ArrayLike, numpy.float64]) -> typing.Any:
        """
        TMP36 temperature [degC] for its V; float or array
        """
    def to_dict(self) -> dict:
        ...
    def validate(self) -> None:
        """
        Raises ValueError naming the first field out of range.
        """
    def volts(self, mean_counts: typing.Annotated[numpy.typing.ArrayLike, numpy.float64]) -> typing.Any:
        """
        V at the pin for a mean conversion [counts] (a frame's sum of conversions / oversample); float or array
        """
    @property
    def adc_reference_V(self) -> float:
        """
        ADC reference voltage (AVCC of the Mega) [V], allowed [1.000000, 5.500000]
        """
    @adc_reference_V.setter
    def adc_reference_V(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def pressure_kPa_per_V(self) -> float:
        """
        pressure transducer slope (appendix B linear fit) [kPa/V], allowed [-100000.000000, 100000.000000]
        """
    @pressure_kPa_per_V.setter
    def pressure_kPa_per_V(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def pressure_offset_kPa(self) -> float:
        """
        pressure transducer gauge pressure at 0 V [kPa], allowed [-100000.000000, 100000.000000]
        """
    @pressure_offset_kPa.setter
    def pressure_offset_kPa(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def tmp36_V_per_C(self) -> float:
        """
        TMP36 scale factor [V/degC], allowed [0.000100, 1.000000]
        """
    @tmp36_V_per_C.setter
    def tmp36_V_per_C(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def tmp36_offset_V(self) -> float:
        """
        TMP36 output at 0 degC [V], allowed [0.000000, 2.000000]
        """
    @tmp36_offset_V.setter
    def tmp36_offset_V(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
class Reader:
    """
    Reads the logger on `port` into the CSV `output` (time_s, [pressure_kPa,] temperature_C, pressure_V, temperature_V, boot, seq), whole lines written after every read; fsync_interval_s [s]: fsync at most this often (0: every read, inf: never); an existing output is refused (ValueError) unless replace_existing.
    """
    def __enter__(self) -> Reader:
        ...
    def __exit__(self, *args) -> None:
        ...
    def __init__(self, port: str, output: str, calibration: LoggerCalibration, pressure_calibrated: bool = True, baud: typing.SupportsInt | typing.SupportsIndex = 115200, assert_dtr: bool = True, banner_timeout_s: typing.SupportsFloat | typing.SupportsIndex = 3.0, reconnect_interval_s: typing.SupportsFloat | typing.SupportsIndex = 0.25, fsync_interval_s: typing.SupportsFloat | typing.SupportsIndex = 1.0, replace_existing: bool = False) -> None:
        ...
    def banner(self) -> typing.Any:
        """
        The board's banner, or None.
        """
    def close(self) -> None:
        ...
    def last(self) -> typing.Any:
        """
        The last row written, or None.
        """
    def poll(self, timeout_s: typing.SupportsFloat | typing.SupportsIndex) -> int:
        """
        Waits up to timeout_s [s] for data, writes the rows; reopens a lost port. Returns rows written.
        """
    def stats(self) -> dict:
        """
        Counters: bytes, frames, skipped_bytes, resyncs, checksum_errors, gaps, missing_frames, resets, disconnects, ...
        """
    @property
    def connected(self) -> bool:
        ...
    @property
    def last_error(self) -> str:
        """
        why the last open failed, '' if it did not
        """
def fit_pressure(applied_psi: collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex], measured_V: collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex]) -> dict:
    """
    Least-squares line gauge kPa = offset + slope V through the calibration points (appendix B: 0-80 psi every 10 psi). Returns {kPa_per_V, offset_kPa, max_residual_kPa}; ValueError naming the problem.
    """
def list_ports() -> list:
    """
    Serial ports (libserialport) with their /dev/serial/by-id names, which survive re-plugging.
    """
ADC_FULL_SCALE: int = 1024
FIRMWARE_VERSION: str = '1.0.0'
FRAME_SIZE: int = 16
FRAME_VERSION: int = 1
READ_BYTES: int = 4096
