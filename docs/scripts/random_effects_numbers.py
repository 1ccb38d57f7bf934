"""The numbers docs/random.md quotes for the load effects, the vehicle and the tire filter (PEM
against vbikit's Monte Carlo).

Run from the repository root (a few minutes)::

    python docs/scripts/random_effects_numbers.py

writes docs/figures/random-effects-numbers.json (tests/random_vibration/test_pem_load_effects.py
checks that the page quotes it).  The demo: HS20-44 on the paper's 16.76 m beam, 20 modes,
multi-point tire n = 6 over 0.254 m, bilateral, ISO class C, 75 km/h; Monte Carlo on road seeds
1…1000 (the σ ratios also on seeds 1001…3000: three sets, and pooled).
"""
from __future__ import annotations

import dataclasses
import json
import sys
from pathlib import Path

import numpy as np
from scipy.stats import chi2

from vbikit.analysis.effects import load_effect_responses
from vbikit.analysis.impact import impact_factor, static_direction, static_modal_history
from vbikit.random import Probes, PseudoRoad, pseudo_excitation
from vbikit.random.montecarlo import monte_carlo
from vbikit.random.response import random_response
from vbikit.road.psd import RoadPSD
from vbikit.scenario.pipeline import scenario_of
from vbikit.scenario.preflight import preflight

OUT = Path(__file__).resolve().parents[1] / "figures" / "random-effects-numbers.json"
N = 1000
POINT = {"model": "point"}
MULTI = {"model": "multipoint", "n_points": 6, "contact_length": 0.254}


def plan_of(tire: dict, n_modes: int = 20):
    spec = {"bridge": {"model": "paper-bridge-2-beam", "n_modes": n_modes, "damping_ratio": 0.02},
            "vehicle": {"model": "hs20-44"}, "tire": {**tire, "loss_of_contact": False},
            "road": {"class": "C", "seed": 1}, "crossing": {"speed_kmh": 75, "approach": 10}}
    return preflight(scenario_of(spec))


def inside_pct(std: np.ndarray, samples: np.ndarray) -> float:
    """% of the random time points where σ² is inside the 99 % χ² interval of the sample variance."""
    n = samples.shape[0]
    s2 = samples.var(axis=0, ddof=1)
    lo, hi = s2 * (n - 1) / chi2.ppf(0.995, n - 1), s2 * (n - 1) / chi2.ppf(0.005, n - 1)
    on = std > 0.02 * std.max()
    return round(100 * float(((std**2 >= lo) & (std**2 <= hi))[on].mean()), 1)


def ratio(std: np.ndarray, samples: np.ndarray) -> list[float]:
    """median and 5–95 % of σ_PEM / σ_MC over the random time points."""
    s = samples.std(axis=0, ddof=1)
    on = std > 0.02 * std.max()
    r = std[on] / s[on]
    return [round(float(np.median(r)), 4), round(float(np.quantile(r, 0.05)), 4), round(float(np.quantile(r, 0.95)), 4)]


