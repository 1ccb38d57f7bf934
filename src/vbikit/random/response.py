"""A crossing on a random road without sampling: the mean history (the smooth-road crossing), the
standard deviation history of every response by pseudo-excitation (``vbikit.random.pem``), and
the design numbers that follow: the distribution of the peak deflection and of the impact factor
at each response point (peaks of Gaussian histories with PEM's covariance; the Poisson up-crossing
estimate of ``vbikit.random.peaks`` as a cross-check), and the probability of lift-off."""
from __future__ import annotations

import dataclasses
import logging
import time as _time
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from vbikit.analysis.impact import static_direction
from vbikit.analysis.plan import ResponsePlan
from vbikit.analysis.response import PointResponse, plan_responses
from vbikit.random.lines import Lines
from vbikit.random.peaks import exceedance_probability, peak_distribution
from vbikit.random.pem import PEMResult, Probes, PseudoRoad, pseudo_excitation
from vbikit.solve.crossing import Crossing
from vbikit.solve.result import CrossingResult
from vbikit.solve.simulate import simulate

log = logging.getLogger(__name__)

#: Gaussian histories sampled for the peak statistics (one matrix product each 256)
SAMPLES = 4000
#: the quantiles of the impact factor reported by default
QUANTILES = (0.5, 0.9, 0.95)
#: lift-off probability above which the linear theory is not trusted (the user is sent to Monte Carlo)
LIFT_OFF_LIMIT = 1e-3
#: how good the numbers are, in words (validated in tests/random_vibration; docs/random.md)
QUALITY = ("σ histories exact for the linear system up to the wavenumber grid (grid_change) and the time step "
           "(< 1 % on the paper's beam); they match 1,000 Monte-Carlo crossings within sampling error. Impact-factor "
           "statistics from the peaks of Gaussian histories with exactly that covariance (sampling error stated); "
           "the Poisson up-crossing quantiles (impact_factor_quantiles_crossings) are a cross-check that runs low "
           "below the 90 % quantile")
#: grid check (σ on every line vs every second line) above which the answer is flagged
GRID_LIMIT = 0.02


@dataclass
class RandomResponse:
    """The random crossing: ``mean`` (the smooth-road crossing), its ``points`` (mean and static
    histories per response point), ``pem`` (variances), ``summary`` (JSON-ready numbers)."""

    mean: CrossingResult
    points: list[PointResponse]
    pem: PEMResult
    summary: dict[str, Any]

    def dataset(self):
        """xarray Dataset: ``mean`` and ``std`` of the deck displacement, velocity, acceleration and
        bottom-fibre strain over (time, point), and of the wheel forces over (time, wheel)."""
        import xarray as xr

        t = self.pem.time
        n = min(t.size, self.mean.time.size)
        pts = np.arange(len(self.points))
        data: dict[str, Any] = {}
        for q, unit in (("displacement", "m"), ("velocity", "m/s"), ("acceleration", "m/s2"), ("strain", "1")):
            data[f"{q}_mean"] = (("time", "point"), np.stack([getattr(p, q)[:n] for p in self.points], axis=1),
                                 {"units": unit, "long_name": f"mean deck {q} (smooth-road crossing)"})
            data[f"{q}_std"] = (("time", "point"), self.pem.std(q)[:n], {"units": unit,
                                                                         "long_name": f"standard deviation of the deck {q} (pseudo-excitation)"})
        wheels = [w.name for w in self.mean.crossing.vehicle.wheels]
        data["wheel_force_mean"] = (("time", "wheel"), self.mean.wheel_forces[:n], {"units": "N"})
        data["wheel_force_std"] = (("time", "wheel"), self.pem.std("wheel_force")[:n], {"units": "N"})
        s = self.summary
        attrs = {"method": s["method"], "grid_change": s["grid_change"], "n_lines": s["n_lines"],
                 "lift_off_probability": s["lift_off_probability"], "warnings": "; ".join(s["warnings"])}
        return xr.Dataset(data, coords={"time": t[:n], "point": pts, "wheel": wheels,
                                        "x": ("point", [p.x for p in self.points]),
                                        "y": ("point", [p.y for p in self.points])}, attrs=attrs)


