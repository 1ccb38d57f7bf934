"""Benchmark: σ(t) of the demo crossing by pseudo-excitation against Monte Carlo, same run.

Run from the repository root::

    python benchmarks/bench_random.py               # 1,000 Monte-Carlo crossings, 3 PEM runs
    python benchmarks/bench_random.py --crossings 200 --repeat 3

The case: the demo scenario (``vbikit demo``: HS20-44 on the paper's 16.76 m beam, 20 modes,
multi-point tire n = 6 over 0.254 m, ISO 8608 class C, 75 km/h) with bilateral tires (so that
every sampled crossing is the linear system PEM describes).

Measured (wall clock, ``time.perf_counter``):

* PEM: ``vbikit.random.pseudo_excitation`` for the mid-span point (442 wavenumber lines, two
  Newmark substeps per engine step), median of ``--repeat`` runs after one warm-up;
* Monte Carlo: ``vbikit.random.montecarlo.monte_carlo`` over ``--crossings`` seeds (road
  generation, static start and integration on the engine's batched lanes, every lane's
  mid-span displacement history kept), one run after a 32-crossing warm-up;
* accuracy of each: PEM's grid check (σ on every line vs every second line) and Monte Carlo's
  95 % sampling half-width of σ, √(χ² interval) ≈ ±1.96/√(2N);
* agreement: median and 5–95 % range of σ_PEM/σ_MC over the time points where σ is above 2 %
  of its peak;
* the ratio: Monte-Carlo time / PEM time (goal ≥ 20 at 1,000 crossings), and at equal accuracy:
  the crossings whose 95 % half-width of σ is 1 % (N = (1.96/0.01)²/2 = 19,208; PEM's own grid and
  time-step errors are below 1 %), their time extrapolated linearly from the measured run.
"""
from __future__ import annotations

import argparse
import statistics
import time

from _args import benchmark_args

_P = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
_P.add_argument("--crossings", type=int, default=1000, help="Monte-Carlo crossings (default 1000)")
ARGS = benchmark_args(__doc__, "timed PEM runs after the warm-up (default 5)", _P)

import numpy as np  # noqa: E402

from vbikit.random import Probes, PseudoRoad, pseudo_excitation  # noqa: E402
from vbikit.random.montecarlo import monte_carlo  # noqa: E402
from vbikit.road.psd import RoadPSD  # noqa: E402
from vbikit.scenario import demo_scenario_text, scenario_from_toml  # noqa: E402
from vbikit.scenario.preflight import preflight  # noqa: E402


def main() -> None:
    scenario = scenario_from_toml(demo_scenario_text().replace('contact_length = 0.254',
                                                               'contact_length = 0.254\nloss_of_contact = false'))
    plan = preflight(scenario)
    crossing, dt, data = plan.built.crossing, plan.run.dt, plan.run.kernel_data
    bridge = crossing.bridge
    x = bridge.default_x_at(bridge.default_response_y)
    shapes = bridge.mode_shapes([x], [bridge.default_response_y])
    road = PseudoRoad(RoadPSD.iso("C"))

    def pem():
        return pseudo_excitation(crossing, road, Probes(shapes), dt, data=data)

    pem()  # warm-up
    times = []
    for _ in range(max(1, ARGS.repeat)):
        t0 = time.perf_counter()
        res = pem()
        times.append(time.perf_counter() - t0)
    t_pem = statistics.median(times)

    monte_carlo(crossing, road, range(10_001, 10_033), lambda r: None)  # warm-up (compiles the lanes' kernel)
    t0 = time.perf_counter()
    runs = np.array(monte_carlo(crossing, road, range(1, ARGS.crossings + 1), lambda r: r.displacement(x)))
    t_mc = time.perf_counter() - t0

    s_pem = res.std("displacement")[:, 0]
    s_mc = runs.std(axis=0, ddof=1)
    n = min(s_pem.size, s_mc.size)
    on = s_pem[:n] > 0.02 * s_pem.max()
    ratio = s_pem[:n][on] / s_mc[:n][on]
    print(f"case: {scenario.name} (bilateral tires); {n - 1} steps of {dt:.3g} s")
    print(f"PEM: {res.lines.size} lines, median {t_pem:.2f} s over {len(times)} runs "
          f"(min {min(times):.2f}, max {max(times):.2f}); grid check {res.grid_change('displacement'):.2%}")
    print(f"Monte Carlo: {ARGS.crossings} crossings in {t_mc:.2f} s; 95 % sampling half-width of σ "
          f"±{1.96 / np.sqrt(2 * ARGS.crossings):.1%}")
    print(f"σ_PEM/σ_MC at mid-span: median {np.median(ratio):.4f}, 5–95 % {np.percentile(ratio, 5):.4f}–"
          f"{np.percentile(ratio, 95):.4f}")
    print(f"ratio Monte Carlo / PEM: {t_mc / t_pem:.1f}× at {ARGS.crossings} crossings")
    # equal accuracy: the Monte-Carlo crossings whose 95 % half-width of σ is 1 % (PEM's grid and step
    # errors are below that), their time extrapolated linearly from the measured one
    n_equal = int(np.ceil((1.96 / 0.01) ** 2 / 2))
    print(f"equal accuracy (±1 % on σ): {n_equal} crossings ≈ {t_mc / ARGS.crossings * n_equal:.0f} s, "
          f"ratio ≈ {t_mc / ARGS.crossings * n_equal / t_pem:.0f}×")


if __name__ == "__main__":
    main()
