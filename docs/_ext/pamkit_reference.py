"""A Sphinx directive that writes the reference's generated tables from pamkit itself, so that they
cannot drift from the code: ``.. pamkit-reference:: NAME`` with NAME one of

    experiment-file   every section and key of an experiment file (pamkit.reference.experiment_keys)
    data-columns      the data CSV's columns of each kind of test (pamkit.reference.data_columns)
    params-file       every key of a muscle-parameters file (pamkit.reference.params_file_keys)
    effect-catalog    every effect of the built-in catalog, with its parameters (pamkit.effects.catalog)
    effect-table      the same catalog as one table: parameters, what each effect is, what gives it away
    effect-gallery    each effect's gallery figure with its caption (validation/effects_gallery.py)
    cli               every command's --help (pamkit.cli.command_help)
    templates         `pamkit template KIND` of each kind (pamkit.templates.template)

The tables are written as reStructuredText and parsed in place.
"""

from __future__ import annotations

import importlib.util
from pathlib import Path

from docutils import nodes
from docutils.statemachine import StringList
from sphinx.util.docutils import SphinxDirective
from sphinx.util.nodes import nested_parse_with_titles

from pamkit import reference
from pamkit.cli import command_help
from pamkit.effects import catalog, table_rows
from pamkit.templates import TEMPLATE_KINDS, template


def _cell(text: str) -> str:
    return " ".join(str(text).split()) or " "


def _table(header: list[str], rows: list[list[str]], widths: str = "auto") -> list[str]:
    lines = [".. list-table::", "   :header-rows: 1", f"   :widths: {widths}", ""]
    for row in [header, *rows]:
        lines.append(f"   * - {_cell(row[0])}")
        lines += [f"     - {_cell(cell)}" for cell in row[1:]]
    return lines + [""]


def _kinds(kinds: tuple[str, ...]) -> str:
    return "all" if set(kinds) == set(reference.KINDS) else ", ".join(kinds) or "none"


def experiment_file() -> list[str]:
    lines: list[str] = []
    keys = reference.experiment_keys()
    for section in ("muscle", "bladder", "friction", "gas", "calibrate", "uncertain", "test", "campaign"):
        title = f"[{section}]"
        lines += [title, "-" * len(title), ""]
        rows = [
            [
                f"``{key.name}``",
                key.unit or "",
                key.default or "",
                key.allowed or "",
                _kinds(key.required) if key.required else "",
                _kinds(key.kinds),
                key.meaning,
            ]
            for key in keys
            if key.section == section
        ]
        lines += _table(["key", "unit", "default", "allowed", "required by", "taken by", "meaning"], rows)
    return lines


def data_columns() -> list[str]:
    lines: list[str] = []
    for kind in reference.KINDS:
        title = f"{kind}"
        lines += [title, "-" * len(title), "", reference.KIND_MEANINGS[kind] + ".", ""]
        rows = [
            [
                f"``{c.name}``",
                c.unit,
                "required" if c.required else "optional",
                f"``{c.si_name}`` [{c.si_unit}]",
                c.meaning,
            ]
            for c in reference.data_columns(kind)
        ]
        lines += _table(["column", "unit", "", "in Python (SI)", "meaning"], rows)
    return lines


def params_file() -> list[str]:
    lines: list[str] = []
    keys = reference.params_file_keys()
    for section in ("build", "bladder", "friction", "gas", "extensions", "initial", "rig"):
        title = f"[{section}]"
        lines += [title, "-" * len(title), ""]
        rows = [
            [f"``{k.name}``", k.unit, k.allowed, "required" if k.required else "see meaning", k.meaning]
            for k in keys
            if k.section == section
        ]
        lines += _table(["key", "unit", "allowed", "", "meaning"], rows)
    return lines


def effect_catalog() -> list[str]:
    effects = catalog()
    lines: list[str] = []
    for name in effects.names():
        effect = effects.make(name)
        lines += [f"``{name}``", "-" * (len(name) + 4), ""]
        lines += [f"*Acts on:* {effect.stage().name}. " + _cell(effect.description()), ""]
        signature = effect.signature()
        if signature:
            lines += [f"*What gives it away:* {_cell(signature.format(channel='the channel'))}.", ""]
        options = effect.options()
        if options:
            lines += ["*Options:* " + ", ".join(f"``{k}`` (default ``{v}``)" for k, v in options.items()), ""]
        rows = [
            [
                f"``{p.name}``",
                p.unit,
                f"{p.value:g}",
                f"{p.realistic_min:g} – {p.realistic_max:g}",
                f"{p.plausible_min:g} – {p.plausible_max:g}",
                p.plausible_source,
            ]
            for p in effect.parameters()
        ]
        if rows:
            lines += _table(
                ["parameter", "unit", "default", "realistic", "plausible", "source of the plausible range"], rows
            )
    return lines


def effect_table() -> list[str]:
    rows = [
        [f"``{name}``", fields.replace("`", "``") or "none", what, away] for name, fields, what, away in table_rows()
    ]
    return _table(["name", "parameters", "what it is", "what gives it away"], rows, "15 25 35 25")


GALLERY = Path(__file__).resolve().parents[2] / "validation" / "effects_gallery.py"


def effect_gallery() -> list[str]:
    spec = importlib.util.spec_from_file_location("effects_gallery", GALLERY)
    gallery = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(gallery)
    lines: list[str] = []
    for name in catalog().names():
        lines += [
            f"**{name}** — {_cell(gallery.caption(name))}",
            "",
            f".. image:: effects/{name}.png",
            f"   :alt: {name}",
            "",
        ]
    return lines


def cli() -> list[str]:
    lines: list[str] = []
    for name, text in command_help():
        lines += [f"``{name}``", "-" * (len(name) + 4), "", ".. code-block:: text", ""]
        lines += ["   " + line if line else "" for line in text.splitlines()]
        lines.append("")
    return lines


def templates() -> list[str]:
    lines: list[str] = []
    for kind in TEMPLATE_KINDS:
        title = f"pamkit template {kind}"
        lines += [title, "-" * len(title), "", ".. code-block:: toml", ""]
        lines += ["   " + line if line else "" for line in template(kind).splitlines()]
        lines.append("")
    return lines


GENERATORS = {
    "experiment-file": experiment_file,
    "data-columns": data_columns,
    "params-file": params_file,
    "effect-catalog": effect_catalog,
    "effect-table": effect_table,
    "effect-gallery": effect_gallery,
    "cli": cli,
    "templates": templates,
}


class PamkitReference(SphinxDirective):
    required_arguments = 1

    def run(self) -> list[nodes.Node]:
        name = self.arguments[0]
        if name not in GENERATORS:
            raise self.error(f"pamkit-reference: unknown table {name!r} (known: {', '.join(GENERATORS)})")
        container = nodes.section()
        container.document = self.state.document
        nested_parse_with_titles(
            self.state, StringList(GENERATORS[name](), source=f"<pamkit-reference {name}>"), container
        )
        return container.children


def setup(app):
    app.add_directive("pamkit-reference", PamkitReference)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
