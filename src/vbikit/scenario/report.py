"""The report of one crossing: what ``vbikit run`` prints, writes and plots, as a Python object."""
from __future__ import annotations

import csv
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from vbikit.analysis.effects import LoadEffectResponse
from vbikit.analysis.plan import ResponsePlan
from vbikit.analysis.response import PointResponse, history_table
from vbikit.solve.result import CrossingResult

if TYPE_CHECKING:  # pragma: no cover
    import pandas as pd
    import xarray as xr


@dataclass(frozen=True)
class Report:
    """A finished crossing and its reduction (build with [`vbikit.run`][vbikit.scenario.run]).

    Attributes
    ----------
    name : str
        The scenario's name ("" if none).
    result : CrossingResult
        The histories of the coupled solve.
    plan : ResponsePlan
        The response points and load effects read from it.
    points : list of PointResponse
        Dynamic and static histories at every response point (``plan.points`` order).
    girders : list of PointResponse
        Per-girder histories at the headline point's section (slab-on-girder decks; else empty).
    effects : list of LoadEffectResponse
        Moment, shear and reaction histories.
    summary : dict
        Exactly what ``vbikit run --json`` prints (keys and units: docs/results.md).
    """

    name: str
    result: CrossingResult
    plan: ResponsePlan
    points: list[PointResponse]
    girders: list[PointResponse] = field(default_factory=list)
    effects: list[LoadEffectResponse] = field(default_factory=list)
    summary: dict[str, Any] = field(default_factory=dict)

    @property
    def response(self) -> PointResponse:
        """The headline (first) response point's histories."""
        return self.points[0]

    @property
    def warnings(self) -> list[str]:
        return list(self.summary.get("warnings", []))

    def histories(self) -> dict[str, tuple[NDArray[np.float64], str]]:
        """Every CSV column: name → (values, unit) ([`vbikit.analysis.response.history_table`][vbikit.analysis.history_table])."""
        return history_table(self.result, self.points, self.girders, self.effects, self.plan.point_names)

    def write_csv(self, path: str | Path) -> Path:
        """Write [`histories`][vbikit.scenario.Report.histories] as CSV, headers ``name [unit]``, 9 significant digits (atomically)."""
        from vbikit._files import atomic_write

        table = self.histories()

        def write(tmp: Path) -> None:
            with tmp.open("w", newline="") as fh:
                writer = csv.writer(fh)
                writer.writerow([f"{name} [{unit}]" for name, (_, unit) in table.items()])
                for row in np.column_stack([v for v, _ in table.values()]):
                    writer.writerow([f"{v:.9g}" for v in row])

        atomic_write(Path(path), write)
        return Path(path)

    def write_summary(self, path: str | Path) -> Path:
        """Write ``summary`` as indented strict JSON (atomically)."""
        from vbikit._files import json_text, write_text

        write_text(Path(path), json_text(self.summary, 2) + "\n")
        return Path(path)

    def to_xarray(self, static: bool = True) -> "xr.Dataset":
        """The crossing as a labelled dataset ([`CrossingResult.to_xarray`][vbikit.solve.CrossingResult.to_xarray]) at the report's
        response points (coordinate ``point``: their names, as in the CSV) and girder sections, with the
        load-effect histories (``<name>``, ``<name>_static``): the CSV's names and units; the run's flags in its
        attributes ``flags`` (records, JSON), ``warnings`` and ``flag_codes``, as every dataset carries them
        (``vbikit.analysis.checks.summary_flag_attrs``), so the dataset alone says which values are in doubt."""
        from vbikit.analysis.checks import summary_flag_attrs

        ds = self.result.to_xarray([(p.x, p.y) for p in self.points], girder_x=self.plan.first.x, static=static,
                                   names=self.plan.point_names, effects=self.effects)
        ds.attrs.update(summary_flag_attrs(self.summary))
        return ds

    def to_dataframe(self, static: bool = True) -> "pd.DataFrame":
        """The histories as a wide pandas DataFrame ([`CrossingResult.to_dataframe`][vbikit.solve.CrossingResult.to_dataframe]):
        every column of the CSV ([`histories`][vbikit.scenario.Report.histories]) under the same header."""
        return self.result.to_dataframe([(p.x, p.y) for p in self.points], girder_x=self.plan.first.x, static=static,
                                        names=self.plan.point_names, effects=self.effects)

    def plot(self, path: str | Path) -> Path:
        """Figure of the displacement, strain and acceleration at every response point, dynamic
        against static, and the tire forces."""
        from vbikit.plot import plot_crossing

        return plot_crossing(self.result, self.points, path, names=self.plan.point_names)
