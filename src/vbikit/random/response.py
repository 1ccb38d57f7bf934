"""A crossing on a random road without sampling: the mean history (the smooth-road crossing), the
standard deviation history of every response by pseudo-excitation (``vbikit.random.pem``), and
the design numbers that follow (``vbikit.random.peaks``): the distribution of the peak
deflection and of the impact factor at each response point, and the probability of lift-off."""
from __future__ import annotations

import dataclasses
import logging
import time as _time
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from vbikit.analysis.plan import ResponsePlan
from vbikit.analysis.response import PointResponse, plan_responses
from vbikit.random.lines import Lines
from vbikit.random.peaks import exceedance_probability, peak_distribution
from vbikit.random.pem import PEMResult, Probes, PseudoRoad, pseudo_excitation
from vbikit.solve.crossing import Crossing
from vbikit.solve.result import CrossingResult
from vbikit.solve.simulate import simulate

log = logging.getLogger(__name__)

#: the quantiles of the impact factor reported by default
QUANTILES = (0.5, 0.9, 0.95)
#: lift-off probability above which the linear theory is not trusted (the user is sent to Monte Carlo)
LIFT_OFF_LIMIT = 1e-3
#: how good the numbers are, in words (validated in tests/random_vibration; docs/random.md)
QUALITY = ("σ histories exact for the linear system up to the wavenumber grid (grid_change) and the time step "
           "(< 1 % on the paper's beam); they match 1,000 Monte-Carlo crossings within sampling error. The 90 % and "
           "95 % impact-factor quantiles match Monte Carlo; the mean, std and median of the impact factor come from "
           "the Poisson crossing count, which makes the lower half of the peak distribution too wide, so they run "
           "low — use the upper quantiles")
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
        """xarray Dataset: ``mean`` and ``std`` of the deck displacement, velocity and acceleration
        over (time, point), and of the wheel forces over (time, wheel)."""
        import xarray as xr

        t = self.pem.time
        n = min(t.size, self.mean.time.size)
        pts = np.arange(len(self.points))
        data: dict[str, Any] = {}
        for q, unit in (("displacement", "m"), ("velocity", "m/s"), ("acceleration", "m/s2")):
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
                    data=None) -> RandomResponse:
    """Mean, σ and impact-factor distribution of ``crossing`` on the random ``road`` at the points of
    ``plan``, on the time grid of step ``dt`` [s] (the engine's step for the sampled road).

    The impact factor at a point is IM = (P − R_st)/R_st with P the peak of the dynamic response in
    the static peak's direction (a random variable: ``peak_distribution``) and R_st the static peak
    (``vbikit.analysis.impact``)."""
    started = _time.perf_counter()
    smooth = simulate(dataclasses.replace(crossing, road=None, road_right=None, dt=dt))
    points = plan_responses(smooth, plan)
    shapes = crossing.bridge.mode_shapes([p.x for p in points], [p.y for p in points])
    pem = pseudo_excitation(crossing, road, Probes(np.atleast_2d(shapes)), dt, lines=lines, substeps=substeps,
                            data=data)
    n = min(pem.time.size, smooth.time.size)
    entries = []
    for j, p in enumerate(points):
        entries.append(_point_entry(pem, p, j, n, quantiles))
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
        "method": "pseudo-excitation (Newmark, %d substeps) with Poisson up-crossings and Vanmarcke's correction"
                  % substeps,
        **{k: head[k] for k in ("impact_factor_mean", "impact_factor_std", "impact_factor_quantiles",
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


def _point_entry(pem: PEMResult, p: PointResponse, j: int, n: int, quantiles) -> dict[str, Any]:
    static = p.static_displacement[:n]
    i_st = int(np.argmax(np.abs(static)))
    sign = float(np.sign(static[i_st]) or 1.0)
    r_st = sign * float(static[i_st])
    mean, rate = sign * p.displacement[:n], sign * p.velocity[:n]
    std, rate_std = pem.std("displacement")[:n, j], pem.std("velocity")[:n, j]
    dist = peak_distribution(pem.time[:n], mean, std, rate, rate_std, pem.cov_dv[:n, j], pem.lambda1[:n, j])
    im = lambda b: (b - r_st) / r_st if r_st > 0 else float("nan")  # noqa: E731
    i_peak = int(np.argmax(mean))
    return {"x": p.x, "y": p.y,
            "impact_factor_mean": im(dist.mean), "impact_factor_std": dist.std / r_st if r_st > 0 else float("nan"),
            "impact_factor_quantiles": {f"{q:g}": im(dist.quantile(q)) for q in quantiles},
            "displacement_peak_mean": sign * dist.mean, "displacement_peak_std": dist.std,
            "static_peak": sign * r_st, "std_at_peak": float(std[i_peak]),
            "impact_factor_smooth": im(float(mean.max())),
            "displacement_std_max": float(std.max()),
            "acceleration_std_max": float(pem.std("acceleration")[:n, j].max())}
