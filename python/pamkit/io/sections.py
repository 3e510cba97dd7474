"""The muscle's sections of an experiment file into the parameter structs: [muscle] into
MuscleBuild (or its braid angle instead of the fibers' turns), [bladder] into the membrane's
law, [friction] and [gas] into theirs, [calibrate] into the bounds of what the file leaves
unknown. Keys are the structs' own field names (C++'s for_each_field), so a field added there is
a key here."""

from __future__ import annotations

import math
from pathlib import Path

from pamkit._core import (
    BladderLaw,
    Construction,
    FrictionParams,
    GasParams,
    GasProcess,
    MuscleBuild,
    deflated_braid_angle_deg,
    fiber_revolutions_for_braid_angle,
)
from pamkit.io.guards import check_keys, fail, number

# [gas] keys beyond GasParams' fields: the process by name.
GAS_PROCESS_KEY = "process"
# [muscle] key beyond MuscleBuild's fields: what a datasheet gives instead of fiber_revolutions.
BRAID_ANGLE_KEY = "braid_angle_deg"
# [muscle] key beyond MuscleBuild's fields: how fibres and membrane are put together, by name.
CONSTRUCTION_KEY = "construction"
# [muscle] dimensions that scale with the braid diameter when a file leaves them out.
SCALED_WITH_DIAMETER = (
    "bladder_diameter_m",
    "bladder_thickness_m",
    "fiber_thickness_m",
    "end_diameter_m",
    "cone_generator_m",
)
# [bladder] keys: the law by name, and the neo-Hookean modulus.
BLADDER_LAWS = ("thesis", "neo_hookean", "none")


def fill_struct(path: Path, section: str, table: dict, struct, extra_keys=()):
    """Sets the fields of a bound parameter struct from a TOML table, by the struct's own field
    list, rejecting unknown keys and validating the result."""
    fields = type(struct).fields()
    check_keys(path, section, table, sorted(list(fields) + list(extra_keys)))
    for key, value in table.items():
        if key not in extra_keys:
            setattr(struct, key, number(path, f"[{section}] {key}", value))
    try:
        struct.validate()
    except ValueError as error:
        raise fail(path, f"[{section}] {error}") from None
    return struct


def _scaled_defaults(path: Path, table: dict) -> MuscleBuild:
    """The defaults of the dimensions a file leaves out, scaled with its braid diameter: PAM 2's
    (table C.4) are for a 20 mm braid, and a 10 mm muscle declared by its datasheet (length and
    diameter) would otherwise get a bladder and end caps wider than its braid."""
    build = MuscleBuild()
    if "diameter_m" not in table:
        return build
    scale = number(path, "[muscle] diameter_m", table["diameter_m"]) / build.diameter_m
    for name in SCALED_WITH_DIAMETER:
        if name not in table:
            setattr(build, name, scale * getattr(build, name))
    return build


def read_build(path: Path, table: dict) -> MuscleBuild:
    """[muscle]: MuscleBuild's fields, or braid_angle_deg instead of fiber_revolutions, and the
    construction by name ("sleeve", the default, or "embedded")."""
    table = dict(table)
    angle = table.pop(BRAID_ANGLE_KEY, None)
    if angle is not None and "fiber_revolutions" in table:
        raise fail(path, f"[muscle] gives both {BRAID_ANGLE_KEY} and fiber_revolutions: give one, they say the same")
    construction = table.pop(CONSTRUCTION_KEY, "sleeve")
    if not isinstance(construction, str) or construction not in Construction.__members__:
        raise fail(
            path, f"[muscle] {CONSTRUCTION_KEY} = {construction!r} must be one of {', '.join(Construction.__members__)}"
        )
    build = _scaled_defaults(path, table)
    build.construction = Construction.__members__[construction]
    # The keys beyond the build's fields, taken out above, are named among the known ones.
    named = (BRAID_ANGLE_KEY, CONSTRUCTION_KEY)
    if angle is None:
        return fill_struct(path, "muscle", table, build, named)
    angle = number(path, f"[muscle] {BRAID_ANGLE_KEY}", angle)
    for key, value in table.items():  # the angle converts through the other dimensions
        if key in type(build).fields():
            setattr(build, key, number(path, f"[muscle] {key}", value))
    try:
        build.fiber_revolutions = fiber_revolutions_for_braid_angle(build, angle)
    except ValueError as error:
        raise fail(path, f"[muscle] {error}") from None
    return fill_struct(path, "muscle", table, build, named)


