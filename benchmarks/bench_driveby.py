"""Drive-by datasets at scale: the wall time of the published scour set (examples/driveby/scour_1800.toml)
coupled and decoupled, and the decoupled mode's error against the coupled one over mass ratio,
span, speed and roughness.

    python benchmarks/bench_driveby.py --passes 20 --workers 2   # 3 classes × 20 passes, × 600/20 extrapolated
    python benchmarks/bench_driveby.py --passes 600 --workers 2  # the whole set (1800 passes)
    python benchmarks/bench_driveby.py --cpu-only                # 0. only

0. CPU time per pass, one process, one BLAS thread, the two modes alternating on the same passes
   of the example (thread CPU time, ``time.thread_time``, the minimum over ``--rounds``): the
   solution alone (``simulate`` against ``simulate_decoupled`` on the same crossings) and the
   whole pass (``run_case``: crossing, solution, sensors, identification, labels; the cache of
   built crossings emptied before each round, as every pass of a run is new), after a warm-up;
   and the solution of passes that differ only in their road (base speed, no vehicle spread),
   coupled, decoupled, and decoupled with the bridge part shared between them;
1. timing: the example file with ``variability.passes`` = ``--passes`` (per class), coupled and decoupled
   (``coupling_check_every`` = 0: no coupled checks), run by ``run_driveby`` on ``--workers``
   processes after a one-pass warm-up (numba compilation), each run on its own worker processes
   (started, then ended: their start-up counts, as in a command-line run): wall time, and CPU time
   (user + system of this process and its exited worker processes, ``resource.getrusage``: what
   the run costs, whatever else loads the machine); × 600 / passes is the whole set's, extrapolated (printed as
   such unless --passes 600);
2. error map: one pass of the test cart (f_v = 3.2 Hz, undamped) over a simply supported beam
   (4 modes, 2 % damping, 4800 kg/m), coupled and decoupled:
   relative RMS difference of the cart's acceleration, and whether the coupled run's tire left the
   surface (the decoupled mode keeps it in contact); grid: mass ratio (cart / bridge mass) × span
   (15, 25, 40 m, EI scaled so f_1 = 5.62 Hz) × speed × road class (seed 1).

Writes nothing but temporary datasets (deleted).
"""
from __future__ import annotations

import argparse
import copy
import math
import tempfile
import time
import tomllib
from pathlib import Path

EXAMPLE = Path(__file__).resolve().parents[1] / "examples" / "driveby" / "scour_1800.toml"


def _cpu_seconds() -> float:
    """User + system CPU time [s] of this process and of its finished children (the worker
    processes, counted once they have exited): the run's CPU time whatever the machine's load."""
    import resource

    return sum(r.ru_utime + r.ru_stime for r in (resource.getrusage(resource.RUSAGE_SELF),
                                                   resource.getrusage(resource.RUSAGE_CHILDREN)))


def timing(passes: int, workers: int) -> dict[str, float]:
    import numpy as np

    from vbikit.driveby.spec import parse_driveby
    from vbikit.driveby.study import run_driveby
    from vbikit.study.workers import shutdown_workers

    base = tomllib.loads(EXAMPLE.read_text())
    times = {}
    for coupling in ("coupled", "decoupled"):
        for n, key in ((1, "warm-up"), (passes, coupling)):
            data = copy.deepcopy(base)
            data["variability"]["passes"] = n
            data["coupling"], data["coupling_check_every"] = coupling, 0
            with tempfile.TemporaryDirectory() as out:
                t0, c0 = time.perf_counter(), _cpu_seconds()
                run_driveby(parse_driveby(data, EXAMPLE.parent), out, workers=workers, figures=False)
                shutdown_workers()  # the workers exit: their CPU time is counted (a measured run starts its own)
                if key != "warm-up":
                    times[key] = time.perf_counter() - t0
                    times[f"{key}_cpu"] = _cpu_seconds() - c0
    data = copy.deepcopy(base)  # the decoupled mode's error on the example itself: every pass checked
    data["variability"]["passes"] = 4
    data["coupling"], data["coupling_check_every"] = "decoupled", 1
    with tempfile.TemporaryDirectory() as out:
        ds = run_driveby(parse_driveby(data, EXAMPLE.parent), out, workers=workers, figures=False)
    err, df = ds["coupling_error_rms"].values, abs(ds["coupling_frequency_difference_hz"].values)
    times["example_error_median"], times["example_error_max"] = float(np.median(err)), float(err.max())
    times["example_frequency_difference_max_hz"] = float(df.max())
    times["example_resolution_hz"] = float(ds["resolution_hz"].values.mean())
    return times


