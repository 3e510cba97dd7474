"""Experiment files to start from (``pamkit template KIND``): each kind of test with every key it
may give, explained from the reference (:mod:`pamkit.reference`), the values a test of that kind
needs set to examples to replace and the others commented out with their defaults."""

from __future__ import annotations

import sys
import textwrap
from typing import Any

if sys.version_info >= (3, 11):
    import tomllib
else:
    import tomli as tomllib

from pamkit.io.sections import BRAID_ANGLE_KEY
from pamkit.reference import KIND_MEANINGS, KINDS, SEALED, SUPPLIED, Key, data_columns, experiment_keys, number_text

# What each template sets (the rest of its keys are written commented out, with their defaults).
# The table kinds characterise a commercial muscle, declared as its datasheet gives it and as
# data/experiments/festo/ declares a Festo fluidic muscle (a DMSP-10 here): its fibres in its
# membrane, flat press-fitted flanges with end zones, the braid angle and the end zones to
# calibrate (the declaration the independent DMSP tests of docs/validation.md are diagnosed with);
# a thesis-style muscle by its build.
_DATASHEET_MUSCLE: dict[str, dict[str, Any]] = {
    "muscle": {
        "construction": "embedded",
        "length_m": 0.25,
        "diameter_m": 0.01,
        "bladder_diameter_m": 0.01,
        "bladder_thickness_m": 0.5e-3,
        BRAID_ANGLE_KEY: 20.0,
        "fiber_thickness_m": 0.0,
        "end_diameter_m": 0.005,
        "cone_generator_m": 0.0,
        "end_zone_m": 0.008,
    },
    "bladder": {"law": "none"},
    "calibrate": {BRAID_ANGLE_KEY: [10.0, 45.0], "end_zone_m": [0.0, 0.02]},
}
_BUILT_MUSCLE: dict[str, dict[str, Any]] = {"muscle": {"length_m": 0.225, "diameter_m": 0.02}}
TEMPLATE_VALUES: dict[str, dict[str, dict[str, Any]]] = {
    SEALED: {**_BUILT_MUSCLE, "test": {"inflation_pressure_kPa": 207.0, "ambient_temperature_C": 20.0}},
    SUPPLIED: {
        **_BUILT_MUSCLE,
        "test": {"gas": "supplied", "inflation_pressure_kPa": 0.0, "ambient_temperature_C": 20.0},
    },
    "isometric_map": {**_DATASHEET_MUSCLE, "test": {"kind": "isometric_map"}},
    "isotonic": {**_DATASHEET_MUSCLE, "test": {"kind": "isotonic", "load_N": 100.0}},
    "free_inflation": {**_BUILT_MUSCLE, "test": {"kind": "free_inflation"}},
}
TEMPLATE_KINDS = (*KINDS, "campaign")


def _toml(value: Any) -> str:
    if isinstance(value, str):
        return f'"{value}"'
    if isinstance(value, list):
        return "[" + ", ".join(_toml(v) for v in value) + "]"
    return number_text(value)


def _explained(key: Key) -> str:
    unit = f"[{key.unit}] " if key.unit else ""
    notes = [f"default {key.default}" if key.default else "", f"allowed {key.allowed}" if key.allowed else ""]
    extra = "; ".join(n for n in notes if n)
    return f"{unit}{key.meaning}" + (f" ({extra})" if extra else "")


def _comment(text: str, width: int = 100) -> list[str]:
    return ["# " + line for line in textwrap.wrap(text, width - 2)]


def _is_value(text: str) -> bool:
    """Whether a default as the reference shows it is a TOML value (and not a sentence)."""
    try:
        tomllib.loads(f"value = {text}")
    except tomllib.TOMLDecodeError:
        return False
    return True


def template(kind: str, data: str = "run.csv") -> str:
    """An experiment file of a kind of test with every key it may give, explained: the values a
    test of that kind needs set to examples to replace, the others commented out with their
    defaults (``pamkit template KIND``).

    Parameters
    ----------
    kind : str
        One of :data:`TEMPLATE_KINDS`: ``sealed``, ``supplied``, ``isometric_map``, ``isotonic``,
        ``free_inflation``, or ``campaign`` (a campaign file naming two tests).
    data : str
        The data CSV ``[test] data`` names.

    Returns
    -------
    str
        The TOML text.

    Raises
    ------
    ValueError
        For an unknown kind, naming the known ones.
    """
    if kind not in TEMPLATE_KINDS:
        raise ValueError(f"no template for {kind!r} (known: {', '.join(TEMPLATE_KINDS)})")
    keys = experiment_keys()
    if kind == "campaign":
        lines = [
            "# A pamkit campaign: several tests of one muscle, diagnosed together (pamkit diagnose THIS.toml).",
            "# Each test is an experiment file of its own (pamkit template KIND); the sections below are shared by",
            "# all of them, and a test may then not give them again.",
            "",
            "[campaign]",
            *_comment(_explained(next(k for k in keys if k.section == "campaign"))),
            'tests = ["test_1.toml", "test_2.toml"]',
            "",
            "[muscle]",
        ]
        for name, value in _BUILT_MUSCLE["muscle"].items():
            lines += _comment(_explained(next(k for k in keys if k.section == "muscle" and k.name == name)))
            lines.append(f"{name} = {_toml(value)}")
        return "\n".join(lines) + "\n"
    values = {section: dict(table) for section, table in TEMPLATE_VALUES[kind].items()}
    values.setdefault("test", {})["data"] = data
    columns = ", ".join(f"{c.name}{'' if c.required else ' (optional)'}" for c in data_columns(kind))
    lines = _comment(
        f"A pamkit experiment: {KIND_MEANINGS[kind]}. Written by `pamkit template {kind}`: replace the example "
        f"values, put the measured rows in {data} (columns: {columns}), and check the file with `pamkit simulate "
        "THIS.toml -o predicted.csv`. Above each key: its unit, meaning, default and allowed values; a key left "
        "commented out keeps its default."
    )
    for section in ("muscle", "bladder", "friction", "gas", "calibrate", "test"):
        given = values.get(section, {})
        lines += ["", f"[{section}]"]
        for key in (k for k in keys if k.section == section and kind in k.kinds):
            lines += _comment(_explained(key))
            if key.name in given:
                lines.append(f"{key.name} = {_toml(given[key.name])}")
            elif section == "calibrate":
                lines.append(f"# {key.name} = [lower, upper]")
            else:
                lines.append(f"# {key.name} = {key.default if _is_value(key.default) else '...'}")
    return "\n".join(lines) + "\n"
