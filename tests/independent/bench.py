"""The bench's instruments, re-stated from the thesis (section 3.2, appendices B and G.2) and the
ATmega2560 datasheet rather than imported, and the writer of an experiment (TOML + CSV, the
format of docs/reference/experiment-file.rst).

- Load cell (Instron 4482, 100 kN cell far below its range): white noise of 1 N RMS (0.5-2 N,
  a 100 kN cell's floor, in the near-model world), recorded in steps of 0.2 N (a 20-bit
  conversion of ±100 kN).
- Crosshead encoder: exported in mm with 3 decimals, i.e. steps of 1 µm.
- Arduino Mega, 10-bit ADC on a 5 V reference, one conversion per sample: counts =
  round(V · 1024 / 5), with 2 mV RMS of electrical noise at its input.
  61CP transducer: V = 0.56 V + 0.04 V/psi · p; the host's appendix-B line psi = 25 V − 14
  (one count: 25 · 5/1024 psi = 0.842 kPa).
  TMP36: V = 0.5 V + 10 mV/°C · T (one count: 0.488 °C).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

KPA_PER_PSI = 6.894757293168  # NIST SP 811
LOAD_CELL_NOISE_N = 1.0
LOAD_CELL_STEP_N = 0.2
ENCODER_STEP_M = 1e-6
ADC_COUNTS = 1024
ADC_REFERENCE_V = 5.0
ADC_NOISE_V = 2e-3
TRANSDUCER_ZERO_V = 0.56
TRANSDUCER_V_PER_PSI = 0.04
HOST_PSI_PER_V = 25.0
HOST_PSI_AT_0V = -14.0
TMP36_ZERO_V = 0.5
TMP36_V_PER_C = 0.01


def quantise(values, step):
    return np.round(np.asarray(values, dtype=float) / step) * step


def load_cell(force_N, rng, noise_N=LOAD_CELL_NOISE_N):
    """What the load cell records: white noise of `noise_N` RMS, in steps of 0.2 N."""
    force = np.asarray(force_N, dtype=float)
    return quantise(force + rng.normal(0.0, noise_N, force.shape), LOAD_CELL_STEP_N)


def encoder(elongation_m, rng=None, noise_m=0.0):
    x = np.asarray(elongation_m, dtype=float)
    if noise_m > 0:
        x = x + rng.normal(0.0, noise_m, x.shape)
    return quantise(x, ENCODER_STEP_M)


def _adc_volts(volts, rng):
    noisy = np.asarray(volts, dtype=float) + rng.normal(0.0, ADC_NOISE_V, np.shape(volts))
    counts = np.clip(np.floor(noisy * ADC_COUNTS / ADC_REFERENCE_V + 0.5), 0, ADC_COUNTS - 1)
    return counts * ADC_REFERENCE_V / ADC_COUNTS


def pressure_logger(gauge_kPa, rng):
    """What the host writes for a gauge pressure [kPa]."""
    volts = TRANSDUCER_ZERO_V + TRANSDUCER_V_PER_PSI * np.asarray(gauge_kPa, dtype=float) / KPA_PER_PSI
    return (HOST_PSI_PER_V * _adc_volts(volts, rng) + HOST_PSI_AT_0V) * KPA_PER_PSI


def temperature_logger(temperature_C, rng):
    volts = TMP36_ZERO_V + TMP36_V_PER_C * np.asarray(temperature_C, dtype=float)
    return (_adc_volts(volts, rng) - TMP36_ZERO_V) / TMP36_V_PER_C


def write_columns(path: Path, columns: dict[str, np.ndarray]) -> None:
    """Writes `columns` as a CSV file with their names for a header."""
    path.parent.mkdir(parents=True, exist_ok=True)
    header = list(columns)
    table = np.column_stack([np.asarray(columns[c], dtype=float) for c in header])
    lines = [",".join(header)] + [",".join(f"{v:.10g}" for v in row) for row in table]
    path.write_text("\n".join(lines) + "\n")


def write_experiment(
    folder: Path, name: str, muscle: dict, test: dict, columns: dict[str, np.ndarray], comment: str
) -> Path:
    """Writes NAME.toml and NAME.csv into `folder`; returns the TOML's path."""
    write_columns(folder / f"{name}.csv", columns)

    def value(v):
        if isinstance(v, str):
            return f'"{v}"'
        return str(int(v)) if float(v).is_integer() else repr(float(v))

    text = f"# {comment}\n\n[muscle]\n" + "".join(f"{k} = {value(v)}\n" for k, v in muscle.items())
    text += "\n[test]\n" + "".join(f"{k} = {value(v)}\n" for k, v in test.items()) + f'data = "{name}.csv"\n'
    path = folder / f"{name}.toml"
    path.write_text(text)
    return path
