"""Whole against kernel per crossing, workload by workload: what a crossing costs beyond the step loop
(set-up: road, mode tables, static start; output reduction), and the same against another source tree.

    python benchmarks/bench_per_crossing.py                          # this tree, 5 repeats
    python benchmarks/bench_per_crossing.py --compare /path/to/src   # also another tree's src/, same run
    python benchmarks/bench_per_crossing.py --workloads demo 3d --repeat 9

Workloads (each warmed up once, then ``--repeat`` timed rounds; the figure is the minimum):

* ``demo``: ``vbikit.run`` of the demo scenario (beam, 20 modes, multipoint n = 6, 75 km/h);
* ``3d``: ``vbikit.run`` of ``examples/paper/bridge2_hs20_girder4.toml`` (3D deck, Girder 4);
* ``fig10``: the study runner's ``run_batch`` on the paper's Fig. 10 study (first batch, 2 profiles
  per point), per crossing;
* ``fig10-32``: the same study with its 20 profiles, the first 32-crossing batch (32 lanes) of each
  tire model at 75 km/h (96 crossings a round), per crossing;
* ``paper``: the whole paper programme (Figs. 5–8, 10, 11) with 3 profiles per point (1,296
  crossings, batches of 9 lanes) through ``run_study`` in this process (``workers=1``: datasets
  written to a temporary folder), per crossing;
* ``traffic``: ``TrafficStudy.run_event`` of the first 12 events of the 5,000-truck benchmark stream
  (``bench_traffic.py``'s base: 3D deck, 10 modes, point tires, class B, a road per event), per event;
* ``lifetime``: ``run_event`` of 12 dynamic events of ``bench_lifetime.py``'s lifetime (4-mode beam,
  axle trucks), per event.

Measured: thread CPU time (``time.thread_time``) of the whole call and, inside it, of the compiled
step loop (``vbikit.solve.kernels.lean``, ``lean_lanes``, their ``_quadratic`` variants and ``implicit`` wrapped); "outside" = whole − kernel;
and "calls", the function calls per crossing of one more round under ``cProfile`` (Python functions, and C
functions called from Python): the interpreter's part as a count, which does not swing with the machine's load.  Every workload
runs in a child process per tree (with ``--compare`` the trees alternate round by round, so that both
see the same machine load), with one BLAS thread: on a busy machine BLAS worker threads that wait
for a core turn a 51 × 51 matrix product into milliseconds of spinning.  Writes nothing but numba's
cache.
"""
from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
WORKLOADS = ("demo", "3d", "fig10", "fig10-32", "paper", "traffic", "lifetime")


def _kernel_clock():
    """Wrap the compiled step loops (the lean kernels, both variants: ``lean`` and ``lean_quadratic`` for one
    lane, ``lean_lanes`` and ``lean_lanes_quadratic`` for many, ``_args.default_step_loops`` naming the default's;
    and ``kernels.implicit``, rigid disks and the lean kernels' hand-overs) so that their thread CPU time adds
    up in ``spent[0]``."""
    from _args import default_step_loops

    from vbikit.solve import kernels

    spent = [0.0]

    def wrap(inner):
        def timed(*args, **kw):
            t0 = time.thread_time()
            try:
                return inner(*args, **kw)
            finally:
                spent[0] += time.thread_time() - t0
        return timed

    for name in {"implicit", "lean", "lean_lanes", *default_step_loops()}:
        if hasattr(kernels, name):
            setattr(kernels, name, wrap(getattr(kernels, name)))
    return spent


