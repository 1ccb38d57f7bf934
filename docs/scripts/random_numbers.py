"""The numbers docs/random.md quotes: PEM against closed forms and against vbikit's Monte Carlo.

Run from the repository root (≈ 1 min)::

    python docs/scripts/random_numbers.py

writes docs/figures/random-numbers.json and the figure random-demo.png (``--no-figure``: not) (tests/random_vibration/test_docs_numbers.py checks that the
page quotes it; its slow test runs this script again and compares).
"""
from __future__ import annotations

import json
import sys
from pathlib import Path

import numpy as np
from scipy.integrate import quad
from scipy.stats import chi2

from vbikit.analysis.impact import impact_factor, static_modal_history
from vbikit.random import Probes, PseudoRoad, band_lines, pseudo_excitation
from vbikit.random.figure import plot_random
from vbikit.random.montecarlo import monte_carlo
from vbikit.random.response import random_response
from vbikit.road.psd import RoadPSD
from vbikit.scenario.pipeline import scenario_of
from vbikit.scenario.preflight import preflight

OUT = Path(__file__).resolve().parents[1] / "figures" / "random-numbers.json"
FIGURE = OUT.with_name("random-demo.png")
MS, MU, KS, CS, KT, CT, V = 10_000.0, 1_000.0, 400e3, 40e3, 1_750e3, 3e3, 25.0


def quarter_car() -> dict[str, float]:
    """Stationary σ on the approach vs ∫ |H|² G dn: relative errors [%]."""
    psd = RoadPSD.iso("C", n_min=0.05, n_max=2.0)
    spec = {"bridge": {"model": "paper-bridge-2-beam", "n_modes": 2},
            "vehicle": {"model": "quarter-car", "sprung_mass": MS, "unsprung_mass": MU, "suspension_stiffness": KS,
                        "suspension_damping": CS, "tire_stiffness": KT, "tire_damping": CT},
            "tire": {"model": "point"}, "road": {"class": "C"}, "crossing": {"speed": V, "approach": 100.0, "dt": 0.002}}
    crossing = preflight(scenario_of(spec)).built.crossing
    res = pseudo_excitation(crossing, PseudoRoad(psd), Probes(np.zeros((1, 2))), 0.002,
                            lines=band_lines(psd.n_min, psd.n_max, ratio=0.02, max_width=0.005))
    late = (res.time > 3.4) & (res.time < 3.9)

    def h(n):
        w = 2 * np.pi * n * V
        s = 1j * w * CS + KS
        z = np.linalg.solve(np.array([[-w * w * MS + s, -s], [-s, -w * w * MU + s + KT + 1j * w * CT]]),
                            np.array([0.0, KT + 1j * w * CT]))
        return w, z

    def exact(f):
        return np.sqrt(quad(lambda n: abs(f(*h(n))) ** 2 * float(psd(np.array(n))), psd.n_min, psd.n_max, limit=400,
                            points=[0.9 / V, 7.0 / V, 8.0 / V])[0])

    cases = {"body_displacement": (lambda w, z: z[0], res.std("vehicle_displacement")[late, 0]),
             "body_acceleration": (lambda w, z: w * w * z[0], res.std("vehicle_acceleration")[late, 0]),
             "tire_force": (lambda w, z: (KT + 1j * w * CT) * (1 - z[1]), res.std("wheel_force")[late, 0])}
    return {k: round(float(np.abs(pem / exact(f) - 1).max() * 100), 3) for k, (f, pem) in cases.items()}


def demo(n: int) -> dict[str, object]:
    """The demo (bilateral tires), class C: σ and IM quantiles against n Monte-Carlo crossings."""
    spec = {"bridge": {"model": "paper-bridge-2-beam", "n_modes": 20, "damping_ratio": 0.02},
            "vehicle": {"model": "hs20-44"},
            "tire": {"model": "multipoint", "n_points": 6, "contact_length": 0.254, "loss_of_contact": False},
            "road": {"class": "C", "seed": 1}, "crossing": {"speed_kmh": 75, "approach": 10}}
    plan = preflight(scenario_of(spec))
    crossing, dt = plan.built.crossing, plan.run.dt
    road = PseudoRoad(RoadPSD.iso("C"))
    rr = random_response(crossing, plan.built.plan, road, dt, data=plan.run.kernel_data)
    x, y = rr.points[0].x, rr.points[0].y
    shape = crossing.bridge.mode_shapes([x], [y])[0]

    def reduce(r):
        im = impact_factor(r.time, r.displacement(x, y), static_modal_history(r) @ shape, r.velocity(x, y))
        return r.displacement(x, y), r.xi_ddot @ shape, im.impact_factor

    runs = monte_carlo(crossing, road, range(1, n + 1), reduce)
    if "--no-figure" not in sys.argv:
        plot_random(rr, FIGURE, [r[0] for r in runs[:30]],
                    title="demo, class C: mean ± kσ by pseudo-excitation, 30 Monte-Carlo crossings (grey)")
    out: dict[str, object] = {"crossings": n}
    for k, name in enumerate(("displacement", "acceleration")):
        s = np.array([r[k] for r in runs])
        s2 = s.var(axis=0, ddof=1)
        p = rr.pem.std(name)[:, 0]
        on = p > 0.02 * p.max()
        lo, hi = s2 * (n - 1) / chi2.ppf(0.995, n - 1), s2 * (n - 1) / chi2.ppf(0.005, n - 1)
        ratio = p[on] / np.sqrt(s2[on])
        out[name] = {"inside_pct": round(float(((p**2 >= lo) & (p**2 <= hi))[on].mean() * 100), 1),
                     "ratio_median": round(float(np.median(ratio)), 4),
                     "ratio_5_95": [round(float(v), 4) for v in np.percentile(ratio, [5, 95])]}
    ims = np.array([r[2] for r in runs])
    out["im_mc"] = {"mean": round(float(ims.mean()), 3),
                    **{f"{q:g}": round(float(np.quantile(ims, q)), 3) for q in (0.5, 0.9, 0.95)}}
    out["im_pem"] = {"mean": round(rr.summary["impact_factor_mean"], 3),
                     **{k: round(v, 3) for k, v in rr.summary["impact_factor_quantiles"].items()}}
    out["im_crossings"] = {k: round(v, 3) for k, v in rr.summary["impact_factor_quantiles_crossings"].items()}
    out["im_sampling_error"] = round(rr.summary["impact_factor_sampling_error"], 4)
    out["grid_change_pct"] = round(rr.summary["grid_change"] * 100, 2)
    out["n_lines"] = rr.summary["n_lines"]
    return out


def main() -> None:
    numbers = {"quarter_car_error_pct": quarter_car(), "demo": demo(1000)}
    OUT.write_text(json.dumps(numbers, indent=2) + "\n")
    print(json.dumps(numbers, indent=2))


if __name__ == "__main__":
    main()
