"""Build + eigen-solve time of the slab-on-girder presets at their default mesh (no mode cache).

    python benchmarks/bench_bridge.py              # all four presets, 5 repeats, 10 modes
    python benchmarks/bench_bridge.py --modes 30   # more modes
    python benchmarks/bench_bridge.py --convergence   # mesh-convergence table of Bridge 2 (docs/bridges.md)

Prints the median wall time of assembling K and M (scipy.sparse) and of eigsh (shift-invert),
separately, plus the time a cached build takes (reading the .npz).  Writes nothing except a
temporary cache directory, deleted at exit.
"""
from __future__ import annotations

import argparse
import tempfile
import time

import numpy as np

from vbikit.bridge import BRIDGE_PRESETS
from vbikit.bridge.girder_deck import SlabOnGirderBridge

PRESETS = ("paper-bridge-1", "paper-bridge-2", "paper-bridge-3", "cypress-bayou")


def timed(fn, repeat):
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - t0)
    return float(np.median(times)), out


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--modes", type=int, default=10)
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--convergence", action="store_true")
    args = ap.parse_args()
    if args.convergence:
        ref = SlabOnGirderBridge(span=16.76, diaphragms=(0, 8.38, 16.76), n_modes=5, n_elements=320, use_cache=False).frequencies_hz
        print("| elements | element length [m] | f1 | f2 | f3 | f4 | f5 [Hz] | max error vs 320 elements |")
        print("|---|---|---|---|---|---|---|---|")
        for n in (8, 10, 16, 20, 34, 40, 80, 160, 320):
            f = SlabOnGirderBridge(span=16.76, diaphragms=(0, 8.38, 16.76), n_modes=5, n_elements=n, use_cache=False).frequencies_hz
            print(f"| {n} | {16.76 / n:.3f} | " + " | ".join(f"{v:.4f}" for v in f) + f" | {np.abs(f / ref - 1).max():.1e} |")
        return
    with tempfile.TemporaryDirectory() as cache:
        print(f"{'preset':<16} {'DOF':>5} {'assemble [s]':>13} {'eigsh [s]':>10} {'total [s]':>10} {'cached [s]':>10}  f1..f5 [Hz]")
        for name in PRESETS:
            make = lambda: BRIDGE_PRESETS[name].build(n_modes=args.modes, use_cache=False)  # noqa: E731
            t_asm, (K, _, free) = timed(lambda: make().assemble(), args.repeat)
            t_tot, b = timed(lambda: (lambda br: (br.omega, br)[1])(make()), args.repeat)
            BRIDGE_PRESETS[name].build(n_modes=args.modes, cache_dir=cache).omega  # fill the cache
            t_cache, _ = timed(lambda: BRIDGE_PRESETS[name].build(n_modes=args.modes, cache_dir=cache).omega, args.repeat)
            f = ", ".join(f"{v:.3f}" for v in b.frequencies_hz[:5])
            print(f"{name:<16} {free.size:>5} {t_asm:>13.4f} {t_tot - t_asm:>10.4f} {t_tot:>10.4f} {t_cache:>10.4f}  {f}")


if __name__ == "__main__":
    main()