def cpu_per_pass(passes: int = 30, rounds: int = 5) -> dict[str, float]:
    """Thread CPU time [ms] per pass (module docstring, 0.), minimum over ``rounds``."""
    from vbikit._blas import single_thread_blas
    from vbikit.driveby.decoupled import simulate_decoupled
    from vbikit.driveby.spec import parse_driveby
    from vbikit.driveby import study
    from vbikit.driveby.study import case_crossing, run_case
    from vbikit.solve import simulate

    specs = {}
    for coupling in ("coupled", "decoupled"):
        data = tomllib.loads(EXAMPLE.read_text())
        data["coupling"], data["coupling_check_every"] = coupling, 0
        specs[coupling] = parse_driveby(data, EXAMPLE.parent)
    crossings = [case_crossing(specs["coupled"], specs["coupled"].cases[i]) for i in range(passes)]
    solvers = {"coupled": simulate, "decoupled": simulate_decoupled}
    best = {f"{kind}_{mode}": math.inf for kind in ("solution", "pass") for mode in solvers}
    with single_thread_blas():
        for mode, solve in solvers.items():  # warm-up: compilation, caches
            solve(crossings[0])
            run_case(specs[mode], 0)
        for _ in range(rounds):
            for mode, solve in solvers.items():
                t0 = time.thread_time()
                for c in crossings:
                    solve(c)
                best[f"solution_{mode}"] = min(best[f"solution_{mode}"], (time.thread_time() - t0) / passes * 1e3)
                study._BUILT.clear()  # every pass builds its crossing, as in a run (its passes are all new)
                t0 = time.thread_time()
                for i in range(passes):
                    run_case(specs[mode], i)
                best[f"pass_{mode}"] = min(best[f"pass_{mode}"], (time.thread_time() - t0) / passes * 1e3)
    return best


def shared_bridge(passes: int = 20, rounds: int = 5) -> dict[str, float]:
    """Thread CPU time [ms] of a decoupled solution with and without the bridge part shared
    (``decoupled._bridge_part``): the example at its base speed 20 m/s, no vehicle spread, passes of
    one scour class differing only in their road (a sweep over roads or noise)."""
    from vbikit._blas import single_thread_blas
    from vbikit.driveby import decoupled
    from vbikit.driveby.spec import parse_driveby
    from vbikit.driveby.study import case_crossing
    from vbikit.solve import simulate

    data = tomllib.loads(EXAMPLE.read_text())
    del data["variability"]["speed"]
    data["variability"]["vehicle_spread"] = 0.0
    spec = parse_driveby(data, EXAMPLE.parent)
    classes = len(spec.variability.scour_classes)
    crossings = [case_crossing(spec, spec.cases[classes * i]) for i in range(passes)]
    best = {"coupled": math.inf, "decoupled, bridge solved": math.inf, "decoupled, bridge shared": math.inf}
    with single_thread_blas():
        simulate(crossings[0])
        decoupled.simulate_decoupled(crossings[0])
        for _ in range(rounds):
            for key in best:
                t0 = time.thread_time()
                for c in crossings:
                    if key == "coupled":
                        simulate(c)
                    else:
                        if key.endswith("solved"):
                            decoupled._SHARED.clear()
                        decoupled.simulate_decoupled(c)
                best[key] = min(best[key], (time.thread_time() - t0) / passes * 1e3)
    return best