#: ``--stages``: functions whose thread CPU time is summed per crossing or event (inclusive: a stage
#: that calls another counts it too), module -> attribute path (``a|b``: the first that the tree has,
#: so that ``--compare`` can time an older tree; a stage neither tree has is left out)
STAGES = {
    "random road (window)": ("vbikit.scenario.build", "build_road"),
    "event crossing (vehicles combined)": ("vbikit.traffic.study", "_Template.with_vehicles"),
    "plan (step, budget)": ("vbikit.solve.simulate", "plan_run"),
    "kernel data (tables, bundles)": ("vbikit.solve.system", "kernel_data"),
    "static start": ("vbikit.solve.system", "static_state"),
    "step maps": ("vbikit.solve.modal_step", "exact_step"),
    "vehicle step maps": ("vbikit.solve.modal_step", "vehicle_step"),
    "static reference": ("vbikit.solve.system", "static_modal_history"),
    "static point histories": ("vbikit.analysis.response", "static_point_histories"),
    "contact influences": ("vbikit.analysis.effects", "contact_influence_table|contact_influences"),
    "load-effect histories": ("vbikit.analysis.effects", "load_effect_responses"),
    "output reduction (traffic, all outputs)": ("vbikit.traffic.study", "reduce_crossing"),
    "knot limits (lifetime)": ("vbikit.lifetime.peaks", "knot_limits|with_knot_limits"),
    "rainflow": ("vbikit.fatigue", "rainflow"),
}


def _stage_clocks(stages: dict[str, tuple[str, str]] = STAGES) -> dict[str, float]:
    """Wrap the functions of ``stages`` (name -> (module, attribute path), as ``STAGES``) so that their thread
    CPU time adds up per name."""
    import importlib

    spent = {name: 0.0 for name in stages}
    for name, (module, path) in stages.items():
        importlib.import_module(module)
        found = None
        for alternative in path.split("|"):
            owner = sys.modules[module]  # the module itself (a package may shadow it with a function)
            *parents, attr = alternative.split(".")
            for part in parents:
                owner = getattr(owner, part, None)
            if owner is not None and hasattr(owner, attr):
                found = owner, attr
                break
        if found is None:
            continue
        owner, attr = found
        inner = getattr(owner, attr)

        def timed(*args, _inner=inner, _name=name, **kw):
            t0 = time.thread_time()
            try:
                return _inner(*args, **kw)
            finally:
                spent[_name] += time.thread_time() - t0

        setattr(owner, attr, timed)
    return spent


def _workload(name: str):
    """(function running one round, crossings a round)."""
    if name in ("demo", "3d"):
        import vbikit

        src = ROOT / ("src/vbikit/scenario/demo.toml" if name == "demo" else "examples/paper/bridge2_hs20_girder4.toml")
        return (lambda: vbikit.run(src)), 1
    if name == "fig10":
        from vbikit.study.compute import run_batch
        from vbikit.study.paper import paper_study

        study = paper_study("fig10", 2)
        batch = study.batches()[0] if hasattr(study, "batches") else None
        return (lambda: run_batch(study, batch)), len(batch)
    if name == "fig10-32":
        from vbikit.study.compute import run_batch
        from vbikit.study.paper import paper_study

        study = paper_study("fig10", 20)
        batches = [next(b for b in study.batches() if study.scenario_dict(b[0])["tire"]["model"] == tire
                        and study.scenario_dict(b[0])["crossing"]["speed_kmh"] == 75 and len(b) == 32)
                   for tire in ("point", "multipoint", "disk")]
        return (lambda: [run_batch(study, b) for b in batches]), sum(len(b) for b in batches)
    if name == "paper":
        import atexit
        import shutil
        import tempfile

        from vbikit.study import run_study
        from vbikit.study.paper import FIGURES, paper_study

        studies = [paper_study(fig, 3) for fig in FIGURES]
        tmp = tempfile.mkdtemp(prefix="vbikit-bench-")  # temporary datasets, one per study and round
        atexit.register(shutil.rmtree, tmp, True)

        def programme():
            for study in studies:
                run_study(study, Path(tmp) / f"{study.name}-{time.time_ns()}.nc", workers=1)

        return programme, sum(s.size for s in studies)
    if name == "traffic":
        sys.path.insert(0, str(ROOT / "benchmarks"))
        from bench_traffic import _base, _stream

        from vbikit.traffic.study import traffic_study

        job = traffic_study(_stream(5000, 600.0), _base(0.01), batch_size=16)
        events = range(12)
        return (lambda: [job.run_event(e) for e in events]), len(events)
    if name == "lifetime":
        sys.path.insert(0, str(ROOT / "benchmarks"))
        from bench_lifetime import spec

        from vbikit.lifetime.run import prepare

        prep = prepare(spec(7, 4000.0, 0.001), ".")
        day0 = prep.static_job().run_batch((0,))
        gid = (day0["ev_day"] * 2**20 + day0["ev_index"])[:12]
        dyn = prep.dynamic_job(gid)
        return (lambda: [dyn.run_event(int(g)) for g in gid]), len(gid)
    raise SystemExit(f"unknown workload {name!r}; choose from {', '.join(WORKLOADS)}")


