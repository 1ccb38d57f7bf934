"""Benchmark: a paper study by pseudo-excitation (``vbikit study paper-fig6 --method pem``) against
its Monte-Carlo version (20 road profiles a cell, the paper's), CPU per cell and where it goes.

Run from the repository root::

    python benchmarks/bench_pem_study.py --repeat 2    # every 3rd of Fig. 6's 24 batches (24 cells), MC study whole
    python benchmarks/bench_pem_study.py --stride 1 --repeat 1   # all 72 cells (≈ 4 min of CPU)
    python benchmarks/bench_pem_study.py --fig fig8 --stride 4

The case: ``vbikit.study.paper.paper_study(fig, method="pem")`` (Fig. 6: HS20-44 on the 3D
``paper-bridge-2`` deck at Girder 4; n = 1, 3 … 9 tire points × 45/75/105 km/h × classes B–D:
72 cells), one process, no pools, BLAS on one thread throughout (``vbikit.study.workers`` limits
each worker so).

Measured (CPU time of the process, ``time.process_time``: other jobs on a shared machine count
less; BLAS on one thread, as in the study's worker processes; after a warm-up batch that loads or
compiles the kernels; every figure the minimum over ``--repeat`` runs):

* PEM as the study runs it (``PemStudy.run_batch``: a batch holds the cells that differ only in
  the road class, which share one pseudo-excitation and one set of sampled Gaussian histories,
  ``run_random_levels``; ``peaks="study"``: the headline point's and the first bending moment's
  peak statistics, no up-crossing cross-check) on every ``--stride``-th batch, with its parts: the
  smooth-road crossing (the mean), the σ histories (``pseudo_excitation``: 254 lines, every point,
  load effect and wheel force), the load effects' mode-acceleration combination
  (``_combine_acceleration``), the peaks of 4,000 Gaussian histories (``_sampled_peaks``) and the Poisson
  up-crossing cross-check (``peak_distribution``), per cell;
* the same cells one at a time (``run_random(..., peaks="study")``: no sharing), and reduced as
  the study reduced them before 2026-12-04 (``peaks="all"``: what ``vbikit run --random`` reports,
  statistics of every load effect — moment, shear, two reactions — and the cross-check of each,
  which the study did not store), with this version's blocked cross-check levels and sampling
  layout (the former code's loop over levels was slower still);
* Monte Carlo: the same figure's study with ``--samples`` road profiles a cell
  (``vbikit.study.run.run_study``, ``workers=1``: every crossing in this process), whole, after a
  warm-up run of the study with one profile a cell;
* the extrapolation to the whole study (× cells / measured cells) and the Monte-Carlo crossings a
  cell whose impact-factor mean has PEM's sampling error (4,000 independent peaks, the same
  estimator: 4,000 crossings a cell) and their time at the measured cost of a crossing.
"""
from __future__ import annotations

import argparse
import collections
import tempfile
import time
from pathlib import Path

from _args import benchmark_args

_P = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
_P.add_argument("--fig", default="fig6", help="paper figure (default fig6; not fig11: a road defect)")
_P.add_argument("--stride", type=int, default=3, help="time every stride-th batch (default 3: 8 of Fig. 6's 24, 24 cells)")
_P.add_argument("--samples", type=int, default=20, help="road profiles a cell of the Monte-Carlo study (default 20)")
ARGS = benchmark_args(__doc__, "runs of each part, the minimum reported (default 5; --repeat 2 ≈ 4 min)", _P)

import numpy as np  # noqa: E402

import vbikit.random.response as response  # noqa: E402
from vbikit._blas import single_thread_blas  # noqa: E402
from vbikit.scenario.pipeline import run_random  # noqa: E402
from vbikit.study.paper import paper_study  # noqa: E402
from vbikit.study.pem import PemStudy  # noqa: E402
from vbikit.study.run import run_study  # noqa: E402

PARTS = {"simulate": "smooth-road crossing (mean)", "pseudo_excitation": "σ histories (pseudo_excitation)",
         "_combine_acceleration": "mode-acceleration effects", "_sampled_peaks": "peaks of 4,000 Gaussian histories",
         "peak_distribution": "up-crossing cross-check"}