def effects() -> dict:
    plan = plan_of(MULTI)
    crossing, road = plan.built.crossing, PseudoRoad(RoadPSD.iso("C"))
    # the load effects by mode superposition in PEM and Monte Carlo (the random part of the plan's mode
    # acceleration is checked against the engine line by line: tests/random_vibration/test_pem_mode_acceleration.py)
    ms_plan = dataclasses.replace(plan.built.plan, load_effect_method="mode-superposition")
    rr = random_response(crossing, ms_plan, road, plan.run.dt, data=plan.run.kernel_data)
    fx = [e.effect for e in rr.effects]
    modal = np.stack([e.modal for e in fx], axis=1)
    m = [e.kind for e in fx].index("moment")

    def reduce(r):
        xi_st = static_modal_history(r)
        ma = load_effect_responses(r, [fx[m]], "mode-acceleration")[0].dynamic
        return r.xi @ modal, r.q_ddot, impact_factor(r.time, r.xi @ modal[:, m], xi_st @ modal[:, m]).impact_factor, ma

    runs = monte_carlo(crossing, road, range(1, N + 1), reduce)
    eff, qdd = np.array([r[0] for r in runs]), np.array([r[1] for r in runs])
    im, ma = np.array([r[2] for r in runs]), np.array([r[3] for r in runs])
    k = min(eff.shape[1], rr.pem.time.size)
    out: dict = {"crossings": N}
    for j, e in enumerate(rr.effects):
        if e.name in ("moment_x8.38", "reaction_s0"):
            out[e.name] = {"inside_pct": inside_pct(rr.effect_std(j)[:k], eff[:, :k, j]),
                           "ratio": ratio(rr.effect_std(j)[:k], eff[:, :k, j])}
    # two more independent sets of N roads (seeds N+1 … 3N): how much of a set's σ ratio is its own
    # sampling, and the three sets pooled
    more = np.array(monte_carlo(crossing, road, range(N + 1, 3 * N + 1), lambda r: r.xi @ modal))
    k3 = min(k, more.shape[1])
    pooled = np.concatenate([eff[:, :k3], more[:, :k3]])
    for j, e in enumerate(rr.effects):
        if e.name in ("moment_x8.38", "reaction_s0"):
            out[e.name]["set_medians"] = [ratio(rr.effect_std(j)[:k3], part[:, :, j])[0]
                                          for part in (eff[:, :k3], more[:N, :k3], more[N:, :k3])]
            out[e.name]["pooled"] = {"crossings": 3 * N, "inside_pct": inside_pct(rr.effect_std(j)[:k3], pooled[:, :, j]),
                                     "ratio": ratio(rr.effect_std(j)[:k3], pooled[:, :, j])}
    body = list(rr.mean.crossing.vehicle.dof_names).index("tractor_heave")
    out["tractor_heave_acceleration"] = {"inside_pct": inside_pct(rr.pem.std("vehicle_acceleration")[:k, body],
                                                                  qdd[:, :k, body])}
    s = rr.summary["effects"][m]
    out["moment_im_pem"] = {"mean": round(s["impact_factor_mean"], 3),
                            **{q: round(v, 3) for q, v in s["impact_factor_quantiles"].items()}}
    out["moment_im_mc"] = {"mean": round(float(im.mean()), 3),
                           **{f"{q:g}": round(float(np.quantile(im, q)), 3) for q in (0.5, 0.9, 0.95)}}
    out["moment_im_smooth"] = {"mode_superposition": round(s["impact_factor_smooth"], 4),
                               "mode_acceleration": round(smooth_im(load_effect_responses(rr.mean, [fx[m]])[0]), 4)}
    # the random part by the two methods (Monte Carlo): how much the truncated modes' static part adds
    out["moment_std_max_ma_over_ms"] = round(float(ma[:, :k].std(axis=0, ddof=1).max()
                                                   / eff[:, :k, m].std(axis=0, ddof=1).max()), 4)
    return out


def smooth_im(response) -> float:
    """IM of a smooth-road load-effect history in its static peak's direction (sampled peaks)."""
    sign = static_direction(response.static)
    r_st = float(np.max(sign * response.static))
    return float((np.max(sign * response.dynamic) - r_st) / r_st)


def tire_filter(spacing: float) -> dict:
    """ρ by PEM and by Monte Carlo on roads sampled every ``spacing`` [m] (PEM on the engine's step
    for them)."""
    sys.path.insert(0, str(OUT.parents[2]))  # the repository root: the test's own comparison
    from tests.random_vibration.test_pem_tire_filter import _tire

    road = PseudoRoad(RoadPSD.iso("C"))
    got = {}
    for name, tire in (("point", POINT), ("multi", MULTI)):
        got[name] = _tire(tire, road, N, 20, spacing)
    rng = np.random.default_rng(0)
    out: dict = {"roads": N, "road_spacing": spacing}
    for key in ("wheel force", "acceleration"):
        (pp, mp), (pm, mm) = got["point"], got["multi"]
        v = lambda a: float(a.var(axis=0, ddof=1).mean())  # noqa: E731
        boot = []
        for _ in range(2000):
            d = rng.integers(0, N, N)
            boot.append(np.sqrt(v(mm[key][d]) / v(mp[key][d])))
        lo, hi = np.quantile(boot, [0.005, 0.995])
        out[key.replace(" ", "_")] = {"pem": round(float(np.sqrt(pm[key].mean() / pp[key].mean())), 4),
                                      "mc": round(float(np.sqrt(v(mm[key]) / v(mp[key]))), 4),
                                      "mc_99": [round(float(lo), 4), round(float(hi), 4)]}
    return out


def main() -> None:
    numbers = {"demo_effects": effects(), "tire_filter": tire_filter(0.01), "tire_filter_fine_road": tire_filter(0.005)}
    OUT.write_text(json.dumps(numbers, indent=2) + "\n")
    json.dump(numbers, sys.stdout, indent=2)


if __name__ == "__main__":
    main()