def measure(name: str, repeat: int, stages: bool = False) -> dict:
    """Warm-up, then ``repeat`` rounds: min whole and kernel thread CPU per crossing [ms] (and, with
    ``stages``, the ``STAGES`` of that round)."""
    run, n = _workload(name)
    spent = _kernel_clock()
    clocks = _stage_clocks() if stages else {}
    run()  # warm-up: compile or load the kernels, build the caches
    whole, kernel, parts = [], [], []
    for _ in range(repeat):
        spent[0] = 0.0
        for key in clocks:
            clocks[key] = 0.0
        t0 = time.thread_time()
        run()
        whole.append((time.thread_time() - t0) / n * 1e3)
        kernel.append(spent[0] / n * 1e3)
        parts.append({key: v / n * 1e3 for key, v in clocks.items() if v > 0.0})
    k = min(range(repeat), key=whole.__getitem__)
    return {"workload": name, "whole_ms": whole[k], "kernel_ms": kernel[k], "outside_ms": whole[k] - kernel[k],
            "stages_ms": parts[k], "calls": _calls(run) / n}


def _calls(run) -> int:
    """The function calls of one more round (cProfile's count: Python functions, and C functions called
    from Python, numpy's among them): the interpreter's share of a crossing as a count, which the
    machine's load does not change (the thread CPU times above swing with it)."""
    import cProfile
    import pstats

    profile = cProfile.Profile()
    profile.enable()
    run()
    profile.disable()
    return sum(entry[1] for entry in pstats.Stats(profile).stats.values())


def _child(src: str, name: str, repeat: int, stages: bool = False) -> dict:
    env = dict(os.environ, PYTHONPATH=src, OPENBLAS_NUM_THREADS="1", OMP_NUM_THREADS="1", MKL_NUM_THREADS="1")
    out = subprocess.run([sys.executable, __file__, "--child", name, "--repeat", str(repeat)]
                         + (["--stages"] if stages else []), env=env, capture_output=True, text=True, check=True)
    return json.loads(out.stdout.strip().splitlines()[-1])


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--workloads", nargs="+", default=list(WORKLOADS), choices=WORKLOADS)
    p.add_argument("--repeat", type=int, default=5)
    p.add_argument("--rounds", type=int, default=2, help="alternating rounds per tree with --compare (default 2)")
    p.add_argument("--compare", default=None, help="another tree's src/ folder, measured in the same run")
    p.add_argument("--stages", action="store_true",
                   help="also the thread CPU time of the stages outside the loop (STAGES; inclusive, per crossing)")
    p.add_argument("--child", default=None, help=argparse.SUPPRESS)
    args = p.parse_args()
    if args.child:
        print(json.dumps(measure(args.child, args.repeat, args.stages)))
        return
    here = str(ROOT / "src")
    trees = {"this": here} | ({"compare": args.compare} if args.compare else {})
    print(f"{'workload':10s} {'tree':8s} {'whole ms':>9s} {'kernel ms':>10s} {'outside ms':>11s} {'calls':>7s}")
    for name in args.workloads:
        best: dict[str, dict] = {}
        for _ in range(args.rounds if args.compare else 1):
            for label, src in trees.items():
                r = _child(src, name, args.repeat, args.stages)
                if label not in best or r["whole_ms"] < best[label]["whole_ms"]:
                    best[label] = r
        for label, r in best.items():
            print(f"{name:10s} {label:8s} {r['whole_ms']:9.1f} {r['kernel_ms']:10.1f} {r['outside_ms']:11.1f} "
                  f"{r['calls']:7.0f}")
            for stage, ms in r.get("stages_ms", {}).items():
                print(f"{'':10s} {'':8s} {ms:9.2f}  {stage}")
        if args.compare:
            print(f"{name:10s} {'ratio':8s} {best['compare']['whole_ms'] / best['this']['whole_ms']:9.2f}x "
                  f"(compare / this, whole)")


if __name__ == "__main__":
    main()