def random_response(crossing: Crossing, plan: ResponsePlan, road: PseudoRoad, dt: float, *,
                    quantiles: tuple[float, ...] = QUANTILES, lines: Lines | None = None, substeps: int = 2,
                    samples: int = SAMPLES, data=None) -> RandomResponse:
    """Mean, σ and impact-factor distribution of ``crossing`` on the random ``road`` at the points of
    ``plan``, on the time grid of step ``dt`` [s] (the engine's step for the sampled road).

    The impact factor at a point is IM = (P − R_st)/R_st with P the peak of the dynamic response in
    the static peak's direction and R_st the static peak (``vbikit.analysis.impact``).  P's
    distribution: the peaks of ``samples`` histories of the Gaussian process with PEM's covariance
    (``PEMResult.sample_displacement``: exact for the linear system, with a sampling error stated
    in the summary), and as a cross-check by Poisson up-crossings (``peak_distribution``)."""
    if int(samples) != samples or samples < 100:
        raise ValueError(f"samples must be an integer >= 100, got {samples!r}")
    started = _time.perf_counter()
    smooth = simulate(dataclasses.replace(crossing, road=None, road_right=None, dt=dt))
    points = plan_responses(smooth, plan)
    shapes = crossing.bridge.mode_shapes([p.x for p in points], [p.y for p in points])
    strains = crossing.bridge.strain_shapes([p.x for p in points], [p.y for p in points])
    pem = pseudo_excitation(crossing, road, Probes(np.atleast_2d(shapes), np.atleast_2d(strains)), dt, lines=lines, substeps=substeps,
                            data=data, keep_lines=True)
    n = min(pem.time.size, smooth.time.size)
    peaks = _sampled_peaks(pem, points, n, samples)
    entries = []
    for j, p in enumerate(points):
        entries.append(_point_entry(pem, p, j, n, quantiles, peaks[:, j]))
    wheel_std = pem.std("wheel_force")[:n]
    lift = {w.name: exceedance_probability(smooth.wheel_forces[:n, k], wheel_std[:, k])
            for k, w in enumerate(crossing.vehicle.wheels)}
    p_lift = max(lift.values(), default=0.0)
    grid = max(pem.grid_change(q) for q in ("displacement", "acceleration", "wheel_force"))
    warnings = []
    if p_lift > LIFT_OFF_LIMIT:
        warnings.append(f"a tire lifts off with probability {p_lift:.2g} at some instant (> {LIFT_OFF_LIMIT:g}): the "
                        "linear theory does not hold there; use Monte Carlo (several road seeds, tires that can lift)")
    if grid > GRID_LIMIT:
        warnings.append(f"the wavenumber grid is coarse: σ changes by {grid:.1%} between every and every second line")
    head = entries[0]
    summary: dict[str, Any] = {
        "method": "pseudo-excitation (Newmark, %d substeps); peaks of %d Gaussian histories with its covariance "
                  "(cross-check: Poisson up-crossings with Vanmarcke's correction)" % (substeps, samples),
        **{k: head[k] for k in ("impact_factor_mean", "impact_factor_std", "impact_factor_quantiles",
                                "impact_factor_sampling_error", "impact_factor_quantiles_crossings",
                                "displacement_peak_mean", "displacement_peak_std", "static_peak", "std_at_peak")},
        "lift_off_probability": p_lift,
        "lift_off_probability_by_wheel": lift,
        "grid_change": grid,
        "n_lines": pem.lines.size * road.line_factors().shape[0],
        "quality": QUALITY,
        "points": entries,
        "warnings": warnings,
        "seconds": _time.perf_counter() - started,
    }
    return RandomResponse(smooth, points, pem, summary)


def _sampled_peaks(pem: PEMResult, points: list[PointResponse], n: int, samples: int) -> NDArray[np.float64]:
    """(samples, n_pt): the peak of each sampled history in its static peak's direction."""
    sign = np.array([static_direction(p.static_displacement[:n]) for p in points])
    mean = np.stack([p.displacement[:n] for p in points], axis=1) * sign  # (n_t, n_pt)
    out = [np.max(mean[None] + y[:, :n] * sign, axis=1) for y in pem.sample_displacement(samples)]
    return np.concatenate(out, axis=0)


def _point_entry(pem: PEMResult, p: PointResponse, j: int, n: int, quantiles, peaks: NDArray[np.float64]) -> dict[str, Any]:
    static = p.static_displacement[:n]
    sign = static_direction(static)
    r_st = float(np.max(sign * static))
    mean, rate = sign * p.displacement[:n], sign * p.velocity[:n]
    std, rate_std = pem.std("displacement")[:n, j], pem.std("velocity")[:n, j]
    dist = peak_distribution(pem.time[:n], mean, std, rate, rate_std, pem.cov_dv[:n, j], pem.lambda1[:n, j])
    ok = r_st > 0
    im = (peaks - r_st) / r_st if ok else np.full(peaks.size, np.nan)
    cross = lambda b: (b - r_st) / r_st if ok else float("nan")  # noqa: E731
    i_peak = int(np.argmax(mean))
    return {"x": p.x, "y": p.y,
            "impact_factor_mean": float(im.mean()), "impact_factor_std": float(im.std(ddof=1)),
            "impact_factor_quantiles": {f"{q:g}": float(np.quantile(im, q)) for q in quantiles},
            "impact_factor_sampling_error": float(im.std(ddof=1) / np.sqrt(im.size)),
            "impact_factor_samples": int(im.size),
            "impact_factor_quantiles_crossings": {f"{q:g}": cross(dist.quantile(q)) for q in quantiles},
            "displacement_peak_mean": sign * float(peaks.mean()), "displacement_peak_std": float(peaks.std(ddof=1)),
            "static_peak": sign * r_st, "std_at_peak": float(std[i_peak]),
            "impact_factor_smooth": cross(float(mean.max())),
            "displacement_std_max": float(std.max()),
            "acceleration_std_max": float(pem.std("acceleration")[:n, j].max()),
            "strain_std_max": float(pem.std("strain")[:n, j].max())}
