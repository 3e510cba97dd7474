"""
Conversions for quantities that cross a boundary in other units (units.hpp).
"""
from __future__ import annotations
__all__: list[str] = ['KELVIN_AT_ZERO_CELSIUS', 'KILOPASCAL_PER_BAR', 'KILOPASCAL_PER_PSI', 'MILLIMETRE_PER_METRE', 'NEWTON_PER_KILOGRAM_FORCE', 'PASCAL_PER_KILOPASCAL']
KELVIN_AT_ZERO_CELSIUS: float = 273.15
KILOPASCAL_PER_BAR: float = 100.0
KILOPASCAL_PER_PSI: float = 6.894757293168361
MILLIMETRE_PER_METRE: float = 1000.0
NEWTON_PER_KILOGRAM_FORCE: float = 9.80665
PASCAL_PER_KILOPASCAL: float = 1000.0
