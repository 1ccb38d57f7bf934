"""Step-size sensitivity of the implicit integrators' impact factor on point tires over random roads
(the road rate under a point at a step end, and how it lines up with the road's stations).

    python benchmarks/bench_rate_alignment.py                 # the default cases and scans
    python benchmarks/bench_rate_alignment.py --events 25 31 --ks 0.9 1.0 1.1 --no-demo
    python benchmarks/bench_rate_alignment.py --time 5        # + the lean kernel's thread CPU per crossing
    python benchmarks/bench_rate_alignment.py --no-traffic --no-demo --scenario my.toml

Cases: events of ``bench_traffic``'s stream (``paper-bridge-2``, 10 modes, point tires, class B road at
1 cm stations, a new road seed per event; ``--events``, default the first five with one truck and the
first five with two) and the ``vbikit demo`` crossing (HS20-44, multipoint tire n = 6, class C road,
16.76 m beam).  For each case, with dt the planned step (``plan_run``):

1. the reference: RK4 at dt/8 (``--rk4-spread``: also RK4 at dt/8 × 0.94 … 1.06, its own spread);
2. the default integrator at dt × k for each k of ``--ks`` (default 0.90 … 1.10 in 0.02, then 1.5, 1.53,
   2.0): the displacement impact factor IM (response at Girder 4 midspan; the demo's response point)
   minus the reference's;
3. ``--band``: per k, the rms of the cell-slope road rate (what the implicit integrators read before
   the secant rate) minus the secant rate over the half-step positions (consistent with the road
   crossed), whole and below 15 Hz (the deck's and axles' band);
4. ``--drift``: per k, the accumulated dashpot impulse error of the first point of the first vehicle,
   max_n |Σ_{j<n} [dt (ṙ_j + ṙ_{j+1})/2 − (r_{j+1} − r_j)]| [m] with ṙ the road rate the kernels take
   at a step end (``flat_road`` with the implicit integrators' span dt/2; ``--cell``: the cell's slope, as
   before the secant rate) and r the road under the point: how far the trapezoid of the rates drifts
   from the road the point actually crosses.

``LEAN_COUNTS['fallback']`` is reported (runs the full kernel finished).  ``--time N``: N crossings of
each case at dt through ``simulate``, thread CPU time of the one-lane lean kernel (the variant the default
integrator runs, ``_args.default_step_loops``) per crossing, min and median (run in separate processes per code version to compare versions).
Prints one table; writes nothing.
"""
from __future__ import annotations

import argparse
import dataclasses
import statistics
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).parent))

DEFAULT_KS = [round(0.90 + 0.02 * i, 2) for i in range(11)] + [1.5, 1.53, 2.0]


def traffic_cases(events):
    """(name, crossing, (x, y) response point) of events ``events`` of ``bench_traffic``'s stream
    (None: the first five with one truck and the first five with two)."""
    from bench_traffic import _base, _stream
    from vbikit.traffic.study import traffic_study

    job = traffic_study(_stream(2000, 600.0), _base(0.01), batch_size=16)
    ctx = job.context()
    if events is None:
        ones = [e for e in range(len(job.events)) if len(job.events[e]) == 1][:5]
        twos = [e for e in range(len(job.events)) if len(job.events[e]) == 2][:5]
        events = ones + twos
    out = []
    for e in events:
        c = ctx.template.with_vehicles(job.crossing(e).vehicles, *ctx.road(job.road_seed(e)))
        out.append((f"ev{e}({len(job.events[e])})", c, (None, float(c.bridge.girder_y[3]))))
    return out


def demo_case():
    """The ``vbikit demo`` crossing and its response point."""
    from vbikit.scenario import demo_scenario_text, scenario_from_toml
    from vbikit.scenario.build import build

    built = build(scenario_from_toml(demo_scenario_text(), source="demo.toml"))
    return ("demo", built.crossing, (built.response_x, built.response_y))


def scenario_case(path: str):
    """A scenario file's crossing and its response point (``--scenario``)."""
    from vbikit.scenario import scenario_from_toml
    from vbikit.scenario.build import build

    built = build(scenario_from_toml(Path(path).read_text(), source=Path(path).name))
    return (Path(path).stem, built.crossing, (built.response_x, built.response_y))


