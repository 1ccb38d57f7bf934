"""Benchmark: σ(t) of the demo crossing by pseudo-excitation against Monte Carlo, same run.

Run from the repository root::

    python benchmarks/bench_random.py               # 1,000 Monte-Carlo crossings twice, 5 PEM runs
    python benchmarks/bench_random.py --crossings 200 --mc-repeat 1 --repeat 3

The case: the demo scenario (``vbikit demo``: HS20-44 on the paper's 16.76 m beam, 20 modes,
multi-point tire n = 6 over 0.254 m, ISO 8608 class C, 75 km/h) with bilateral tires (so that
every sampled crossing is the linear system PEM describes).

Measured (CPU time of the process, ``time.process_time``, so that other jobs on a shared machine
count less; every figure the minimum over its repeats, each after a warm-up that loads or compiles
the kernels):

* PEM: ``vbikit.random.pseudo_excitation`` (the default: exact modal stepping, default lines) for
  the mid-span point (displacement, velocity, acceleration, strain, vehicle DOFs, wheel forces),
  ``--repeat`` runs;
* the former PEM (``method="newmark"``, two substeps, the former 442 lines: ratio 0.05,
  0.01 cycle/m, no tail), ``--old-repeat`` runs (0: skipped);
* Monte Carlo: ``vbikit.random.montecarlo.monte_carlo`` over ``--crossings`` seeds (road
  generation, static start and integration on the engine's batched lanes, every lane's mid-span
  displacement history kept), ``--mc-repeat`` runs;
* accuracy of PEM: its grid check (σ on every line vs every second line, max over time / peak σ)
  and its error against a reference on 7 × as many lines (ratio 0.0125, 0.0025 cycle/m, uniform),
  both for the mid-span displacement; of Monte Carlo: the 95 % sampling half-width of σ at a time
  point, √(χ² interval) ≈ ±1.96/√(2N) of σ there;
* agreement: median and 5–95 % range of σ_PEM/σ_MC over the time points where σ is above 2 % of
  its peak;
* the ratio: Monte-Carlo time / PEM time at ``--crossings`` (goal ≥ 20 at 1,000), and at equal
  accuracy: the crossings N whose half-width 1.96/√(2N) equals PEM's error ε, N = (1.96/ε)²/2, their
  time extrapolated linearly from the measured run — once with ε = the grid check (what PEM claims
  of itself: an upper bound), once with ε = the error against the fine grid (what it achieves).
  Monte Carlo's half-width is taken per time point relative to σ there, which favours Monte Carlo
  (PEM's ε is the worst time point's error relative to the peak).  The time-step error is not in
  either: PEM steps the engine's equations with the engine's integrator and step, so both estimate
  σ of the same discrete system.
"""
from __future__ import annotations

import argparse
import time

from _args import benchmark_args

_P = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
_P.add_argument("--crossings", type=int, default=1000, help="Monte-Carlo crossings (default 1000)")
_P.add_argument("--mc-repeat", type=int, default=2, help="timed Monte-Carlo runs (default 2)")
_P.add_argument("--old-repeat", type=int, default=1, help="timed runs of the former PEM path (default 1; 0 skips)")
ARGS = benchmark_args(__doc__, "timed PEM runs after the warm-up (default 5)", _P)

import numpy as np  # noqa: E402

from vbikit.random import Probes, PseudoRoad, band_lines, pseudo_excitation  # noqa: E402
from vbikit.random.montecarlo import monte_carlo  # noqa: E402
from vbikit.road.psd import RoadPSD  # noqa: E402
from vbikit.scenario import demo_scenario_text, scenario_from_toml  # noqa: E402
from vbikit.scenario.preflight import preflight  # noqa: E402


def timed(fn, repeat: int):
    """(result of the last run, min CPU seconds over ``repeat`` runs)."""
    best, out = float("inf"), None
    for _ in range(max(1, repeat)):
        t0 = time.process_time()
        out = fn()
        best = min(best, time.process_time() - t0)
    return out, best