def read_bladder(path: Path, table: dict) -> BladderLaw:
    """[bladder]: law = "thesis" (default), "neo_hookean" (with shear_modulus_Pa) or "none"."""
    check_keys(path, "bladder", table, ("law", "shear_modulus_Pa"))
    law = table.get("law", "thesis")
    if law not in BLADDER_LAWS:
        raise fail(path, f"[bladder] law = {law!r} must be one of {', '.join(BLADDER_LAWS)}")
    if law == "neo_hookean":
        if "shear_modulus_Pa" not in table:
            raise fail(path, "[bladder] law = 'neo_hookean' needs shear_modulus_Pa (rubbers: 0.2e6-3e6 Pa)")
        try:
            return BladderLaw.neo_hookean(number(path, "[bladder] shear_modulus_Pa", table["shear_modulus_Pa"]))
        except ValueError as error:
            raise fail(path, f"[bladder] {error}") from None
    if "shear_modulus_Pa" in table:
        raise fail(path, f"[bladder] shear_modulus_Pa belongs to law = 'neo_hookean', not {law!r}")
    return BladderLaw.thesis() if law == "thesis" else BladderLaw.none()


def calibratable_fields() -> dict[str, tuple[float, float, str]]:
    """What [calibrate] may name: each field with its allowed range and unit."""
    fields = {name: (info["min"], info["max"], info["unit"]) for name, info in MuscleBuild.fields().items()}
    fields[BRAID_ANGLE_KEY] = (1.0, 89.0, "deg")
    fields["load_N"] = (0.0, 1e5, "N")
    fields["bladder.shear_modulus_Pa"] = (0.0, 1e9, "Pa")
    return fields


def declared_value(name: str, build: MuscleBuild, bladder: BladderLaw, load_N: float | None = None) -> float:
    """The value an experiment file declares for a [calibrate] name (NaN for a load it leaves out)."""
    if name == "load_N":
        return load_N if load_N is not None else math.nan
    if name == BRAID_ANGLE_KEY:
        return deflated_braid_angle_deg(build)
    if name == "bladder.shear_modulus_Pa":
        return bladder.shear_modulus_Pa
    return getattr(build, name)


def read_calibrate(path: Path, table: dict, bladder: BladderLaw) -> dict[str, tuple[float, float]]:
    """[calibrate]: fields not known, each with [lower, upper] bounds within its allowed range."""
    flat: dict[str, object] = {}
    for key, value in table.items():
        if isinstance(value, dict):  # [calibrate.bladder] or bladder.shear_modulus_Pa = [...]
            flat.update({f"{key}.{inner}": bounds for inner, bounds in value.items()})
        else:
            flat[key] = value
    allowed = calibratable_fields()
    out = {}
    for name, bounds in flat.items():
        if name not in allowed:
            raise fail(path, f"[calibrate] {name}: not a field pamkit can calibrate (known: {', '.join(allowed)})")
        if (
            not isinstance(bounds, list)
            or len(bounds) != 2
            or not all(isinstance(b, (int, float)) and not isinstance(b, bool) for b in bounds)
        ):
            raise fail(path, f"[calibrate] {name} = {bounds!r} must be [lower, upper]")
        lower, upper = float(bounds[0]), float(bounds[1])
        low, high, unit = allowed[name]
        if not (math.isfinite(lower) and math.isfinite(upper) and lower < upper):
            raise fail(path, f"[calibrate] {name} = [{lower}, {upper}] needs finite lower < upper")
        if lower < low or upper > high:
            raise fail(path, f"[calibrate] {name} = [{lower}, {upper}] {unit} leaves the allowed [{low}, {high}]")
        if name == "bladder.shear_modulus_Pa" and bladder.form != BladderLaw.Form.neo_hookean:
            raise fail(path, "[calibrate] bladder.shear_modulus_Pa needs [bladder] law = 'neo_hookean'")
        if name == "fiber_revolutions" and BRAID_ANGLE_KEY in flat:
            raise fail(path, f"[calibrate] names both fiber_revolutions and {BRAID_ANGLE_KEY}: they are one unknown")
        out[name] = (lower, upper)
    return out


