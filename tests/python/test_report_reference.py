"""docs/reference/report.md against the reports the diagnosis writes: every key of a time series',
a static table's and a campaign's JSON document is one the page defines. The page's key columns
are read as patterns (`<channel>` stands for a measured channel, `<name>` for any other key, `[]`
for each entry of a list); a key no pattern matches fails the test with its path.

The page names a channel as the data file does (`pressure_kPa`); a report may name it so or by
its SI name inside pamkit (`gauge_pressure_Pa`), and either matches `<channel>`, so that the page
documents a channel's key once, whichever name the report's writer gives it. Nothing else does:
a key where a channel goes that is no channel's name in either form is undocumented."""

from __future__ import annotations

import json
import os
import re
import shutil
from pathlib import Path

import pytest

import pamkit
from pamkit.diagnosis.tables.kinds import PREDICTED
from pamkit.io.columns import file_name

SOURCE_DIR = Path(os.environ.get("PAMKIT_SOURCE_DIR", Path(__file__).resolve().parents[2]))
PAGE = SOURCE_DIR / "docs" / "reference" / "report.md"
EXPERIMENTS = SOURCE_DIR / "data" / "experiments"


def tokens(pattern: str) -> tuple[str, ...]:
    """`candidates[].gain.<channel>` -> ("candidates", "[]", "gain", "<channel>")."""
    return tuple(part for piece in pattern.split(".") for part in re.split(r"(\[\])", piece) if part)


def documented() -> dict[str, set[tuple[str, ...]]]:
    """The page's key patterns, section by section."""
    sections: dict[str, set[tuple[str, ...]]] = {}
    current = None
    for line in PAGE.read_text().splitlines():
        if line.startswith("## "):
            current = line[3:].strip()
            sections[current] = set()
        match = re.match(r"\| `([^`]+)` \|", line)
        if match and current is not None:
            sections[current].add(tokens(match.group(1)))
    return sections


# The measured channels, by the name a data file gives each and by its SI name inside pamkit: a
# time series' (declared once, in C++), and what a static table's diagnosis predicts.
CHANNEL = "<channel>"
CHANNELS = {name for channel in pamkit.measured_channels() for name in (channel, file_name(channel))} | {
    channel for channels in PREDICTED.values() for channel in channels
}


def matches(path: tuple[str, ...], pattern: tuple[str, ...]) -> bool:
    """Whether a key's path is the pattern's: `<channel>` a measured channel's name, any other
    `<name>` any key, anything else itself."""
    return len(path) == len(pattern) and all(
        p == q or (p in CHANNELS if q == CHANNEL else q.startswith("<")) for p, q in zip(path, pattern)
    )


def undocumented(value, patterns: set[tuple[str, ...]], path: tuple[str, ...] = ()) -> list[str]:
    """The paths in `value` (a JSON document) that no pattern defines: a key is defined by a
    pattern it matches, or descended into where longer patterns go on from it."""
    found = []
    children = []
    if isinstance(value, dict):
        children = [(path + (str(key),), child) for key, child in value.items()]
    elif isinstance(value, list) and any(isinstance(item, dict) for item in value):
        children = [(path + ("[]",), item) for item in value]
    for child_path, child in children:
        deeper = [p for p in patterns if len(p) > len(child_path) and matches(child_path, p[: len(child_path)])]
        if deeper:
            found += undocumented(child, patterns, child_path)
        elif not any(matches(child_path, p) for p in patterns):
            found.append(".".join(child_path).replace(".[]", "[]"))
    return found


@pytest.fixture(scope="module")
def pages():
    sections = documented()
    discovered = sections["Discovered terms"]
    series = sections["A time series"] | discovered
    return {
        "series": series,
        "table": sections["A static table"] | discovered,
        "campaign": sections["A campaign of time series"] | {("per_test", "[]", *p) for p in series},
    }


def check(report: pamkit.Report, patterns) -> None:
    document = json.loads(report.to_json())  # as written: what a reader of the file meets
    missing = sorted(set(undocumented(document, patterns)))
    assert not missing, f"keys the report page does not define: {missing}"


def test_a_time_series_report_is_documented(pages):
    check(pamkit.diagnose(EXPERIMENTS / "example" / "experiment.toml", threads=2), pages["series"])


def test_a_supplied_time_series_report_is_documented(pages):
    check(pamkit.diagnose(EXPERIMENTS / "supplied" / "isometric_sweep.toml", threads=2), pages["series"])


@pytest.mark.parametrize(
    "tests",
    [
        ["festo/DMSP-10-250.toml"],
        ["isotonic/isotonic.toml"],
        ["thesis/table_3_4_pam1.toml", "thesis/table_3_4_pam2.toml"],  # unexplained: discovered terms, a data check
    ],
)
def test_a_static_table_report_is_documented(pages, tests):
    check(pamkit.diagnose([EXPERIMENTS / t for t in tests], threads=2), pages["table"])


def test_a_campaign_report_is_documented(pages, tmp_path):
    for name in ("a", "b"):  # two tests of the one muscle of the bundled example
        shutil.copy(EXPERIMENTS / "example" / "experiment.csv", tmp_path / "experiment.csv")
        (tmp_path / f"{name}.toml").write_text((EXPERIMENTS / "example" / "experiment.toml").read_text())
    report = pamkit.diagnose([tmp_path / "a.toml", tmp_path / "b.toml"], threads=2)
    assert report.kind == "campaign"
    check(report, pages["campaign"])


def test_an_undocumented_key_is_caught(pages):
    # The check itself: a key the page does not define is reported with its path.
    document = {"cause": "none", "decision": {"margins": {"significance": 0.1}, "new_key": 1}}
    assert undocumented(document, pages["series"]) == ["decision.new_key"]
    assert undocumented({"candidates": [{"effect": "leak", "novel": 2}]}, pages["series"]) == ["candidates[].novel"]


def test_a_channel_is_documented_by_either_of_its_names(pages):
    # The page documents `baseline.rmse.<channel>` once: the file's name of a channel and its SI
    # name both match it, and a key that is neither is caught.
    assert {"pressure_kPa", "gauge_pressure_Pa", "temperature_C", "temperature_K", "force_N"} <= CHANNELS
    for pressure in ("pressure_kPa", "gauge_pressure_Pa"):
        document = {"baseline": {"rmse": {"force_N": 1.0, pressure: 2.0}}, "gain": {pressure: 0.5}}
        assert undocumented(document, pages["series"]) == []
    document = {"baseline": {"rmse": {"pressure_psi": 2.0}}, "evidence": {"noise": {"stroke": 0.1}}}
    assert undocumented(document, pages["series"]) == ["baseline.rmse.pressure_psi", "evidence.noise.stroke"]
    # A table's channels are its own: the free-inflation table's diameter_m.
    assert undocumented({"noise": {"diameter_m": 1e-4}}, pages["table"]) == []