def impact(crossing, point) -> float:
    """The displacement impact factor of ``crossing`` (simulated) at ``point``."""
    from vbikit.analysis import point_response
    from vbikit.solve import simulate

    return point_response(simulate(crossing), *point).displacement_impact.impact_factor


def impulse_drift(crossing, dt: float, cell: bool = False) -> float:
    """max_n |Σ_{j<n} [dt (ṙ_j + ṙ_{j+1})/2 − Δr_j]| [m] of the first contact point at step ``dt``, with
    the road elevation and rate the lean kernel takes at each step end (``flat_road``: the secant over the
    half-step positions, span dt/2; ``cell``: the cell's slope, span 0)."""
    from vbikit.solve.plan import plan_run
    from vbikit.solve.system import flat_road, kernel_data, point_positions, road_data

    c = dataclasses.replace(crossing, dt=dt)
    grid = plan_run(c).grid
    data = kernel_data(c)
    travel, speed = grid.travel, grid.speed
    x0, _ = point_positions(data, travel[0], speed[0])
    x1, _ = point_positions(data, travel[-1], speed[-1])
    road = road_data([(v.road, v.road_right) for v in [c]], float(min(x0.min(), x1.min())),
                     float(max(x0.max(), x1.max())))
    span = 0.0 if cell else 0.5 * dt
    r, rd = [], []
    for row in range(0, travel.shape[0], 2):
        x, vx = point_positions(data, travel[row], speed[row])
        a, b = flat_road(data, road, x, vx, span)
        r.append(a[0])
        rd.append(b[0])
    r, rd = np.array(r), np.array(rd)
    err = np.cumsum(0.5 * dt * (rd[1:] + rd[:-1]) - np.diff(r))
    return float(np.max(np.abs(err)))


def rate_error_band(crossing, dt: float, band: float = 15.0) -> tuple[float, float]:
    """The cell-slope road rate (the kernels' before the secant) minus the secant rate over the half-step
    positions (consistent with the road crossed: its trapezoid telescopes), e_n [m/s] of the first
    contact point at step ends of step ``dt`` while on the road: (rms of e, rms of its part below ``band``
    [Hz]).  The part below ``band`` is the force error c·e the deck and the axles respond to; the rest
    is averaged out by them."""
    from vbikit.solve.plan import plan_run
    from vbikit.solve.system import flat_road, kernel_data, point_positions, road_data

    c = dataclasses.replace(crossing, dt=dt)
    grid = plan_run(c).grid
    data = kernel_data(c)
    travel, speed = grid.travel, grid.speed
    last = travel.shape[0] - 1
    x0, _ = point_positions(data, travel[0], speed[0])
    x1, _ = point_positions(data, travel[-1], speed[-1])
    road = road_data([(c.road, c.road_right)], float(min(x0.min(), x1.min())), float(max(x0.max(), x1.max())))
    e = []
    for row in range(2, last - 1, 2):
        x, vx = point_positions(data, travel[row], speed[row])
        _, cell = flat_road(data, road, x, vx, 0.0)
        _, sec = flat_road(data, road, x, vx, 0.5 * dt)
        e.append(cell[0] - sec[0])
    e = np.array(e)
    spec = np.fft.rfft(e)
    f = np.fft.rfftfreq(e.size, dt)
    low = np.fft.irfft(np.where(f <= band, spec, 0.0), e.size)
    return float(np.sqrt(np.mean(e**2))), float(np.sqrt(np.mean(low**2)))


