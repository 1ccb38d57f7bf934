"""Benchmark: cost of one crossing with each tire model, as ratios to the single-point tire.

Run from the repository root::

    python benchmarks/bench_tires.py              # 5 timed runs per model
    python benchmarks/bench_tires.py --repeat 9
    python benchmarks/bench_tires.py --cold       # fresh numba cache: the warm-ups include JIT compilation

The case (the paper's Fig. 9 crossing): ``hs20_44()`` on ``paper_beam(16.76, "II", n_modes=20)``,
ISO 8608 class C road (seed 1) with the 20 mm depression at the bridge entry
(``Defect.of_kind("depression")``), 75 km/h, RK4 with the automatic time step, loss of contact
on (the default).  Tire models: ``PointTire()``, ``MultiPointTire(6)``, ``DiskTire()``,
``RigidDiskTire()`` (R = 0.5 m, 0.01 m spacing: 61 points per wheel for both disks).

Measured (wall clock, ``time.perf_counter``) per call of ``vbikit.solve.simulate(Crossing(...))``,
i.e. everything a crossing costs (time-step choice with the RK4 stability check, road sampling,
mode tabulation, static start, integration):

* warm-up: one call per model first (loading or compiling the numba kernels), reported apart;
* timed: ``--repeat`` rounds, each round running every model once (interleaved, so that slow
  drifts of a shared machine hit all models alike); median, min, max per model;
* ratio: median of the model / median of the point tire, from the same run; also the ratio of
  the fastest runs, less sensitive to other load on a shared machine;
* context per model: contact points, steps, dt, impact factor, smallest wheel force.

The library is not modified; nothing is written except numba's cache.
"""
from __future__ import annotations

import os
import statistics
import sys
import time

from _args import benchmark_args


ARGS = benchmark_args(__doc__, "timed rounds after the warm-up (default 5, min 3)")  # before numba is imported (--cold)

import numpy as np  # noqa: E402

from vbikit.analysis import point_response  # noqa: E402
from vbikit.bridge import paper_beam  # noqa: E402
from vbikit.contact import DiskTire, MultiPointTire, PointTire, RigidDiskTire  # noqa: E402
from vbikit.road import Defect, RoadPSD, random_profile, with_defects  # noqa: E402
from vbikit.solve import Crossing, simulate  # noqa: E402
from vbikit.vehicle import hs20_44  # noqa: E402

SPEED = 75.0 / 3.6  # [m/s]


def main() -> int:
    repeat = max(3, ARGS.repeat)
    t_start = time.perf_counter()
    beam = paper_beam(16.76, "II", n_modes=20)
    truck = hs20_44()
    road = with_defects(random_profile(RoadPSD.iso("C"), seed=1), [Defect.of_kind("depression")])
    tires = {
        "point": PointTire(),
        "multipoint n=6": MultiPointTire(n_points=6),
        "disk": DiskTire(),
        "rigid disk": RigidDiskTire(),
    }
    crossings = {name: Crossing(beam, truck, tire, road, speed=SPEED, integrator="rk4") for name, tire in tires.items()}

    print("vbikit tire-model benchmark: HS20-44, Bridge 2 beam (16.76 m, Type II, 20 modes), ISO C road seed 1 "
          f"+ 20 mm depression at x = 0, {SPEED * 3.6:.0f} km/h, RK4, automatic dt")
    print(f"python {sys.version.split()[0]}, numpy {np.__version__}, {os.cpu_count()} CPUs"
          + (", fresh numba cache (--cold)" if ARGS.cold else ""))

    warm, results = {}, {}
    for name, cr in crossings.items():
        t0 = time.perf_counter()
        results[name] = simulate(cr)
        warm[name] = time.perf_counter() - t0
    runs: dict[str, list[float]] = {name: [] for name in crossings}
    for _ in range(repeat):
        for name, cr in crossings.items():
            t0 = time.perf_counter()
            simulate(cr)
            runs[name].append(time.perf_counter() - t0)

    base, base_min = statistics.median(runs["point"]), min(runs["point"])
    print(f"\n{'tire model':<16} {'points':>6} {'steps':>7} {'dt [s]':>9} {'warm-up':>8} "
          f"{'median [s]':>10} {'min':>7} {'max':>7} {'ratio':>6} {'(min)':>6} {'IM':>7} {'F_min [kN]':>10}")
    for name, cr in crossings.items():
        res = results[name]
        im = point_response(res).displacement_impact.impact_factor
        rs = runs[name]
        print(f"{name:<16} {cr.contact.n:>6} {res.n_steps:>7} {res.dt:9.3e} {warm[name]:8.3f} "
              f"{statistics.median(rs):10.3f} {min(rs):7.3f} {max(rs):7.3f} {statistics.median(rs) / base:6.2f} "
              f"{min(rs) / base_min:6.2f} "
              f"{im:7.4f} {res.wheel_forces.min() / 1e3:10.2f}")
    print(f"\nratio = median / median of the point tire, (min) = fastest / fastest ({repeat} interleaved rounds); "
          f"total wall time {time.perf_counter() - t_start:.1f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
