"""σ(t), mean and impact factor of the load effects (moment, shear, reaction) and of the vehicle's
accelerations by pseudo-excitation (``vbikit.random.response``; by the plan's method, mode acceleration,
and by mode superposition R = Σ_i r_i ξ_i):

* a closed form that fails on a wrong sign or factor: with one mode of the simply supported Euler
  beam, φ = a sin(πx/L), the midspan moment is M = EI φ''(L/2) ξ = −EI (π/L)² w(L/2) and the entry
  reaction R₀ = EI φ'''(0) ξ = −EI (π/L)³ w(L/2) (Clough & Penzien 1993, §8; signs of
  ``vbikit.bridge.effects``: sagging and upward reaction positive, z up), so σ_M = EI (π/L)² σ_w,
  mean M = −EI (π/L)² mean w, and their impact factors are the deflection's;
* vbikit's own Monte Carlo (the engine on sampled roads of the same PSD, bilateral tires, its load
  effects by the same method, mode acceleration): PEM's σ²
  inside the 99 % χ² interval of the sample variance at ≥ 95 % of the random time points (the rule
  of ``test_pem_monte_carlo``), and the moment's mean impact factor within 3.3 standard errors
  (99.9 %) of the Monte-Carlo mean.
"""
from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from tests.random_vibration.test_pem_monte_carlo import _inside, _plan
from vbikit.analysis.effects import load_effect_responses
from vbikit.random import PseudoRoad
from vbikit.random.montecarlo import monte_carlo
from vbikit.random.response import random_response
from vbikit.road.psd import RoadPSD


def _random(n_modes: int, tire: dict, samples: int = 4000, method: str | None = None):
    """The random crossing of the demo's beam, load effects by the plan's method (default mode
    acceleration) or ``method``."""
    plan = _plan(n_modes, tire)
    road = PseudoRoad(RoadPSD.iso("C"))
    response_plan = plan.built.plan if method is None else dataclasses.replace(plan.built.plan, load_effect_method=method)
    rr = random_response(plan.built.crossing, response_plan, road, plan.run.dt, data=plan.run.kernel_data,
                         samples=samples)
    return plan, road, rr


def test_one_mode_moment_and_reaction_are_the_deflection_times_closed_form_factors():
    _, _, rr = _random(1, {"model": "point"}, samples=400, method="mode-superposition")
    beam = rr.mean.crossing.bridge
    k = np.pi / beam.span
    assert abs(rr.points[0].x - beam.span / 2) < 1e-12
    w_std, w_mean = rr.pem.std("displacement")[:, 0], rr.points[0].displacement
    n = min(w_std.size, w_mean.size)
    names = [e.name for e in rr.effects]
    m, r0 = names.index("moment_x8.38"), names.index("reaction_s0")
    assert np.allclose(rr.effect_std(m)[:n], beam.EI * k**2 * w_std[:n], rtol=1e-9, atol=0)
    assert np.allclose(rr.effects[m].dynamic[:n], -beam.EI * k**2 * w_mean[:n], rtol=1e-9, atol=1e-9)
    assert np.allclose(rr.effect_std(r0)[:n], beam.EI * k**3 * w_std[:n], rtol=1e-9, atol=0)
    point, moment = rr.summary["points"][0], rr.summary["effects"][m]
    assert moment["static_peak"] > 0 > point["static_peak"]  # sagging moment under a downward deflection
    for key in ("impact_factor_mean", "impact_factor_std"):
        assert moment[key] == pytest.approx(point[key], rel=1e-9)
    assert moment["impact_factor_quantiles"] == pytest.approx(point["impact_factor_quantiles"], rel=1e-9)
    ds = rr.dataset()
    assert float(ds["moment_x8.38_std"].max()) == pytest.approx(moment["std_max"])
    assert ds["vehicle_acceleration_std"].shape[1] == len(rr.mean.crossing.vehicle.dof_names)


def _compare(n_modes: int, tire: dict, n: int):
    plan, road, rr = _random(n_modes, tire)
    crossing = plan.built.crossing
    effects = [e.effect for e in rr.effects]
    m = [e.kind for e in effects].index("moment")

    method = rr.effects[0].method  # the plan's: mode acceleration

    def reduce(r):
        responses = load_effect_responses(r, effects, method, check_step=False)
        im = responses[m].impact.impact_factor
        return np.stack([e.dynamic for e in responses], axis=1), r.q_ddot, im

    runs = monte_carlo(crossing, road, range(1, n + 1), reduce)
    eff, qdd = np.array([r[0] for r in runs]), np.array([r[1] for r in runs])
    im = np.array([r[2] for r in runs])
    k = min(eff.shape[1], rr.pem.time.size)
    found = {e.name: _inside(rr.effect_std(j)[:k], eff[:, :k, j]) for j, e in enumerate(rr.effects)}
    dof = rr.mean.crossing.vehicle.dof_names
    acc = rr.pem.std("vehicle_acceleration")[:k]
    for j, name in enumerate(dof):
        if acc[:, j].max() > 1e-6:  # roll DOFs are not excited by identical wheel lines
            found[name] = _inside(acc[:, j], qdd[:, :k, j])
    z = (rr.summary["effects"][m]["impact_factor_mean"] - im.mean()) / np.sqrt(im.var(ddof=1) / n
                                                                              + rr.summary["effects"][m]["impact_factor_sampling_error"]**2)
    return found, z


