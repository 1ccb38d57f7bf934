"""A study with ``method = "pem"``: one pseudo-excitation analysis per cell (``vbikit.random``).

Where a Monte-Carlo study runs one crossing per sampled road and leaves the statistics over the
``sample`` dimension to the user, a PEM study runs, for every combination of its axes (no
``road.seed`` axis), the random-vibration analysis of ``vbikit run --random``
(``vbikit.scenario.pipeline.run_random``) and stores the impact factor's distribution over the
random road at the headline response point — mean, standard deviation, quantiles and the mean's
sampling error — and of the first bending moment of the response plan (by the plan's
``load_effect_method``, mode acceleration by default, ``vbikit.random.response``), with the
lift-off probability and the wavenumber grid check that say whether the linear theory holds.
It runs on ``vbikit.study.run.run_study``'s machinery as a job (one cell a batch: resumable,
local processes or Dask).
"""
from __future__ import annotations

import itertools
import json
from typing import Any, Optional

import numpy as np
from numpy.typing import NDArray

from vbikit.study.spec import Study

#: what a PEM cell stores: name -> (summary key path, units, long name); scalars per cell
PEM_OUTPUTS: dict[str, tuple[tuple[str, ...], str, str]] = {
    "impact_factor_mean": (("impact_factor_mean",), "1", "mean impact factor over the random road (PEM)"),
    "impact_factor_std": (("impact_factor_std",), "1", "standard deviation of the impact factor (PEM)"),
    "impact_factor_sampling_error": (("impact_factor_sampling_error",), "1",
                                     "sampling error of the mean impact factor (Gaussian histories with PEM's covariance)"),
    "moment_impact_factor_mean": (("effects", "moment", "impact_factor_mean"), "1",
                                  "mean impact factor of the first bending moment (the plan's load-effect method, PEM)"),
    "moment_impact_factor_std": (("effects", "moment", "impact_factor_std"), "1",
                                 "standard deviation of the first bending moment's impact factor (PEM)"),
    "lift_off_probability": (("lift_off_probability",), "1", "largest probability of a tire lifting off at one instant"),
    "grid_change": (("grid_change",), "1", "wavenumber grid check: σ on every vs every second line"),
}
#: the axes whose cells share a batch: the road's level (the PSD times a factor; ``run_random_levels``)
LEVEL_KEYS = ("road.class",)
#: outputs that may be NaN (a plan without a moment)
OPTIONAL = ("moment_impact_factor_mean", "moment_impact_factor_std")


def pem_dataset_flags(data: dict[str, NDArray], axes) -> list:
    """The single ``vbikit run --random``'s quality flags over a PEM study's cells
    (``vbikit.random.response.QUALITY_RULES``: ``lift_off``, ``coarse_grid``, the same rules and
    limits): one flag per code naming how many cells, and the worst cell with its value."""
    from vbikit.analysis.checks import Flag
    from vbikit.random.response import QUALITY_RULES

    flags = []
    for code, key, limit, finding, advice in QUALITY_RULES:
        values = np.atleast_1d(np.asarray(data[key], float))
        n_over = int(np.sum(values > limit))
        if not n_over:
            continue
        worst_at = np.unravel_index(int(np.nanargmax(values)), values.shape)
        worst = float(values[worst_at])
        cell = ", ".join(f"{a.key} = {a.values[i]}" for a, i in zip(axes, worst_at)) or "the study's one cell"
        flags.append(Flag(code, f"{n_over} of {values.size} cells: {finding.format(value=worst, limit=limit)} in the "
                          f"worst cell, {cell}" + (f": {advice}" if advice else ""),
                          output=key, subject=f"{n_over} cells", value=worst, threshold=limit))
    return flags


def _value(summary: dict[str, Any], path: tuple[str, ...]) -> float:
    if path[0] == "effects":
        first = next((e for e in summary["effects"] if e["kind"] == path[1]), None)
        return float("nan") if first is None else float(first[path[2]])
    return float(summary[path[0]])