# [uncertain] when a file gives none: the braid's wind within 5 % of the declared revolutions. The
# wind is the build number a builder knows least well (turns counted by hand over the braided
# length, and the angle the sleeve settles at on its end fittings); 5 % is a tenth of a turn in the
# thesis's two, 1.3 degrees of PAM 2's deflated 31.2-degree braid angle.
DEFAULT_WIND_TOLERANCE = 0.05


def read_uncertain(path: Path, table: dict, build: MuscleBuild) -> dict[str, float]:
    """[uncertain]: how far the built muscle may be from what [muscle] declares, each field a
    tolerance (±, in the field's own unit: turns, degrees, metres) the diagnosis checks its causes
    against. Without the section: the wind within DEFAULT_WIND_TOLERANCE of the declared
    revolutions; an empty section declares the build exact."""
    if table is None:
        return {"fiber_revolutions": DEFAULT_WIND_TOLERANCE * build.fiber_revolutions}
    allowed = {name: bounds for name, bounds in calibratable_fields().items() if name not in NOT_BUILD}
    out = {}
    for name, value in table.items():
        if name not in allowed:
            raise fail(path, f"[uncertain] {name}: not a field of the build (known: {', '.join(allowed)})")
        tolerance = number(path, f"[uncertain] {name}", value)
        low, high, unit = allowed[name]
        if not (math.isfinite(tolerance) and tolerance > 0.0):
            raise fail(path, f"[uncertain] {name} = {value!r} must be a tolerance > 0 {unit} (the ± of the build)")
        declared = declared_value(name, build, BladderLaw.thesis())
        if declared - tolerance < low or declared + tolerance > high:
            raise fail(
                path,
                f"[uncertain] {name} = {tolerance:g}: the declared {declared:g} ± {tolerance:g} {unit} leaves the "
                f"allowed [{low}, {high}]",
            )
        out[name] = float(tolerance)
    if "fiber_revolutions" in out and BRAID_ANGLE_KEY in out:
        raise fail(path, f"[uncertain] names both fiber_revolutions and {BRAID_ANGLE_KEY}: they are one number")
    return out


# Names [calibrate] takes that are not the build's: the test's load and the membrane's law.
NOT_BUILD = ("load_N", "bladder.shear_modulus_Pa")


def read_friction(path: Path, table: dict) -> FrictionParams:
    """[friction]: FrictionParams' fields."""
    return fill_struct(path, "friction", table, FrictionParams())


def read_gas(path: Path, table: dict) -> GasParams:
    """[gas]: GasParams' fields, and the process by name (process = "heat_transfer", say)."""
    gas = GasParams()
    if GAS_PROCESS_KEY in table:
        name = table[GAS_PROCESS_KEY]
        if not isinstance(name, str) or name not in GasProcess.__members__:  # a list is no dict key
            raise fail(path, f"[gas] process = {name!r} must be one of {', '.join(GasProcess.__members__)}")
        gas.process = GasProcess.__members__[name]
    return fill_struct(path, "gas", table, gas, extra_keys=(GAS_PROCESS_KEY,))