def test_load_effects_and_vehicle_accelerations_match_monte_carlo():
    """6 modes, point tires, class C: 200 crossings."""
    found, z = _compare(6, {"model": "point"}, 200)
    assert all(v >= 0.95 for v in found.values()), found
    assert abs(z) < 3.3, z


@pytest.mark.slow
def test_load_effects_match_monte_carlo_demo():
    """The demo's bridge and tire (20 modes, multi-point n = 6): 600 crossings."""
    found, z = _compare(20, {"model": "multipoint", "n_points": 6, "contact_length": 0.254}, 600)
    assert all(v >= 0.95 for v in found.values()), found
    assert abs(z) < 3.3, z


def test_cli_text_reports_load_effects_and_vehicle(tmp_path, monkeypatch):
    """``vbikit run --random`` prints every load effect's peak, σ and IM and the vehicle's σ."""
    from typer.testing import CliRunner

    import vbikit.scenario.pipeline as pipeline
    from vbikit.cli import app

    _, _, rr = _random(1, {"model": "point"}, samples=400, method="mode-superposition")
    monkeypatch.setattr(pipeline, "run_random", lambda *a, **k: rr)
    path = tmp_path / "s.toml"
    path.write_text("")
    res = CliRunner().invoke(app, ["run", str(path), "--random"])
    assert res.exit_code == 0, res.output
    moment = next(e for e in rr.summary["effects"] if e["kind"] == "moment")
    assert "moment moment_x8.38 (mode-superposition)" in res.output
    assert f"{moment['impact_factor_mean']:9.4f}" in res.output
    assert "σ max wheel force" in res.output and "tractor_heave" in res.output


def test_page_quotes_the_stored_effect_numbers():
    """docs/random.md quotes what docs/scripts/random_effects_numbers.py stored (run it again when
    the code changes them)."""
    import json
    from pathlib import Path

    root = Path(__file__).resolve().parents[2]
    page = " ".join((root / "docs" / "random.md").read_text(encoding="utf-8").split())
    n = json.loads((root / "docs" / "figures" / "random-effects-numbers.json").read_text())
    d, f = n["demo_effects"], n["tire_filter"]
    m, r = d["moment_x8.38"], d["reaction_s0"]
    q = " / ".join
    want = [f"at {m['inside_pct']:g} % (mid-span moment) and {r['inside_pct']:g} % (entry reaction)",
            f"at {d['tractor_heave_acceleration']['inside_pct']:g} % for the tractor's heave acceleration",
            f"median {m['ratio'][0]:.4f} (5–95 %: {m['ratio'][1]:.4f}–{m['ratio'][2]:.4f})",
            f"{r['ratio'][0]:.4f} ({r['ratio'][1]:.4f}–{r['ratio'][2]:.4f}) for the reaction",
            f"are {r['set_medians'][1]:.4f} and {r['set_medians'][2]:.4f} for the reaction, {m['set_medians'][1]:.4f} and "
            f"{m['set_medians'][2]:.4f} for the moment",
            f"give {r['pooled']['ratio'][0]:.4f} ({r['pooled']['ratio'][1]:.4f}–{r['pooled']['ratio'][2]:.4f}) for the "
            f"reaction, with σ² inside the 99 % χ² interval at {r['pooled']['inside_pct']:g} % of the time points, and "
            f"{m['pooled']['ratio'][0]:.4f} ({m['pooled']['ratio'][1]:.4f}–{m['pooled']['ratio'][2]:.4f}) for the moment, "
            f"at {m['pooled']['inside_pct']:g} %",
            f"by PEM {d['moment_im_pem']['mean']:.3f} and " + q(f"{d['moment_im_pem'][k]:.3f}" for k in ("0.5", "0.9", "0.95")),
            f"by Monte Carlo {d['moment_im_mc']['mean']:.3f} and " + q(f"{d['moment_im_mc'][k]:.3f}" for k in ("0.5", "0.9", "0.95")),
            f"smooth-road IM {d['moment_im_smooth']['mode_superposition']:.4f} against "
            f"{d['moment_im_smooth']['mode_acceleration']:.4f}",
            f"is {d['moment_std_max_ma_over_ms']:.4f} times",
            f"Wheel forces: PEM {f['wheel_force']['pem']:.4f}, Monte Carlo {f['wheel_force']['mc']:.4f}",
            f"{f['wheel_force']['mc_99'][0]:.4f}–{f['wheel_force']['mc_99'][1]:.4f}",
            f"Mid-span acceleration: PEM {f['acceleration']['pem']:.4f}, Monte Carlo {f['acceleration']['mc']:.4f}",
            f"({f['acceleration']['mc_99'][0]:.4f}–{f['acceleration']['mc_99'][1]:.4f})"]
    g = n["tire_filter_fine_road"]
    want += [f"Monte Carlo gives\n{g['acceleration']['mc']:.4f} ({g['acceleration']['mc_99'][0]:.4f}–{g['acceleration']['mc_99'][1]:.4f})"
             .replace("\n", " "), f"PEM on that step {g['acceleration']['pem']:.4f}",
             f"wheel forces {g['wheel_force']['pem']:.4f} against {g['wheel_force']['mc']:.4f} "
             f"({g['wheel_force']['mc_99'][0]:.4f}–{g['wheel_force']['mc_99'][1]:.4f})"]
    for key in ("wheel_force", "acceleration"):  # what the page claims: inside on the finer road
        lo, hi = g[key]["mc_99"]
        assert lo <= g[key]["pem"] <= hi, (key, g)
    missing = [s for s in want if s not in page]
    assert not missing, f"docs/random.md does not quote {missing}: run python docs/scripts/random_effects_numbers.py"
