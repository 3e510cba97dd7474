"""The effect catalog from Python: parse ``--effect NAME:key=value`` specs, list effects, add
your own.

Built-in effects live in C++ (include/pamkit/effects/catalog.hpp). A Python effect derives
from :class:`pamkit.Effect` and is added to a catalog with ``catalog.add(name, factory)``::

    class Creep(pamkit.Effect):
        def name(self): return "creep"
        ...
    catalog = pamkit.effects.catalog()
    catalog.add("creep", Creep)
"""

from __future__ import annotations

from collections.abc import Iterable

from pamkit._core import Effect, EffectCatalog


def catalog() -> EffectCatalog:
    """A new catalog holding the built-in effects."""
    return EffectCatalog.builtin()


def parse_effects(specs: Iterable[str], effect_catalog: EffectCatalog | None = None) -> list[Effect]:
    """Configured effects from specs like ``"heat_transfer:time_constant_s=2"``.

    Raises:
        ValueError: naming the unknown effect, key or bad value.
    """
    effect_catalog = effect_catalog if effect_catalog is not None else catalog()
    return [effect_catalog.parse(spec) for spec in specs]


# Each built-in effect's description says what it is, then, after this, what gives it away.
GIVES_IT_AWAY = "Gives it away:"


def table_rows(effect_catalog: EffectCatalog | None = None) -> list[tuple[str, str, str, str]]:
    """The catalog as the documentation's table, one row an effect: its name; its options and
    parameters (``"`key` (default `value`)"``, ``"`name` [unit]: low–high (default value)"`` over
    the realistic range, joined by "; "); what it is; what gives it away."""
    effect_catalog = effect_catalog if effect_catalog is not None else catalog()
    rows = []
    for name in effect_catalog.names():
        effect = effect_catalog.make(name)
        what, _, away = effect.description().partition(GIVES_IT_AWAY)
        fields = [f"`{key}` (default `{value}`)" for key, value in effect.options().items()] + [
            f"`{p.name}` [{p.unit}]: {p.realistic_min:g}–{p.realistic_max:g} (default {p.value:g})"
            for p in effect.parameters()
        ]
        rows.append((name, "; ".join(fields), what.strip(), away.strip()))
    return rows


def describe(effect_catalog: EffectCatalog | None = None) -> str:
    """A table of every effect: name, stage, parameters (unit, realistic and plausible ranges,
    the plausible range's source), what gives it away."""
    effect_catalog = effect_catalog if effect_catalog is not None else catalog()
    lines = []
    for name in effect_catalog.names():
        effect = effect_catalog.make(name)
        options = ", ".join(f"{key}={value}" for key, value in effect.options().items())
        parameters = ", ".join(
            f"{p.name}={p.value:g} {p.unit} (realistic {p.realistic_min:g}-{p.realistic_max:g}, "
            f"plausible {p.plausible_min:g}-{p.plausible_max:g})"
            for p in effect.parameters()
        )
        sources = "".join(f"\n    plausible {p.name}: {p.plausible_source}" for p in effect.parameters())
        lines.append(
            f"{name} [{effect.stage().name}]: {', '.join(filter(None, [options, parameters]))}\n"
            f"    {effect.description()}{sources}"
        )
    return "\n".join(lines)
