"""What a study's dataset says along each swept axis: the mean of an output by the axis's values, with
its standard error over the road samples (numbers only; ``vbikit study run`` prints them)."""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class AxisMeans:
    """An output's mean at each value of one swept axis (over the other axes and the road samples).

    ``standard_error``: of each mean over the road samples — the standard deviation over the samples
    of the mean over the other axes, divided by √(samples) (NaN without a sample axis of two or more:
    a study without road samples has no sampling error to state).

    ``difference``, ``difference_error``: each value's mean minus the first value's, and the standard
    error of that difference paired over the road samples (every value runs on the same roads, so the
    roads' scatter, which both means share, cancels: the standard deviation over the samples of the
    per-sample difference, / √(samples); NaN without samples; 0 for the first value)."""

    dim: str
    values: tuple
    means: tuple[float, ...]
    standard_error: tuple[float, ...]
    difference: tuple[float, ...] = ()
    difference_error: tuple[float, ...] = ()


def is_sample_dim(dim: str) -> bool:
    """A dimension of road (or other) realisations: ``{ samples = n }`` axes are named ``sample…``."""
    return dim.startswith("sample")


def axis_means(output) -> list[AxisMeans]:
    """``AxisMeans`` of the xarray ``output`` for each of its swept dimensions of two or more values
    (not the sample dimensions), in the dataset's order."""
    samples = [d for d in output.dims if is_sample_dim(d)]
    n_samples = math.prod(output.sizes[d] for d in samples)
    out = []
    for dim in output.dims:
        if is_sample_dim(dim) or output.sizes[dim] < 2:
            continue
        others = [d for d in output.dims if d != dim and not is_sample_dim(d)]
        per_sample = output.mean(dim=others) if others else output
        means = per_sample.mean(dim=samples) if samples else per_sample
        if n_samples >= 2:
            flat = per_sample.transpose(dim, *samples).values.reshape(output.sizes[dim], n_samples)
            se = np.std(flat, axis=1, ddof=1) / math.sqrt(n_samples)
            paired = flat - flat[0]
            d_se = np.std(paired, axis=1, ddof=1) / math.sqrt(n_samples)
        else:
            se = d_se = np.full(output.sizes[dim], np.nan)
        m = np.asarray(means.values, float)
        out.append(AxisMeans(dim, tuple(output[dim].values.tolist()), tuple(float(v) for v in m),
                             tuple(float(v) for v in se), tuple(float(v) for v in m - m[0]),
                             tuple(float(v) for v in d_se)))
    return out


def study_summary(ds, step_check: dict | None = None) -> dict:
    """A study's results as plain data (``vbikit study run --json``): the impact factor over all crossings (per response
    point where there are several: ``point``; mean, min, max) with each swept axis's means by value
    (``axis_means``: ``key`` the study's axis key, ``values``, ``means``, ``standard_error``, ``difference``,
    ``difference_error``; NaN where there is no road sample to state one), how good the step is (``step_check``: the
    base crossing's half-step check the dataset stores, ``vbikit.study.check.stored_step_check``, else the one given,
    ``vbikit.study.check.StudyCheck``; None where the base gives crossing.dt), the
    dataset's ``flag_codes``, ``flags`` (the records, ``vbikit.analysis.checks.dataset_flags``) and ``warnings`` (their
    messages; a dataset written before the records were stored: its "; "-joined messages as one), its ``outputs``,
    the vbikit version that wrote the dataset, and ``units``.  NaN stays NaN here; the writer gives null."""
    import json

    from vbikit.analysis.checks import dataset_flag_codes, dataset_flags
    from vbikit.study.check import stored_step_check

    stored = stored_step_check(ds.attrs)  # (the dataset's own; a dataset written without one: the check given)
    step_check = stored if stored is not None else step_check
    keys = json.loads(ds.attrs.get("axes", "{}"))  # dimension -> the study's axis key (``bridge.model``)
    codes = dataset_flag_codes(ds.attrs)
    records, warnings = dataset_flags(ds.attrs)  # (every message its own, with its record)
    out = {"title": str(ds.attrs.get("title", "")), "vbikit_version": str(ds.attrs.get("vbikit_version", "")),
           "outputs": [str(name) for name in ds.data_vars], "impact_factor": [], "step_check": step_check,
           "flag_codes": codes, "warnings": warnings, "flags": records,
           "units": {"impact_factor": "1", "step_check": {"dt": "s", "study_dt": "s", "largest_change": "1",
                                                          "acceleration_change": "1"}}}
    if "impact_factor" not in ds:  # (the study's outputs key left it out, or a PEM study's)
        return out
    im = ds["impact_factor"]
    per_point = [(str(p), im.sel(point=p)) for p in im["point"].values] if "point" in im.dims else [(None, im)]
    rows = []
    for point, values in per_point:
        axes = [{"key": keys.get(a.dim, a.dim), "values": list(a.values), "means": list(a.means),
                 "standard_error": list(a.standard_error), "difference": list(a.difference),
                 "difference_error": list(a.difference_error)} for a in axis_means(values)]
        rows.append({**({"point": point} if point is not None else {}), "mean": float(values.mean()),
                     "min": float(values.min()), "max": float(values.max()), "axes": axes})
    return out | {"impact_factor": rows}
