"""Unit conversions, declared once in C++ (include/pamkit/units.hpp) and read from there."""

from pamkit._core import units as _units

PASCAL_PER_KILOPASCAL: float = _units.PASCAL_PER_KILOPASCAL
KILOPASCAL_PER_PSI: float = _units.KILOPASCAL_PER_PSI
KILOPASCAL_PER_BAR: float = _units.KILOPASCAL_PER_BAR
NEWTON_PER_KILOGRAM_FORCE: float = _units.NEWTON_PER_KILOGRAM_FORCE
KELVIN_AT_ZERO_CELSIUS: float = _units.KELVIN_AT_ZERO_CELSIUS
MILLIMETRE_PER_METRE: float = _units.MILLIMETRE_PER_METRE