def scan(name, crossing, point, ks, spread: bool, drift: bool, band: bool = False):
    """The case's rows: reference, then ΔIM per k."""
    from vbikit.solve import integrators
    from vbikit.solve.plan import plan_run

    dt = plan_run(crossing).grid.dt
    speeds = [v.speed for v in crossing.vehicles]
    ref = impact(dataclasses.replace(crossing, dt=dt / 8, integrator="rk4"), point)
    line = f"{name:10s} dt {dt * 1e3:.3f} ms  v·dt {min(speeds) * dt * 100:.2f}…{max(speeds) * dt * 100:.2f} cm  " \
           f"IM(rk4, dt/8) {ref:.5f}"
    if spread:
        rk = [impact(dataclasses.replace(crossing, dt=dt / 8 * s, integrator="rk4"), point) - ref
              for s in (0.94, 0.97, 1.03, 1.06)]
        line += f"  rk4 spread {max(abs(v) for v in rk):.1e}"
    print(line, flush=True)
    before = integrators.LEAN_COUNTS["fallback"]
    rows = []
    for k in ks:
        d = impact(dataclasses.replace(crossing, dt=k * dt), point) - ref
        extra = (f"  drift {impulse_drift(crossing, k * dt):.2e} m (cell slope {impulse_drift(crossing, k * dt, True):.2e} m)"
                 if drift else "")
        if band:
            tot, low = rate_error_band(crossing, k * dt)
            extra += f"  rate error rms {tot:.2e} m/s, below 15 Hz {low:.2e} m/s"
        rows.append((k, d))
        print(f"   k {k:5.2f}  dIM {d:+.2e}{extra}", flush=True)
    fb = integrators.LEAN_COUNTS["fallback"] - before
    near = [abs(d) for k, d in rows if 0.895 <= k <= 1.105]
    print(f"   max|dIM| k 0.9…1.1: {max(near, default=float('nan')):.2e}   all k: {max(abs(d) for _, d in rows):.2e}"
          f"   fallbacks {fb}", flush=True)
    return rows


def lean_time(crossing, rounds: int) -> list[float]:
    """Thread CPU time [s] of the one-lane lean kernel per crossing of ``crossing`` at its step."""
    from _args import default_step_loops

    from vbikit.solve import kernels, simulate

    name = default_step_loops()[0]
    inner = getattr(kernels, name)
    spent = []

    def timed(*args):
        t0 = time.thread_time()
        out = inner(*args)
        spent.append(time.thread_time() - t0)
        return out

    setattr(kernels, name, timed)
    try:
        simulate(crossing)  # compiled / cache loaded
        spent.clear()
        for _ in range(rounds):
            simulate(crossing)
    finally:
        setattr(kernels, name, inner)
    return spent


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--events", type=int, nargs="*", default=None)
    ap.add_argument("--ks", type=float, nargs="*", default=DEFAULT_KS)
    ap.add_argument("--no-demo", action="store_true")
    ap.add_argument("--scenario", nargs="*", default=[], help="scenario TOML files to scan as well")
    ap.add_argument("--no-traffic", action="store_true")
    ap.add_argument("--rk4-spread", action="store_true")
    ap.add_argument("--drift", action="store_true", help="also the accumulated dashpot impulse error per k")
    ap.add_argument("--band", action="store_true",
                    help="also the cell-slope rate error against the secant, rms and below 15 Hz (with --no-scan: alone)")
    ap.add_argument("--time", type=int, default=0, help="N: lean kernel thread CPU per crossing, N rounds")
    ap.add_argument("--no-scan", action="store_true")
    args = ap.parse_args(argv)
    import vbikit

    print(f"vbikit from {Path(vbikit.__file__).parent}", flush=True)
    cases = ([] if args.no_traffic else traffic_cases(args.events)) + ([] if args.no_demo else [demo_case()]) + \
        [scenario_case(f) for f in args.scenario]
    for name, crossing, point in cases:
        if not args.no_scan:
            scan(name, crossing, point, args.ks, args.rk4_spread, args.drift, args.band)
        if args.no_scan and args.band:
            from vbikit.solve.plan import plan_run

            dt = plan_run(crossing).grid.dt
            for k in args.ks:
                x0 = crossing.vehicles[0].speed * k * dt / float(np.diff(crossing.road.x[:2])[0])
                tot, low = rate_error_band(crossing, k * dt)
                print(f"{name:10s} k {k:5.2f}  v·dt {x0:.3f} stations (first vehicle)  rate error rms {tot:.2e} m/s, "
                      f"below 15 Hz {low:.2e} m/s", flush=True)
        if args.time:
            t = lean_time(crossing, args.time)
            print(f"{name:10s} lean kernel thread CPU per crossing: min {min(t) * 1e3:.2f} ms, "
                  f"median {statistics.median(t) * 1e3:.2f} ms ({len(t)} calls)", flush=True)


if __name__ == "__main__":
    main()