def print_cpu(passes: int = 30, rounds: int = 5) -> None:
    b = cpu_per_pass(passes, rounds)
    print(f"CPU time per pass (thread time, min of {rounds} rounds of {passes} passes, one process, one BLAS thread):")
    for kind in ("solution", "pass"):
        c, d = b[f"{kind}_coupled"], b[f"{kind}_decoupled"]
        print(f"  {kind:8s}  coupled {c:6.2f} ms   decoupled {d:6.2f} ms   ratio {c / d:5.2f}")
    s = shared_bridge()
    print("solution at 20 m/s, passes differing only in their road: "
          + ", ".join(f"{k} {v:.2f} ms" for k, v in s.items()))


def error_map() -> list[tuple]:
    from vbikit.bridge.beam import EulerBernoulliBeam
    from vbikit.driveby.decoupled import relative_rms_error, simulate_decoupled
    from vbikit.driveby.vehicles import sensor_cart
    from vbikit.road.psd import RoadPSD, random_profile
    from vbikit.solve import Crossing, simulate

    rows = []
    for span in (15.0, 25.0, 40.0):
        mbar = 4800.0
        ei = mbar * (2 * math.pi * 5.62) ** 2 * (span / math.pi) ** 4  # f_1 = 5.62 Hz at every span
        bridge = EulerBernoulliBeam(span=span, EI=ei, mass_per_length=mbar, damping_ratio=0.02, n_modes=4)
        for ratio in (1e-3, 1e-2, 5e-2):
            cart = sensor_cart(mass=ratio * mbar * span)
            for speed in (5.0, 10.0, 20.0):
                for road_class in ("none", "A", "C"):
                    road = None if road_class == "none" else random_profile(RoadPSD.iso(road_class), seed=1,
                                                                            length=span + 20.0, x_start=-10.0)
                    c = Crossing(bridge, cart, speed=speed, approach=2.0, road=road)
                    coupled = simulate(c)
                    b = simulate_decoupled(c).q_ddot[:, 0]
                    lost = bool(coupled.wheel_forces.min() <= 0.0)  # the coupled tire left the surface
                    rows.append((span, ratio, speed, road_class, relative_rms_error(b, coupled.q_ddot[:, 0]), lost))
    return rows


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--passes", type=int, default=20)
    p.add_argument("--workers", type=int, default=2)
    p.add_argument("--no-map", action="store_true", help="timing only")
    p.add_argument("--no-timing", action="store_true", help="error map only")
    p.add_argument("--cpu-only", action="store_true", help="CPU time per pass only (0.)")
    args = p.parse_args()
    if args.cpu_only:
        print_cpu()
        return
    if args.no_timing:
        print_map()
        return
    print_cpu()
    t = timing(args.passes, args.workers)
    scale = 600 / args.passes
    word = "measured" if args.passes == 600 else f"extrapolated × {scale:g} from {3 * args.passes} passes"
    print(f"decoupled error on the example (12 passes, each also run coupled): relative RMS of the sensor record "
          f"median {t.pop('example_error_median'):.3e}, max {t.pop('example_error_max'):.3e}; largest |identified "
          f"frequency difference| {t.pop('example_frequency_difference_max_hz'):.4f} Hz (resolution 1/T "
          f"{t.pop('example_resolution_hz'):.3f} Hz)")
    for k in ("coupled", "decoupled"):
        v, c = t[k], t[f"{k}_cpu"]
        print(f"{k:10s} {3 * args.passes} passes: wall {v:.2f} s, CPU {c:.2f} s; 1800 passes: wall {v * scale:.1f} s, "
              f"CPU {c * scale:.1f} s ({word}), {workers_note(args.workers)}")
    print(f"ratio coupled / decoupled: wall {t['coupled'] / t['decoupled']:.2f}, CPU "
          f"{t['coupled_cpu'] / t['decoupled_cpu']:.2f}")
    if not args.no_map:
        print_map()


def print_map() -> None:
    print("span_m  mass_ratio  speed_m_s  road  decoupled_rel_rms_error  coupled_contact_lost")
    for span, ratio, speed, road, err, lost in error_map():
        print(f"{span:6.1f}  {ratio:10.0e}  {speed:9.1f}  {road:4s}  {err:23.3e}  {'yes' if lost else 'no'}")


def workers_note(workers: int) -> str:
    return f"{workers} workers"


if __name__ == "__main__":
    main()