def main() -> None:
    scenario = scenario_from_toml(demo_scenario_text().replace('contact_length = 0.254',
                                                               'contact_length = 0.254\nloss_of_contact = false'))
    plan = preflight(scenario)
    crossing, dt, data = plan.built.crossing, plan.run.dt, plan.run.kernel_data
    bridge = crossing.bridge
    y = bridge.default_response_y
    x = bridge.default_x_at(y)
    probes = Probes(bridge.mode_shapes([x], [y]), bridge.strain_shapes([x], [y]))
    road = PseudoRoad(RoadPSD.iso("C"))
    psd = road.psd

    def pem(**kw):
        return pseudo_excitation(crossing, road, probes, dt, data=data, **kw)

    pem()  # warm-up
    res, t_pem = timed(pem, ARGS.repeat)
    fine = pem(lines=band_lines(psd.n_min, psd.n_max, ratio=0.0125, max_width=0.0025, tail=0.0))
    old_lines = band_lines(psd.n_min, psd.n_max, ratio=0.05, max_width=0.01, tail=0.0)
    if ARGS.old_repeat > 0:
        old, t_old = timed(lambda: pem(method="newmark", lines=old_lines), ARGS.old_repeat)

    monte_carlo(crossing, road, range(10_001, 10_033), lambda r: None)  # warm-up (compiles the lanes' kernel)
    runs, t_mc = timed(lambda: np.array(monte_carlo(crossing, road, range(1, ARGS.crossings + 1),
                                                    lambda r: r.displacement(x))), ARGS.mc_repeat)

    s_pem, s_ref = res.std("displacement")[:, 0], fine.std("displacement")[:, 0]
    s_mc = runs.std(axis=0, ddof=1)
    n = min(s_pem.size, s_mc.size)
    on = s_pem[:n] > 0.02 * s_pem.max()
    ratio = s_pem[:n][on] / s_mc[:n][on]
    check = res.grid_change("displacement")
    err = float(np.abs(s_pem - s_ref).max() / s_ref.max())
    worst = max(float(np.abs(res.std(k) - fine.std(k)).max() / fine.std(k).max()) for k in res.var)
    print(f"case: {scenario.name} (bilateral tires); {n - 1} steps of {dt:.3g} s")
    print(f"PEM: {res.lines.size} lines, {t_pem:.3f} s CPU (min of {max(1, ARGS.repeat)}); grid check {check:.2%}; "
          f"error against {fine.lines.size} lines {err:.4%} (mid-span displacement), {worst:.4%} (worst output)")
    if ARGS.old_repeat > 0:
        d_old = max(float(np.abs(res.std(k) - old.std(k)).max() / old.std(k).max()) for k in res.var)
        print(f"former PEM (Newmark, 2 substeps, {old_lines.size} lines): {t_old:.3f} s CPU "
              f"(min of {ARGS.old_repeat}); largest σ difference from the new path {d_old:.3%} (worst output)")
    print(f"Monte Carlo: {ARGS.crossings} crossings in {t_mc:.2f} s CPU (min of {max(1, ARGS.mc_repeat)}); "
          f"95 % sampling half-width of σ ±{1.96 / np.sqrt(2 * ARGS.crossings):.1%}")
    print(f"σ_PEM/σ_MC at mid-span: median {np.median(ratio):.4f}, 5–95 % {np.percentile(ratio, 5):.4f}–"
          f"{np.percentile(ratio, 95):.4f}")
    print(f"ratio Monte Carlo / PEM: {t_mc / t_pem:.1f}× at {ARGS.crossings} crossings")
    per = t_mc / ARGS.crossings
    for label, eps in (("grid check", check), ("error against the fine grid", err)):
        n_eq = int(np.ceil((1.96 / eps) ** 2 / 2))
        print(f"equal accuracy ({label}, ε = {eps:.3%}): {n_eq:,} crossings ≈ {per * n_eq:,.0f} s, "
              f"ratio ≈ {per * n_eq / t_pem:,.0f}×")


if __name__ == "__main__":
    main()