SPENT: dict[str, float] = collections.defaultdict(float)


def _timed_part(name):
    inner = getattr(response, name)

    def timed(*a, **kw):
        t0 = time.process_time()
        try:
            return inner(*a, **kw)
        finally:
            SPENT[name] += time.process_time() - t0
    setattr(response, name, timed)


def main() -> None:
    with single_thread_blas():  # as in the study's worker processes (vbikit.study.workers)
        _main()


def _main() -> None:
    for name in PARTS:
        _timed_part(name)
    study = paper_study(ARGS.fig, method="pem")
    job = PemStudy(study)
    batches = job.batches()[::max(1, ARGS.stride)]
    cells = [idx for batch in batches for idx in batch]
    t0 = time.process_time()
    job.run_batch(job.batches()[0])
    print(f"warm-up batch (kernel load or compilation): {time.process_time() - t0:.2f} s CPU")
    rows: dict[str, tuple[float, dict[str, float]]] = {}
    labels = {"study": "study batch (classes share one PEM, peaks=\"study\")",
              "single": "cell alone (peaks=\"study\")", "all": "cell as before (peaks=\"all\")"}

    def run(kind):
        if kind == "study":
            for batch in batches:
                job.run_batch(batch)
            return
        for idx in cells:
            run_random(study.scenario_dict(idx), base_dir=study.base_dir, quantiles=job.quantiles,
                       peaks="study" if kind == "single" else "all")

    for _ in range(max(1, ARGS.repeat)):
        for kind, label in labels.items():
            SPENT.clear()
            t0 = time.process_time()
            run(kind)
            row = ((time.process_time() - t0) / len(cells), {k: v / len(cells) for k, v in SPENT.items()})
            if label not in rows or row[0] < rows[label][0]:
                rows[label] = row
    print(f"PEM, {ARGS.fig}: {len(cells)} of {study.size} cells ({len(batches)} batches), CPU a cell (mean):")
    for label, (total, parts) in rows.items():
        print(f"  {label}: {total:.3f} s; " + ", ".join(f"{PARTS[k]} {parts.get(k, 0.0):.3f} s" for k in PARTS))
    study_cell = rows[labels["study"]][0]
    former = rows[labels["all"]][0]
    print(f"  whole study (× {study.size}): {study_cell * study.size:.1f} s CPU (former {former * study.size:.1f} s, "
          f"{former / study_cell:.1f}×)")

    mc = paper_study(ARGS.fig, samples=ARGS.samples)
    with tempfile.TemporaryDirectory() as tmp:
        t0 = time.process_time()
        run_study(paper_study(ARGS.fig, samples=1), Path(tmp) / "warm.nc", workers=1)  # loads the lanes' kernels
        print(f"Monte Carlo warm-up (1 profile a cell): {time.process_time() - t0:.2f} s CPU")
        t_mc = float("inf")
        for k in range(max(1, ARGS.repeat)):
            t0 = time.process_time()
            run_study(mc, Path(tmp) / f"mc{k}.nc", workers=1)
            t_mc = min(t_mc, time.process_time() - t0)
    per = t_mc / mc.size
    print(f"Monte Carlo, {ARGS.fig}: {mc.size:,} crossings ({ARGS.samples} a cell) in {t_mc:.1f} s CPU, "
          f"{per * 1e3:.2f} ms a crossing, {per * ARGS.samples:.3f} s a cell")
    print(f"ratio PEM study / Monte-Carlo study ({ARGS.samples} profiles): "
          f"{study_cell * study.size / t_mc:.1f}× the CPU")
    n_eq = response.SAMPLES
    print(f"Monte Carlo with PEM's sampling error of the mean IM ({n_eq:,} crossings a cell, ±"
          f"{1 / np.sqrt(n_eq):.1%} of σ_IM against ±{1 / np.sqrt(ARGS.samples):.0%}): ≈ {per * n_eq * study.size:,.0f} s "
          f"CPU, {per * n_eq * study.size / (study_cell * study.size):.0f}× PEM's")


if __name__ == "__main__":
    main()
