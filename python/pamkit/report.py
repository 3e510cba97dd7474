"""The diagnosis report as Python users meet it: :func:`diagnose` runs the diagnosis and returns a
:class:`Report`, which wraps the report's JSON document (its keys: the reference's "Diagnosis
report" page) with tables as pandas DataFrames, the verdict sentence, the figure and a notebook
display.
"""

from __future__ import annotations

import copy
import html
import json
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any, Union

from pamkit.io.experiment import Experiment

if TYPE_CHECKING:
    import pandas as pd
    from matplotlib.figure import Figure

    from pamkit._core import EffectCatalog

# What diagnose() takes: an experiment's TOML path or a loaded Experiment, or several of them.
ExperimentLike = Union[str, Path, "Experiment"]

# Values at or beyond these do not name a cause: the report's "cause" is then one of them.
NO_CAUSE = ("none", "unexplained")


class Report:
    """What the model got wrong in measured data, the cause named (or none within the noise), and
    the gain on data the fit never saw.

    Parameters
    ----------
    data : dict
        The report's JSON document, as :meth:`to_dict` returns it and ``pamkit diagnose --json``
        writes it.
    verdict : str, optional
        The one-sentence verdict (the document of a time series holds it as ``"verdict"``).
    diagnosis : object, optional
        The diagnosis the document was made from (``pamkit.diagnosis``'s result), needed to draw
        the figure; a report read from a JSON file has none.

    Examples
    --------
    >>> report = pamkit.diagnose("data/experiments/example/experiment.toml")  # doctest: +SKIP
    >>> report.cause, report.verdict()  # doctest: +SKIP
    >>> report.candidates[["effect", "score", "significant", "credible"]]  # doctest: +SKIP
    """

    def __init__(self, data: dict[str, Any], verdict: str | None = None, diagnosis: object | None = None):
        self._data = data
        self._verdict = verdict if verdict is not None else data.get("verdict")
        self.diagnosis = diagnosis

    @classmethod
    def read_json(cls, path: str | Path) -> Report:
        """Read a report that ``pamkit diagnose --json`` or :meth:`to_json` wrote.

        Parameters
        ----------
        path : str or Path
            The JSON file.

        Returns
        -------
        Report
            The report, without the diagnosis behind it: :meth:`plot` needs a new diagnosis.

        Raises
        ------
        ValueError
            If the file is not JSON or not a diagnosis report, naming the file (and line and column).
        """
        path = Path(path)
        try:
            data = json.loads(path.read_text(encoding="utf-8"))
        except json.JSONDecodeError as error:
            raise ValueError(f"{path}:{error.lineno}:{error.colno}: not JSON: {error.msg}") from None
        if not isinstance(data, dict) or "cause" not in data:
            raise ValueError(f"{path}: not a pamkit diagnosis report (no 'cause' key)")
        return cls(data)

    @property
    def kind(self) -> str:
        """What was diagnosed: ``"series"`` (one time series), a table kind (``"isometric_map"``,
        ``"isotonic"``, ``"free_inflation"``) or ``"campaign"`` (several time series of one muscle)."""
        return str(self._data.get("kind", "series"))

    @property
    def cause(self) -> str:
        """The effect named, or ``"none"`` (the model explains the data to within its noise) or
        ``"unexplained"`` (structure is left that no credible catalog effect explains)."""
        return str(self._data["cause"])

    @property
    def channels(self) -> list[str]:
        """The measured channels the diagnosis compared, as the report's document names them (its
        ``<channel>`` keys: the reference's "Diagnosis report" page)."""
        return list(self._data["baseline"]["rmse"]) if "rmse" in self._data.get("baseline", {}) else []

    def verdict(self) -> str:
        """The verdict: one sentence naming the cause and its held-out gain, or why none is named.

        Raises
        ------
        ValueError
            For a report read from a JSON document that holds no verdict (a static table's or a
            campaign's written by ``pamkit diagnose --json``).
        """
        if self._verdict is None:
            raise ValueError("this report holds no verdict sentence (its JSON document has no 'verdict' key)")
        return self._verdict

    def to_dict(self) -> dict[str, Any]:
        """The report's JSON document (a copy): the keys the reference's "Diagnosis report" page defines."""
        return copy.deepcopy(self._data)

    def to_json(self, path: str | Path | None = None) -> str:
        """The report as indented JSON text, written to `path` too if given.

        Parameters
        ----------
        path : str or Path, optional
            Where to write it (folders are made).

        Returns
        -------
        str
            The JSON text.
        """
        text = json.dumps(self._data, indent=2, default=float) + "\n"
        if path is not None:
            Path(path).parent.mkdir(parents=True, exist_ok=True)
            Path(path).write_text(text, encoding="utf-8")
        return text

    def plot(self, path: str | Path) -> Path:
        """Write the report's figure: measured, baseline and extended model per channel (time
        series) or per held length or row (tables), the residuals, the candidates' ranking.

        Parameters
        ----------
        path : str or Path
            The image to write; matplotlib infers the format from its suffix (``.png``, ``.pdf``).

        Returns
        -------
        Path
            The path written.

        Raises
        ------
        ValueError
            For a report read from JSON (the figure needs the diagnosis's predictions).
        """
        from pamkit.diagnosis.report import plot  # imported here: see diagnose()

        return plot(self._drawable(), path)  # type: ignore[arg-type]

    def write_next_test(self, path: str | Path) -> list[Path]:
        """Write the test this report asks for (:attr:`separation`: to tell a tie apart, confirm a
        close cause, check for an instrument's error) as an experiment file to run: at `path` the
        test's own sections with ``[test]`` changed as the variant says, beside it the motion to
        run (its CSV, which the lab's data then replace) and what each of the two explanations
        predicts it will measure (``.predictions.csv``); for a zero run, the predictions only.

        Parameters
        ----------
        path : str or Path
            The experiment TOML to write (``NEXT.toml``).

        Returns
        -------
        list of Path
            The files written.

        Raises
        ------
        ValueError
            Where the report asks for no test or none it could run separates the two (saying
            why), for a campaign's or a table's report, and for a report read from JSON.
        """
        from pamkit.diagnosis.series.next_test import write_next_test  # imported here: see diagnose()

        return write_next_test(self._drawable(), path)

    def figure(self) -> Figure:
        """The report's figure, as `plot` writes it, to look at where the session draws: a
        notebook shows it inline, a script with ``matplotlib.pyplot.show()``.

        Returns
        -------
        matplotlib.figure.Figure
            Open in pyplot (close it with ``matplotlib.pyplot.close``).

        Raises
        ------
        ValueError
            For a report read from JSON (the figure needs the diagnosis's predictions).
        """
        from pamkit.diagnosis.report import figure  # imported here: see diagnose()

        return figure(self._drawable())  # type: ignore[arg-type,no-any-return]

    def _drawable(self) -> object:
        """The diagnosis a figure is drawn from; a report read from JSON has none."""
        if self.diagnosis is None:
            raise ValueError("a report read from JSON holds no predictions to draw: diagnose the data again")
        return self.diagnosis

    @property
    def candidates(self) -> pd.DataFrame:
        """Every candidate effect, as ranked: one row each.

        Columns: ``effect``, ``score`` (the combined held-out gain), ``significant``, ``credible``
        and the rest of the document's candidate entries flattened with dots (``gain.<channel>``
        and ``heldout_rmse.<channel>`` for each measured channel, ``params.time_constant_s``, ...).
        A campaign's rows are each effect carried to each test (``test``, ``params.<parameter>``,
        ``gain``, ``carries``).
        """
        import pandas as pd  # imported where a table is built: it adds a sixth of a second to every start

        if self.kind == "campaign":
            rows = [
                {"effect": effect, **entry}
                for effect, entries in self._data.get("carried", {}).items()
                for entry in entries
            ]
            return pd.json_normalize(rows) if rows else pd.DataFrame(columns=["effect", "test"])
        rows = self._data.get("candidates", [])
        return pd.json_normalize(rows) if rows else pd.DataFrame(columns=["effect", "score"])

    @property
    def causes(self) -> pd.DataFrame:
        """The causes the report names, one row each (empty when the cause is ``none`` or
        ``unexplained``): the document's ``causes`` entries flattened with dots where it has
        them, otherwise the candidates' rows of the effects its extended model holds."""
        import pandas as pd  # imported where a table is built: it adds a sixth of a second to every start

        if "causes" in self._data:
            entries: list[dict[str, Any]] = self._data["causes"]
            return pd.json_normalize(entries) if entries else pd.DataFrame(columns=["effect"])
        if self.cause in NO_CAUSE:
            return self.candidates.iloc[0:0]
        named = set((self._data.get("extended") or {}).get("effects", [self.cause]))
        candidates = self.candidates
        rows = candidates[candidates["effect"].isin(named)].reset_index(drop=True)
        return rows.dropna(axis=1, how="all")  # the other candidates' parameters

    @property
    def separation(self) -> dict[str, Any] | None:
        """The test that would tell apart what this one could not, or None (a copy of the
        document's ``separation``): its ``purpose`` (``tie``: two candidates explain the data
        alike; ``confirm``: the cause named is only narrowly ahead of ``between[1]``; ``check``: an
        instrument's error the data did not need), ``between`` (the two models), ``test`` (the
        variant, in SI) and how far apart the two models are there and on this test, over each
        channel's noise. A time series' report only."""
        value = self._data.get("separation")
        return copy.deepcopy(value) if value else None

    @property
    def declared_build(self) -> dict[str, Any] | None:
        """Where a correction of a sealed test's pressure transducer is named, the baseline
        calibrated again with the declared length and diameter free within what a rule and calipers
        read, or None (a copy of the document's ``declared_build``): the fields ``freed``, their
        ``declared`` values and the ``values`` they took [m] (``at_tolerance``: those at the edge of
        their tolerance), its held-out ``gain`` beside the causes' (``causes_gain``), and
        ``explains_as_well``: the data then do not tell the transducer from the declared build, and
        nothing is named. A time series' report only."""
        value = self._data.get("declared_build")
        return copy.deepcopy(value) if value else None

    @property
    def channels_summary(self) -> pd.DataFrame:
        """One row per channel: the noise, the calibrated baseline's and the extended model's
        held-out RMSE (in the channel's unit), the gain and its 95 % interval, where the
        document gives them."""
        import pandas as pd  # imported where a table is built: it adds a sixth of a second to every start

        data = self._data
        baseline = data.get("baseline") or {}
        extended = data.get("extended") or {}
        noise = (data.get("evidence") or {}).get("noise") or data.get("noise") or {}
        # A time series' "rmse" is held out; a table gives both and names the held-out one.
        baseline_rmse = baseline.get("heldout_rmse", baseline.get("rmse", {}))
        extended_rmse = extended.get("heldout_rmse", extended.get("rmse", {}))
        gain = data.get("gain") or {}
        interval = data.get("gain_ci95") or {}
        rows = {
            channel: {
                "noise": noise.get(channel),
                "baseline_rmse": baseline_rmse.get(channel),
                "extended_rmse": extended_rmse.get(channel),
                "gain": gain.get(channel),
                "gain_ci95": interval.get(channel),
            }
            for channel in baseline_rmse
        }
        return pd.DataFrame(rows).transpose()

    def _repr_html_(self) -> str:
        verdict = html.escape(self._verdict) if self._verdict is not None else ""
        parts = [
            "<div>",
            f"<p><b>pamkit diagnosis</b> ({html.escape(self.kind)}): cause <code>{html.escape(self.cause)}</code></p>",
            f"<p>{verdict}</p>" if verdict else "",
            self.channels_summary.to_html(float_format=lambda x: f"{x:.4g}") if self.channels else "",
        ]
        candidates = self.candidates
        if len(candidates):
            shown = [c for c in ("effect", "test", "score", "significant", "credible", "carries") if c in candidates]
            parts.append(
                f"<details><summary>{len(candidates)} candidates</summary>"
                f"{candidates[shown].to_html(index=False, float_format=lambda x: f'{x:.4g}')}</details>"
            )
        parts.append("</div>")
        return "".join(parts)

    def __repr__(self) -> str:
        return f"<pamkit.Report {self.kind}: {self._verdict if self._verdict is not None else self.cause}>"


