"""The reference of pamkit's file formats, built from the code that reads them: every section and
key of an experiment file (with its unit, default, and the kinds of test that take it or need it),
the data columns of each kind, the muscle-parameters file and the command line.

The field lists come from where they are declared: the C++ structs' ``fields()`` (``[muscle]``,
``[friction]``, ``[gas]`` and the parameters file), the experiment file's schema
(:mod:`pamkit.io.schema`: the [test] keys, the kinds and their columns),
:func:`pamkit.io.sections.calibratable_fields` and the columns of :mod:`pamkit.io.columns`. The
documentation (its "Reference" pages) and ``pamkit template`` (:mod:`pamkit.templates`) are
generated from this module, and the tests check it against what the readers accept, so a key the
readers take cannot go undocumented.

Keys and columns are named as a file gives them, in its units (``inflation_pressure_kPa``, a CSV's
``pressure_kPa``); a data column also carries its SI name inside pamkit (``gauge_pressure_Pa`` in
:attr:`pamkit.Experiment.columns` and :func:`pamkit.simulate`'s DataFrame).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from pamkit._core import (
    Construction,
    FrictionParams,
    GasParams,
    GasProcess,
    InitialState,
    ModelExtensions,
    MuscleBuild,
)
from pamkit.io.columns import FILE_OPTIONAL_COLUMNS, REQUIRED_COLUMNS, si_name
from pamkit.io.experiment import GAS_MODES, GLITCH_CHOICES
from pamkit.io.schema import CAMPAIGN_SECTIONS, TABLE_COLUMNS, TABLE_DEFAULTS, TEST_CONDITIONS, TEST_KEYS
from pamkit.io.sections import (
    BLADDER_LAWS,
    BRAID_ANGLE_KEY,
    CONSTRUCTION_KEY,
    DEFAULT_WIND_TOLERANCE,
    GAS_PROCESS_KEY,
    NOT_BUILD,
    SCALED_WITH_DIAMETER,
    calibratable_fields,
)

# The kinds of test the reference and the templates distinguish: a time series sealed or under a
# supplied pressure ([test] gas), and the static tables ([test] kind).
SEALED = "sealed"
SUPPLIED = "supplied"
KINDS = (SEALED, SUPPLIED, *TABLE_COLUMNS)
SERIES_KINDS = (SEALED, SUPPLIED)
TABLE_KINDS = tuple(TABLE_COLUMNS)

KIND_MEANINGS = {
    SEALED: "a time series of a sealed muscle stretched and relaxed on a tensile machine: the thesis's bench test",
    SUPPLIED: "a time series under a pressure the rig supplies (a regulator): cyclic, or isometric with the "
    "length held while the pressure is swept",
    "isometric_map": "settled force at held lengths and supplied pressures: a commercial muscle's force map",
    "isotonic": "the length a muscle settles at under a constant load as the supplied pressure is swept up and vented",
    "free_inflation": "the free length and diameter at each pressure, no load: table 3.4 of the thesis",
}

# The unit a name's suffix says (the project's rule: a quantity's unit is in its name).
SUFFIX_UNITS = (
    ("_kPa", "kPa"),
    ("_Pa", "Pa"),
    ("_per_s", "1/s"),
    ("_s_per_m", "s/m"),
    ("_per_N", "1/N"),
    ("_J_per_kgK", "J/(kg K)"),
    ("_deg", "°"),
    ("_kg", "kg"),
    ("_N", "N"),
    ("_m", "m"),
    ("_s", "s"),
    ("_C", "°C"),
    ("_K", "K"),
)


def unit_of(name: str) -> str:
    """The unit a key's or column's name carries (``"kPa"`` for ``pressure_kPa``), or ``""``."""
    for suffix, unit in SUFFIX_UNITS:
        if name.endswith(suffix):
            return unit
    return ""


@dataclass(frozen=True)
class Key:
    """One key of a file section.

    Attributes
    ----------
    section : str
        The section (``"test"`` for ``[test]``).
    name : str
        The key.
    unit : str
        Its unit ("" for text, choices, counts and ratios).
    default : str
        What it is when left out ("" when it must be given where it applies).
    meaning : str
        What it means.
    kinds : tuple of str
        The kinds of test whose files may give it.
    required : tuple of str
        The kinds of test whose files must give it.
    example : object
        A value ``pamkit template`` writes for it (None: left out of templates unless required).
    allowed : str
        Its allowed values or range.
    """

    section: str
    name: str
    unit: str
    default: str
    meaning: str
    kinds: tuple[str, ...] = KINDS
    required: tuple[str, ...] = ()
    example: Any = None
    allowed: str = ""


def number_text(value: float) -> str:
    """A number as the reference and the templates show it: six significant digits."""
    return f"{value:.6g}"


def _struct_keys(section: str, struct: Any, meanings: dict[str, str] | None = None) -> list[Key]:
    """A bound parameter struct's fields as keys: unit, range and meaning from ``fields()``, the
    default from a default-constructed struct."""
    defaults = struct()
    keys = []
    for name, info in struct.fields().items():
        meaning = info["description"]
        if meanings and name in meanings:
            meaning = f"{meaning}; {meanings[name]}"
        keys.append(
            Key(
                section,
                name,
                info["unit"] if info["unit"] != "1" else "",
                number_text(getattr(defaults, name)),
                meaning,
                allowed=f"[{number_text(info['min'])}, {number_text(info['max'])}]",
            )
        )
    return keys


# [test]'s keys in the reference's words; TEST_KEYS (pamkit.io.schema) says which keys the reader
# takes, and a key it takes that has no entry here fails the documentation's build and its test.
TEST_KEY_MEANINGS = {
    "inflation_pressure_kPa": "gauge pressure after inflation, before the first stretch: a sealed muscle's "
    "fill; a supplied test's pressure at its start (in Python, SI: Experiment.inflation_gauge_pressure_Pa [Pa])",
    "ambient_temperature_C": "ambient temperature, and the gas's at the start (in Python, SI: "
    "Experiment.gas_params.ambient_temperature_K [K])",
    "data": "the data CSV, relative to this file",
    "kind": "what was measured: a time series, or a static table of settled rows",
    "gas": "a sealed muscle (a closed mass of air), or one on a pressure regulator whose measured pressure_kPa "
    "drives the model",
    "initial_length_m": "the muscle's length at zero elongation",
    "load_N": "the constant load the muscle carries (or declared unknown in [calibrate])",
    "load_mass_kg": "the hanging load's mass: the length then follows the load's motion, integrated in time, "
    "instead of the quasi-static path",
    "description": "free text: where the test comes from",
    "zero": "a run with no air (a CSV, relative to this file), whose means (its glitches left out) are taken off "
    "the load cell and the transducer",
    "preload_N": "the force the deflated muscle was mounted with; it sets the mounted length (not with "
    "initial_length_m)",
    "force_range_N": "[lowest, highest] force the load cell reads: it clips beyond, and so does the prediction",
    "pressure_range_kPa": "[lowest, highest] gauge pressure the transducer reads: rows at an end are censored "
    "(predicted, never fitted or scored) (in Python, SI: Experiment.ranges['gauge_pressure_Pa'] [Pa])",
    "specimen": "in a tensile machine's export of several specimens: the one this test is (its Specimen Number)",
    "ignore_columns": "data columns not to read, as the file names them (a logger's valve state, a note); any other "
    "column pamkit does not know is an error, so that a misspelt channel is not left unread",
    "glitches": "a time series' isolated glitches (samples far off their channel's course): left out before the "
    "diagnosis, which says where (warnings[].glitches), or kept",
}


def _test_keys() -> list[Key]:
    """[test]: the keys TEST_KEYS lists, with the kinds that take and need each key as the
    experiment reader decides them (pamkit.io.experiment.load_experiment)."""
    kinds = {
        "load_N": ("isotonic",),
        "load_mass_kg": ("isotonic",),
        "preload_N": (SUPPLIED,),
        "zero": SERIES_KINDS,
        "specimen": SERIES_KINDS,
        "glitches": SERIES_KINDS,
    }
    defaults = {
        "kind": '"series"',
        "gas": '"sealed" (a table: "supplied")',
        "initial_length_m": "sealed: the free length at the inflation pressure; supplied: the deflated length",
        "description": '""',
        "force_range_N": "no clipping",
        "pressure_range_kPa": "no clipping",
        "ignore_columns": "[] (every column read)",
        "glitches": f'"{GLITCH_CHOICES[0]}"',
    }
    allowed = {
        "kind": ", ".join(f'"{k}"' for k in ("series", *TABLE_KINDS)),
        "gas": ", ".join(f'"{g}"' for g in GAS_MODES),
        **{key: f"[{lowest:g}, {highest:g}]" for key, (lowest, highest, _, _) in TEST_CONDITIONS.items()},
        "initial_length_m": "(0, 5]",
        "load_N": "[0, 1e5]",
        "load_mass_kg": "(0, 1e4]",
        "preload_N": "(0, 1e5]",
        "force_range_N": "[lowest, highest]",
        "pressure_range_kPa": "[lowest, highest]",
        "ignore_columns": '["name", ...]',
        "glitches": ", ".join(f'"{choice}"' for choice in GLITCH_CHOICES),
    }
    keys = []
    for name, (series_required, _) in TEST_KEYS.items():
        takes = kinds.get(name, KINDS)
        required = tuple(k for k in takes if series_required and (k in SERIES_KINDS or name == "data"))
        if name == "load_N":
            required = ("isotonic",)  # unless declared unknown in [calibrate]
        default = defaults.get(name, "")
        if name in TABLE_DEFAULTS:
            default = f"a table: {number_text(TABLE_DEFAULTS[name])}"
        keys.append(
            Key(
                "test",
                name,
                unit_of(name),
                default,
                TEST_KEY_MEANINGS[name],
                takes,
                required,
                allowed=allowed.get(name, ""),
            )
        )
    return keys


CONSTRUCTION_MEANING = (
    "how the fibres and the membrane are put together: a bladder inside a braided sleeve (the thesis's muscle), "
    "or fibres embedded in the membrane (a Festo fluidic muscle), whose braid cannot push: held shorter than its "
    "free length it goes slack and carries nothing"
)


def _constructions() -> str:
    return ", ".join(f'"{name}"' for name in Construction.__members__)


def experiment_keys() -> list[Key]:
    """Every key of an experiment file, section by section ([muscle], [bladder], [friction],
    [gas], [calibrate], [uncertain], [test]), and of a campaign file ([campaign])."""
    scaled = "scales with diameter_m from PAM 2's when left out"
    muscle = _struct_keys("muscle", MuscleBuild, {name: scaled for name in SCALED_WITH_DIAMETER})
    muscle.append(
        Key(
            "muscle",
            BRAID_ANGLE_KEY,
            "°",
            "from fiber_revolutions",
            "the deflated braid's angle to the axis, what a datasheet gives, instead of fiber_revolutions",
            allowed="(0, 90)",
        )
    )
    muscle.append(
        Key(
            "muscle",
            CONSTRUCTION_KEY,
            "",
            '"sleeve"',
            CONSTRUCTION_MEANING,
            allowed=_constructions(),
        )
    )
    bladder = [
        Key(
            "bladder",
            "law",
            "",
            '"thesis"',
            "the membrane's stress law: the thesis's polynomial (eqs. 3.1.12-3.1.13), an incompressible "
            "neo-Hookean membrane, or none",
            allowed=", ".join(f'"{law}"' for law in BLADDER_LAWS),
        ),
        Key(
            "bladder",
            "shear_modulus_Pa",
            "Pa",
            "",
            'the neo-Hookean membrane\'s shear modulus (rubbers: 0.2e6-3e6 Pa); only with law = "neo_hookean", '
            "which needs it",
            allowed="> 0",
        ),
    ]
    friction = _struct_keys("friction", FrictionParams)
    gas = _struct_keys(
        "gas",
        GasParams,
        {"ambient_temperature_K": "taken from [test] ambient_temperature_C"},
    )
    gas.append(
        Key(
            "gas",
            GAS_PROCESS_KEY,
            "",
            '"polytropic"',
            "the gas's process: a fixed polytropic exponent, or an energy balance with heat exchanged with the "
            "wall in heat_transfer_time_constant_s",
            allowed=", ".join(f'"{name}"' for name in GasProcess.__members__),
        )
    )
    calibrate = []
    for name, (low, high, unit) in calibratable_fields().items():
        kinds: tuple[str, ...] = ("isotonic",) if name == "load_N" else KINDS
        calibrate.append(
            Key(
                "calibrate",
                name,
                unit if unit != "1" else "",
                "known (as declared)",
                f"unknown: [lower, upper] bounds within [{number_text(low)}, {number_text(high)}]; the diagnosis "
                "calibrates it and reports it with a 95 % interval",
                kinds,
                allowed="[lower, upper]",
            )
        )
    uncertain = [
        Key(
            "uncertain",
            name,
            unit if unit != "1" else "",
            f"{DEFAULT_WIND_TOLERANCE:.0%} of the declared revolutions" if name == "fiber_revolutions" else "exact",
            "how far the built muscle may be from the declared value (±, in its unit): the diagnosis checks each "
            "cause with the build free within it; without the section the braid's wind is uncertain by "
            f"{DEFAULT_WIND_TOLERANCE:.0%} in a time series (a static table frees only the fields its file gives "
            "here), an empty section declares the build exact",
            allowed="> 0",
        )
        for name, (_, _, unit) in calibratable_fields().items()
        if name not in NOT_BUILD
    ]
    campaign = [
        Key(
            "campaign",
            "tests",
            "",
            "",
            "the experiment files of the campaign, relative to this file; the campaign file may give "
            + ", ".join(f"[{s}]" for s in CAMPAIGN_SECTIONS if s != "campaign")
            + " for all of them, which they may then not give",
            required=KINDS,
        )
    ]
    return muscle + bladder + friction + gas + calibrate + uncertain + _test_keys() + campaign


@dataclass(frozen=True)
class Column:
    """One column of an experiment's data CSV.

    Attributes
    ----------
    name : str
        Its name in the CSV (``pressure_kPa``).
    unit : str
        Its unit in the CSV (``kPa``).
    required : bool
        Whether a file of the kind must have it.
    meaning : str
        What it holds.
    si_name : str
        Its name inside pamkit, SI (``gauge_pressure_Pa``): in :attr:`pamkit.Experiment.columns`,
        :meth:`pamkit.Experiment.to_frame` and :func:`pamkit.simulate`'s DataFrame.
    si_unit : str
        The unit of that name (``Pa``).
    """

    name: str
    unit: str
    required: bool
    meaning: str
    si_name: str
    si_unit: str


def _column(name: str, required: bool, meaning: str) -> Column:
    """The column a file names `name`, with its SI name and unit inside pamkit."""
    return Column(name, unit_of(name), required, meaning, si_name(name), unit_of(si_name(name)))


COLUMN_MEANINGS = {
    "time_s": "time since the start of the record, increasing",
    "elongation_m": "stretch from the muscle's length at zero elongation ([test] initial_length_m); may be "
    "negative under a supplied pressure",
    "force_N": "axial force the load cell reads, tension positive",
    "pressure_kPa": "gauge pressure inside the muscle",
    "temperature_C": "gas temperature inside the muscle (the logger's TMP36)",
    "length_m": "the muscle's length between its end caps",
    "diameter_m": "the muscle's outer braid diameter at mid-length",
    "contraction_m": "the muscle's contraction from its deflated length (instead of length_m)",
    "contraction_percent": "the muscle's contraction in per cent of its deflated length, as a datasheet plots "
    "force against contraction (instead of length_m)",
}


def data_columns(kind: str) -> list[Column]:
    """The data CSV's columns of a kind of test, as a file names them (the column lists of
    pamkit.io.columns and pamkit.io.schema), each with its SI name inside pamkit."""
    if kind in SERIES_KINDS:
        columns = [_column(name, True, COLUMN_MEANINGS[name]) for name in REQUIRED_COLUMNS]
        for name in FILE_OPTIONAL_COLUMNS:
            needed = kind == SUPPLIED and name == "pressure_kPa"
            meaning = COLUMN_MEANINGS[name] + ("; the supplied pressure, which drives the model" if needed else "")
            columns.append(_column(name, needed, meaning))
        return columns
    lengths = [
        _column("length_m", True, COLUMN_MEANINGS["length_m"] + " (or contraction_m, contraction_percent)"),
        Column("contraction_m", "m", False, COLUMN_MEANINGS["contraction_m"], "length_m", "m"),
        Column("contraction_percent", "%", False, COLUMN_MEANINGS["contraction_percent"], "length_m", "m"),
    ]
    if kind == "isotonic":
        return [
            _column("pressure_kPa", True, COLUMN_MEANINGS["pressure_kPa"] + "; the supplied pressure"),
            *lengths,
            _column("time_s", False, "time of the row; needed with [test] load_mass_kg"),
        ]
    if kind == "isometric_map":
        return [*lengths, *(_column(name, True, COLUMN_MEANINGS[name]) for name in TABLE_COLUMNS[kind][1:])]
    return [_column(name, True, COLUMN_MEANINGS[name]) for name in TABLE_COLUMNS[kind]]


def params_file_keys() -> list[Key]:
    """Every key of a muscle-parameters file (C++ pamkit/io/params_file.hpp, ``pamkit diagnose
    --params-out``): the parts of MuscleParams by their C++ field lists, every key required but
    [initial]'s and [rig]'s sections."""
    keys = []
    for section, struct in (("build", MuscleBuild), ("friction", FrictionParams), ("gas", GasParams)):
        keys += [
            Key(section, k.name, k.unit, "", k.meaning, required=KINDS, allowed=k.allowed)
            for k in _struct_keys(section, struct)
        ]
    keys.append(Key("build", CONSTRUCTION_KEY, "", "", CONSTRUCTION_MEANING, required=KINDS, allowed=_constructions()))
    keys.append(
        Key("gas", "process", "", "", "the gas's process", required=KINDS, allowed='"polytropic", "heat_transfer"')
    )
    keys += [
        Key("bladder", "form", "", "", "the membrane law", required=KINDS, allowed='"polynomial", "neo_hookean"'),
        Key(
            "bladder",
            "longitudinal_Pa",
            "Pa",
            "",
            'form = "polynomial": coefficients c0..c6 of the longitudinal stress, sigma = sum c_k eps^k (fewer '
            "than seven leave the higher ones 0)",
            allowed="1 to 7 numbers",
        ),
        Key(
            "bladder",
            "hoop_Pa",
            "Pa",
            "",
            'form = "polynomial": coefficients c0..c6 of the hoop stress',
            allowed="1 to 7 numbers",
        ),
        Key("bladder", "shear_modulus_Pa", "Pa", "", 'form = "neo_hookean": the shear modulus', allowed="> 0"),
    ]
    keys += [
        Key("extensions", k.name, k.unit, "", k.meaning, required=KINDS, allowed=k.allowed)
        for k in _struct_keys("extensions", ModelExtensions)
    ]
    keys += [
        Key(
            "initial",
            k.name,
            k.unit,
            "",
            k.meaning + " (the optional section: the sealed test's state at zero elongation)",
            allowed=k.allowed,
        )
        for k in _struct_keys("initial", InitialState)
    ]
    keys.append(
        Key(
            "rig",
            "effects",
            "",
            "",
            "the optional section: what a diagnosis found in the test rig's fixture and instruments, as the effect "
            "catalog parses them; a controller leaves them out, `pamkit simulate --params` applies them",
            allowed='["NAME:key=value,...", ...]',
        )
    )
    return keys