class PemStudy:
    """``study`` (``method = "pem"``) as a job of ``run_study``: one cell a batch."""

    def __init__(self, study: Study) -> None:
        from vbikit.random.response import QUANTILES

        self.study = study
        self.quantiles = QUANTILES

    @property
    def name(self) -> str:
        return self.study.name

    @property
    def axes(self):
        return self.study.axes

    @property
    def size(self) -> int:
        return self.study.size

    def to_json(self) -> str:
        return self.study.to_json()

    def earlier_json(self) -> tuple[str, ...]:
        return self.study.earlier_json()

    def scenario_dict(self, index: tuple[int, ...]) -> dict[str, Any]:
        return self.study.scenario_dict(index)

    def batches(self) -> list[tuple[tuple[int, ...], ...]]:
        """One batch per combination of the axes other than ``road.class`` (``LEVEL_KEYS``), holding
        that axis's cells: they differ only in the road's level, so they share one pseudo-excitation
        (``run_random_levels``)."""
        sizes = [len(a.values) for a in self.axes]
        level = [k for k, a in enumerate(self.axes) if a.key in LEVEL_KEYS]
        other = [range(n) if k not in level else range(1) for k, n in enumerate(sizes)]
        out = []
        for idx in itertools.product(*other):
            cells = itertools.product(*(range(sizes[k]) if k in level else (i,) for k, i in enumerate(idx)))
            out.append(tuple(cells))
        return out

    def run_batch(self, batch: tuple[tuple[int, ...], ...], threads: int = 1) -> dict[str, NDArray]:
        """Every cell of ``batch`` as ``run_random`` gives it (``run_random_levels``: one
        pseudo-excitation for cells that differ only in the road's level): arrays (cells,) of
        ``PEM_OUTPUTS`` and ``impact_factor_quantiles`` (cells, quantiles)."""
        from vbikit.scenario.pipeline import run_random_levels

        out: dict[str, list] = {name: [] for name in PEM_OUTPUTS} | {"impact_factor_quantiles": []}
        runs = run_random_levels([self.study.scenario_dict(idx) for idx in batch], base_dir=self.study.base_dir,
                                 quantiles=self.quantiles, peaks="study")  # the channels PEM_OUTPUTS reads, no cross-check
        for rr in runs:
            s = rr.summary
            for name, (path, _, _) in PEM_OUTPUTS.items():
                out[name].append(_value(s, path))
            out["impact_factor_quantiles"].append([s["impact_factor_quantiles"][f"{q:g}"] for q in self.quantiles])
        arrays = {k: np.array(v, float) for k, v in out.items()}
        arrays["index"] = np.array(batch, np.int64).reshape(len(batch), len(self.axes))
        return arrays

    def part_problem(self, part: Any, batch: tuple) -> Optional[str]:
        """Why a stored part cannot be used (None if it can)."""
        index = part["index"]
        if index.shape != (len(batch), len(self.axes)) or not np.array_equal(
                index, np.array(batch, np.int64).reshape(len(batch), len(self.axes))):
            return "its grid indices are not those of this batch"
        for name in (*PEM_OUTPUTS, "impact_factor_quantiles"):
            if name not in part:
                return f"it holds no {name}"
            want = (len(batch), len(self.quantiles)) if name == "impact_factor_quantiles" else (len(batch),)
            if part[name].shape != want:
                return f"{name} has the wrong shape"
            if name not in OPTIONAL and not np.all(np.isfinite(part[name])):
                return f"{name} is not finite"
        return None

    def assemble(self, parts):
        """The Dataset: every output over the axes' dimensions (quantiles also over ``quantile``)."""
        import xarray as xr

        from vbikit._version import __version__
        from vbikit.scenario.schema import key_unit
        from vbikit.study.spec import cf_key_unit
        from vbikit.study.storage import load_part, part_checksums

        shape = self.study.shape
        dims = [a.name for a in self.axes]
        data = {name: np.full(shape, np.nan) for name in PEM_OUTPUTS}
        quant = np.full(shape + (len(self.quantiles),), np.nan)
        sums = part_checksums(parts)
        for k, batch in enumerate(self.batches()):
            part = load_part(parts, k, sums)
            idx = tuple(part["index"].T) if shape else ()
            for name in data:
                data[name][idx] = part[name] if shape else part[name][0]
            quant[idx] = part["impact_factor_quantiles"] if shape else part["impact_factor_quantiles"][0]
        variables = {name: (dims, data[name], {"units": units, "long_name": long})
                     for name, (_, units, long) in PEM_OUTPUTS.items()}
        variables["impact_factor_quantiles"] = ([*dims, "quantile"], quant, {
            "units": "1", "long_name": "quantiles of the impact factor over the random road (PEM)"})
        coords: dict[str, Any] = {"quantile": ("quantile", np.array(self.quantiles), {"units": "1"})}
        for a in self.axes:
            values = a.coordinate_values
            text = isinstance(values[0], str)
            coords[a.name] = (a.name, np.array(values, dtype=object) if text else np.array(values),
                              {"scenario_key": a.key, "units": cf_key_unit(key_unit(a.key), text),
                               "long_name": f"scenario key {a.key}"})
        from vbikit.analysis.checks import dataset_flag_attrs

        attrs = {"title": self.name or "vbikit study", "study": self.to_json(), "method": "pem",
                 "vbikit_version": __version__, "axes": json.dumps({a.name: a.key for a in self.axes}), "Conventions": "CF-1.8",
                 **dataset_flag_attrs(pem_dataset_flags(data, self.axes))}
        return xr.Dataset(variables, coords=coords, attrs=attrs)