def diagnose(
    path_or_experiments: ExperimentLike | Sequence[ExperimentLike],
    effect_catalog: EffectCatalog | None = None,
    progress: Callable[[str], None] | None = None,
    threads: int | None = None,
    seed: int | None = None,
) -> Report:
    """Diagnose measured data: show what the simulation gets wrong, name the cause, extend the
    model and measure the gain on the units (cycles, sweeps, held lengths, rows) it was not
    fitted to.

    Parameters
    ----------
    path_or_experiments : str or Path or Experiment, or a sequence of them
        An experiment (its TOML path or a loaded :class:`pamkit.Experiment`), a campaign TOML,
        or several experiments of one muscle (a campaign).
    effect_catalog : EffectCatalog, optional
        The effects to try (default: the built-in catalog, :func:`pamkit.effects.catalog`; add
        your own with ``catalog.add``).
    progress : callable, optional
        Called with a message (str) as work proceeds (default: silent).
    threads : int, optional
        Fits run in parallel (default: every core).
    seed : int, optional
        Seeds the bootstrap (default: drawn from the data, so that the same data give the same
        report).

    Returns
    -------
    Report
        The report: :meth:`Report.verdict`, :attr:`Report.cause`, :attr:`Report.candidates`,
        :attr:`Report.causes`, :meth:`Report.to_json`, :meth:`Report.plot`.

    Raises
    ------
    ExperimentError
        (a ValueError) for a file that cannot be read or data that cannot be diagnosed, naming
        the file (and row and column).

    Examples
    --------
    >>> report = pamkit.diagnose("data/experiments/festo/DMSP-10-250.toml")  # doctest: +SKIP
    >>> print(report.verdict())  # doctest: +SKIP
    """
    # Imported here: `import pamkit` (and `pamkit simulate`) starts without the diagnosis package.
    from pamkit.diagnosis.engine import diagnose as run
    from pamkit.diagnosis.report import to_json, verdict

    what: ExperimentLike | list[ExperimentLike]
    if isinstance(path_or_experiments, (str, Path, Experiment)):
        what = path_or_experiments
    else:
        what = list(path_or_experiments)
    diagnosis = run(what, effect_catalog, progress=progress, threads=threads, seed=seed)
    return Report(to_json(diagnosis), verdict(diagnosis), diagnosis)
