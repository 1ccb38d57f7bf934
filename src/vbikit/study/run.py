"""Run a study: batches on local processes or a Dask cluster, stored as they finish, resumable.

Storage (``out`` = e.g. ``results.nc``):

* while running, every finished batch is written to ``<out>.parts/batch-NNNNNN.npz`` by the
  coordinating process, atomically (written to a temporary name, then ``os.replace``), next to
  ``<out>.parts/study.json`` (the canonical study);
* when every batch is there, the parts are assembled into one xarray Dataset (one dimension
  per axis) and written to ``out`` (NetCDF-4, again through a temporary file and a rename);
  the parts directory is then removed unless ``keep_parts``.

While a study runs, ``<out>.lock`` is held (``filelock``): a second run on the same ``out`` is
refused with a message instead of mixing two writers' parts; the lock file is removed when the
run ends, and a lock path that is a symbolic link is refused (``vbikit.study.storage``).  Every
part's SHA-256 is recorded when it is written and checked when it is used: a part changed since
(even rewritten as a valid file with other values) is recomputed on resume and refused when
the parts are assembled.  Worker processes end with the coordinating process, even when it is
killed with SIGKILL (``vbikit.study.workers``).  A study killed at any moment
(SIGKILL, Ctrl-C, a lost machine) loses at most the batches that were running; started again with the same ``out`` it skips the finished batches.  Every
crossing's result depends only on the study (seeds derive from the study seed and the sample
index), so the final dataset is identical to that of an unbroken run.

The same machinery runs any *job* that has what a [`Study`][vbikit.study.Study] has for it —
``name``, ``size`` (work items), ``batches()`` (a tuple of work items per batch) and
``to_json()`` (its canonical text: the resume check) — and its own ``run_batch(batch, threads)``
(arrays of the batch, in a worker), ``part_problem(part, batch)`` (why a stored part is not
usable, or None) and ``assemble(parts)`` (the Dataset from the parts directory, see
``load_part``): e.g. a traffic stream (``vbikit.traffic.study``).
"""
from __future__ import annotations

import hashlib
import io
import json
import logging
import os
import shutil
import time
import zipfile
from concurrent.futures import FIRST_COMPLETED, wait
from pathlib import Path
from typing import Any, Callable, Optional, Sequence

import numpy as np
from numpy.typing import NDArray

from vbikit._files import OutputError, atomic_write, write_text
from vbikit.scenario.schema import key_unit
from vbikit.outputs import OUTPUTS, outputs
from vbikit.study.compute import LONGEST_SPAN, STRAIN_MODE_ERROR, point_names, run_batch
from vbikit.study.spec import Study, StudyError, cf_key_unit as _cf_unit
from vbikit.study.storage import load_part, lock_output, part_bytes, part_checksums, part_path, parts_dir, save_part
from vbikit._validation import default_workers
from vbikit.study.workers import SCHEDULER_CONNECT_TIMEOUT, dask_client, local_pool, shutdown_workers

log = logging.getLogger(__name__)

Progress = Callable[[int, int], None]  # (crossings done, crossings total)


def spec_checksum(study: Study) -> str:
    """SHA-256 of the study's canonical JSON: every part carries it (a part of another study is refused)."""
    return hashlib.sha256(study.to_json().encode()).hexdigest()


def earlier_identities(job) -> tuple[str, ...]:
    """The identities an earlier vbikit version gave this job (its ``earlier_json()``, when it has one: the
    traffic stream's and drive-by's held the base scenario's folder before 2026-12-06): its finished dataset,
    its parts folder and its parts written then are still this job's."""
    return tuple(getattr(job, "earlier_json", tuple)())


def _compute(job, batch: tuple, threads: int) -> dict:
    """One batch of ``job`` (run in a worker): a study's crossings, or the job's own ``run_batch``."""
    own = getattr(job, "run_batch", None)
    return own(batch, threads) if own is not None else run_batch(job, batch, threads)


def _part_problem(parts: Path, k: int, batch: tuple, checksum: str, job, sums: dict[str, str]) -> Optional[str]:
    """Why the part file of batch ``k`` cannot be used (None if it can): unreadable, of another
    batch or study, with missing or non-finite values, or changed since it was written (its
    SHA-256 is not the one recorded in ``sums``)."""
    try:
        data, changed = part_bytes(parts, k, sums)
        with np.load(io.BytesIO(data), allow_pickle=False) as part:
            problem = _content_problem(part, k, batch, checksum, job)
    except (OSError, ValueError, KeyError, EOFError, zipfile.BadZipFile) as err:
        return f"it cannot be read ({type(err).__name__})"
    return problem or changed


def _content_problem(part: Any, k: int, batch: tuple, checksum: str, job) -> Optional[str]:
    if "batch_index" not in part or "spec_checksum" not in part:
        return "it carries no batch index or study checksum"
    if str(part["spec_checksum"]) != checksum and str(part["spec_checksum"]) not in {
            hashlib.sha256(text.encode()).hexdigest() for text in earlier_identities(job)}:
        return "it belongs to another study (checksum differs)"
    if int(part["batch_index"]) != k:
        return f"it holds batch {int(part['batch_index'])}, not batch {k}"
    if hasattr(job, "part_problem"):
        return job.part_problem(part, batch)
    n_axes = len(job.axes)
    index = part["index"]
    if index.shape != (len(batch), n_axes) or not np.array_equal(index, np.array(batch, np.int64).reshape(len(batch), n_axes)):
        return "its grid indices are not those of this batch"
    problem = output_problem(part, len(batch), len(point_names(job.base) or [None]), job.output_names)
    if problem:
        return problem
    if LONGEST_SPAN not in part or part[LONGEST_SPAN].shape != (len(batch),):
        return f"it holds no {LONGEST_SPAN} of its crossings (written by another vbikit version)"
    if "n_steps" in job.output_names and (not np.all(np.isfinite(part["n_steps"])) or np.any(part["n_steps"] < 1)):
        return "its step counts are not valid"
    return None


def output_problem(part: Any, n_rows: int, n_points: int, names: Optional[Sequence[str]] = None) -> Optional[str]:
    """Why the catalogue's outputs ([`vbikit.outputs`][vbikit.outputs]; only those in ``names`` when
    given) stored in a finished part cannot be used
    (None if they can): one missing (the part was written by another vbikit version, or an output
    registered in this process only) or of the wrong shape — (rows, points) for per-point outputs,
    (rows,) per crossing; with one point a part of vbikit versions before response points, (rows,),
    is accepted."""
    for o in outputs(names=names):
        if o.name not in part:
            return f"it holds no {o.name} (written by another vbikit version, or the output is registered here only)"
        shape = part[o.name].shape
        wanted = [(n_rows, n_points)] + ([(n_rows,)] if n_points == 1 else []) if o.scope == "point" else [(n_rows,)]
        if shape not in wanted:
            return f"{o.name} has the wrong shape"
    return None


def output_variables(data: dict[str, NDArray], dims: Sequence[str], names: Optional[Sequence[str]],
                     selected: Optional[Sequence[str]] = None) -> dict[str, Any]:
    """Dataset variables of the catalogue's outputs (only those in ``selected`` when given) from
    ``data`` (per-point outputs with a trailing
    points axis): dimensions ``dims``, and ``point`` for per-point outputs when the response points
    are listed (``names``; None for the [response] shorthand, whose single point has no dimension);
    CF units and long names from the catalogue."""
    variables = {}
    for o in outputs(names=selected):
        arr = data[o.name].astype(np.int64) if o.name == "n_steps" else data[o.name]
        if o.scope == "point" and names is None:
            arr = arr[..., 0]
        point_dim = ["point"] if o.scope == "point" and names is not None else []
        variables[o.name] = ([*dims, *point_dim], arr, {"units": o.cf_unit, "long_name": o.long_name})
    return variables


def part_output(part: Any, name: str, n_points: int) -> NDArray:
    """Output ``name`` of a checked part (``output_problem``), per-point outputs as (rows, points)."""
    values = np.asarray(part[name])
    return values.reshape(-1, n_points) if OUTPUTS[name].scope == "point" else values


def _check_parts(parts: Path, batches: list, checksum: str, job) -> list[str]:
    """Move every damaged or foreign part aside (into ``<parts>/damaged/``, to be recomputed) and
    return one message per part moved."""
    notes = []
    sums = part_checksums(parts)
    for path in sorted(parts.glob("batch-*.npz")):
        try:
            k = int(path.stem.split("-")[1])
        except (IndexError, ValueError):
            k = -1
        problem = "its name is not batch-NNNNNN.npz of this study" if not 0 <= k < len(batches) else \
            _part_problem(parts, k, batches[k], checksum, job, sums)
        if problem is None:
            continue
        aside = parts / "damaged"
        aside.mkdir(exist_ok=True)
        target = aside / f"{path.name}.{int(time.time())}"
        os.replace(path, target)
        notes.append(f"study part {path} is unusable: {problem}; moved to {target}, batch recomputed")
        log.warning(notes[-1])
    return notes


def _prepare_parts(study: Study, out: Path) -> Path:
    parts = parts_dir(out)
    spec = study.to_json()
    if parts.is_symlink():
        raise StudyError(f"{parts} is a symbolic link; the parts of a study are kept in a folder beside --out: remove "
                         "the link or write to another path")
    if parts.exists():
        marker = parts / "study.json"
        if not marker.is_file() or marker.read_text() not in (spec, *earlier_identities(study)):
            raise StudyError(f"{parts} holds partial results of a different run (other inputs, options or version); "
                             "delete it or write to another path")
        if marker.read_text() != spec:  # (an earlier version's identity of this study: this version's from now on)
            write_text(marker, spec)
    else:
        parts.mkdir(parents=True)
        write_text(parts / "study.json", spec)
    return parts


def _pending(parts: Path, n_batches: int) -> list[int]:
    return [k for k in range(n_batches) if not part_path(parts, k).is_file()]


def run_study(
    study: Study,
    out: str | Path,
    workers: Optional[int] = None,
    scheduler: Optional[str] = None,
    progress: Optional[Progress] = None,
    threads: int = 1,
    keep_parts: bool = False,
    connect_timeout: float = SCHEDULER_CONNECT_TIMEOUT,
    step_check: dict | None = None,
):
    """Run (or resume) ``study`` and write its dataset to ``out`` (NetCDF); returns the Dataset.

    ``workers``: local worker processes (default: all cores; 1 runs in this process; kept for
    the next study of this session, see [`shutdown_workers`][vbikit.study.shutdown_workers]);
    ``scheduler``: address of a Dask distributed scheduler (``tcp://host:port``) — then the
    batches run on that cluster instead; ``progress(done, total)`` is called after every
    finished batch (crossings); ``threads``: crossings run at once inside one worker;
    ``connect_timeout`` [s]: how long to try to reach the scheduler; ``step_check``: the base crossing's step
    check (``check_study(…, step_check=True).step_check``, what ``vbikit study run`` passes), stored with the
    dataset (attribute ``step_check``, JSON; ``vbikit.study.check.stored_step_check``) and flagged
    ``step_not_converged`` in its ``warnings`` where it finds the study's step not converged
    (``vbikit.study.check.study_step_flags``).  A study with ``method =
    "pem"`` runs one pseudo-excitation analysis per cell instead (``vbikit.study.pem.PemStudy``).
    """
    from vbikit._validation import checked_workers

    workers = checked_workers(workers, error=StudyError)  # (before anything is written or started)
    out = Path(out)
    if getattr(study, "method", None) == "pem":  # one pseudo-excitation analysis per cell (vbikit.study.pem)
        from vbikit.study.pem import PemStudy

        study = PemStudy(study)
    if out.suffix not in (".nc", ".nc4", ".netcdf"):
        raise StudyError(f"--out must be a NetCDF file name ending in .nc, got {out}")
    try:
        out.parent.mkdir(parents=True, exist_ok=True)
    except OSError as err:
        raise OutputError(err.errno, f"--out {out}: cannot create the folder {out.parent}: {err.strerror}") from None
    with lock_output(out):
        return _run_locked(study, out, workers, scheduler, progress, threads, keep_parts, connect_timeout, step_check)


def _run_locked(study, out, workers, scheduler, progress, threads, keep_parts, connect_timeout, step_check=None):
    if out.exists():
        ds = _open_complete(out, study)
        if ds is not None:
            log.info("%s already holds this finished study", out)
            if progress:
                progress(study.size, study.size)
            return ds
        raise StudyError(f"{out} exists and is not this study's finished dataset; delete it or write to another path")
    parts = _prepare_parts(study, out)
    batches = study.batches()
    checksum = spec_checksum(study)
    _check_parts(parts, batches, checksum, study)
    todo = _pending(parts, len(batches))
    total = study.size
    done = total - sum(len(batches[k]) for k in todo)
    log.info("study %r: %d crossings in %d batches, %d batches to run", study.name, total, len(batches), len(todo))
    if progress:
        progress(done, total)
    t0 = time.perf_counter()

    def finished(k: int, arrays: dict) -> None:
        nonlocal done
        try:
            save_part(parts, k, arrays, checksum)
        except OutputError as err:
            raise OutputError(err.errno, f"{err}; the finished batches are kept in {parts}: run the same command "
                                         "again to resume") from None
        done += len(batches[k])
        if progress:
            progress(done, total)

    if todo:
        _announce_compile(study, [batches[k] for k in todo], scheduler, workers, threads)
        if scheduler is not None:
            _run_dask(study, batches, todo, scheduler, threads, finished, connect_timeout)
        elif (workers or default_workers()) <= 1:
            for k in todo:
                finished(k, _compute(study, batches[k], threads))
        else:
            _run_local(study, batches, todo, workers or default_workers(), threads, finished)
    log.info("study %r: ran %d batches in %.1f s", study.name, len(todo), time.perf_counter() - t0)
    ds = study.assemble(parts) if hasattr(study, "assemble") else assemble(study, parts)
    if step_check is not None:
        from vbikit.study.check import store_step_check

        ds.attrs = store_step_check(ds.attrs, step_check)
    try:
        atomic_write(out, lambda tmp: _to_netcdf(ds, tmp))
    except OutputError as err:
        raise OutputError(err.errno, f"{err}; the finished batches are kept in {parts}: run the same command again "
                                     "to resume") from None
    if not keep_parts:
        shutil.rmtree(parts, ignore_errors=True)
    return ds


def batch_kernels(study, batches, threads: int = 1) -> list:
    """The compiled kernels the ``batches`` (tuples of grid indices) of ``study`` run with ``threads``
    crossings at once in a worker, each once: a parameter study's batch runs its crossings as the lanes
    of kernel calls (``run_batch``: ``BatchSolver.run_many``), split as ``vbikit.solve.batch.lane_chunks``
    splits them — by time step (``batch_steps``), then into ``threads`` calls — so a call of several
    crossings runs its integrator's many-lane kernel (``Integrator.lanes_kernel``; ``newmark``/``exact``:
    ``lean_lanes``) and a call of one its one-lane kernel (``Integrator.kernel``; ``lean``): a batch of
    one, a batch no larger than ``threads`` or one whose crossings all have different steps runs only
    the one-lane kernel.  A job with its own ``run_batch`` (a traffic stream, a PEM study) runs its
    crossings one at a time (one-lane kernel).  The integrator is the first crossing's (``scenario_dict``;
    traffic: the default).  Crossings with a run-in (the job's ``settles_vehicles``, else the first
    crossing's ``crossing.run_in``) run its two loops too (``kernels.run_in_loads``, ``linear_recursion``)."""
    from vbikit.solve.batch import lane_chunks
    from vbikit.solve.integrators import DEFAULT_INTEGRATOR, get_integrator

    first = getattr(study, "scenario_dict", None)  # a parameter study's crossing (traffic: the default)
    name = (first(batches[0][0]).get("crossing", {}).get("integrator") if first is not None and batches else None) \
        or DEFAULT_INTEGRATOR
    integrator = get_integrator(name)
    one_at_a_time = hasattr(study, "run_batch") or first is None
    sizes: set[int] = set()
    steps: dict[str, float] = {}
    for batch in batches:
        if sizes >= {1, 2}:
            break
        if one_at_a_time or len(batch) == 1:
            sizes.add(1)
            continue
        sizes |= {min(len(members), 2) for _, members in lane_chunks(batch_steps(study, batch, steps), threads)}
    makers = ([integrator.kernel] if 1 in sizes else []) + \
        ([integrator.lanes_kernel or integrator.kernel] if 2 in sizes else [])
    kernels = [make() for make in makers if make is not None]
    settles = getattr(study, "settles_vehicles", None)  # (a traffic stream, a lifetime's dynamics: their own rule)
    if settles is None:
        settles = first is not None and bool(batches) and \
            float(first(batches[0][0]).get("crossing", {}).get("run_in") or 0.0) > 0.0
    if settles:  # the vehicles' run-in (vbikit.solve.run_in): its two loops
        from vbikit.solve import kernels as compiled

        kernels += [compiled.run_in_loads, compiled.linear_recursion]
    return [k for i, k in enumerate(kernels) if all(k is not o for o in kernels[:i])]


def batch_steps(study, batch, known: dict[str, float] | None = None) -> list[float]:
    """The time step [s] of each crossing of ``batch`` (grid indices of ``study``): the rule ``simulate``
    and ``BatchSolver.time_step`` apply (``vbikit.solve.timestep.choose_time_step``) to its built
    crossing.  Computed once per set-up and road apart from the seed (``known``: kept across calls):
    the seed changes the elevations, not the sample spacing the step depends on."""
    from vbikit.scenario import build, parse_scenario
    from vbikit.solve.timestep import choose_time_step

    known = {} if known is None else known
    out = []
    for idx in batch:
        d = study.scenario_dict(idx)
        key = json.dumps(d | {"road": {k: v for k, v in (d.get("road") or {}).items() if k != "seed"}},
                         sort_keys=True, default=str)
        if key not in known:
            known[key] = choose_time_step(build(parse_scenario(d, study.base_dir)).crossing)
        out.append(known[key])
    return out


def _announce_compile(study, batches, scheduler, workers, threads: int = 1) -> None:
    """Say that the workers will compile the kernels the ``batches`` run with ``threads`` crossings at
    once (``batch_kernels``) first, each not yet compiled with its expected time (instead of a progress
    bar frozen at 0 %)."""
    from vbikit.solve.compile_notice import announce_compile

    kernels = batch_kernels(study, batches, threads)
    if not kernels:
        return
    if scheduler is not None:
        who = f"every Dask worker of {scheduler} whose machine has not compiled them"
    elif (workers or default_workers()) <= 1:
        who = "this process"
    else:
        who = f"each of the {workers or default_workers()} worker processes, on its first batch"
    announce_compile(kernels, who)
    if may_hand_over(study):
        from vbikit.solve import kernels as compiled

        announce_compile(compiled.implicit, f"{who}, for the steps where a wheel leaves or lands on the road")


def may_hand_over(study) -> bool:
    """Whether the crossings of ``study`` (its base scenario and axes) may run the full contact kernel
    (``integrators._full``): rigid-disk tires, or a road class rougher than ISO 8608 class C, on which
    wheels leave the road (``hopping_road_class``) — for the compile notice (a base given as a file is
    not read: False)."""
    base = getattr(study, "base", None) or {}
    tires = {(base.get("tire") or {}).get("model")}
    classes = {(base.get("road") or {}).get("class")}
    for axis in getattr(study, "axes", ()):
        if axis.key == "tire.model":
            tires |= set(axis.values)
        elif axis.key == "road.class":
            classes |= set(axis.values)
    return "rigid-disk" in tires or any(hopping_road_class(c) for c in classes if isinstance(c, str))


def hopping_road_class(road_class: str) -> bool:
    """Whether a scenario's ``road.class`` (ISO 8608 A … H or the paper's good / average / poor) is one on
    which wheels leave the road: its G_d(n₀) above ``timestep.EXACT_SMOOTH_ROAD_ROUGHNESS``, the bound the
    exact integrator's step rule draws there (class D and rougher)."""
    from vbikit.road.psd import ISO_CLASSES, PAPER_CLASSES
    from vbikit.solve.timestep import EXACT_SMOOTH_ROAD_ROUGHNESS

    key = PAPER_CLASSES.get(road_class, road_class)
    return key in ISO_CLASSES and ISO_CLASSES[key] > EXACT_SMOOTH_ROAD_ROUGHNESS


def _run_local(study, batches, todo, workers, threads, finished) -> None:
    pool = local_pool(workers)
    try:
        futures = {pool.submit(_compute, study, batches[k], threads): k for k in todo}
        pending = set(futures)
        while pending:
            ready, pending = wait(pending, return_when=FIRST_COMPLETED)
            for fut in ready:
                finished(futures[fut], fut.result())
    except BaseException:  # Ctrl-C or a failed batch: keep what is written, stop the rest now
        shutdown_workers(kill=True)
        raise


def _run_dask(study, batches, todo, scheduler, threads, finished, connect_timeout) -> None:
    client = dask_client(scheduler, StudyError, connect_timeout)
    from dask.distributed import as_completed

    try:
        [study_f] = client.scatter([study], broadcast=True)
        futures = [client.submit(_compute, study_f, batches[k], threads, key=f"vbikit-batch-{k}-{os.getpid()}",
                                 pure=False) for k in todo]
        keys = {f.key: k for f, k in zip(futures, todo)}
        for fut in as_completed(futures):
            finished(keys[fut.key], fut.result())
    finally:
        client.close()


def _to_netcdf(ds, path: Path) -> None:
    """Write ``ds`` as NetCDF-4; the library's errors on a full disk ("NetCDF: HDF error") become OSError."""
    try:
        ds.to_netcdf(path, engine="netcdf4")
    except RuntimeError as err:
        free = shutil.disk_usage(path.parent).free
        raise OSError(28 if free < 1 << 20 else 5, f"{err} ({free} bytes free)") from None


def _open_complete(out: Path, study: Study):
    import xarray as xr

    # the job's identity, and those a finished dataset of an earlier version holds for it (``earlier_json``;
    # a study's ``finished_json``: also before its step rule was part of it)
    known = {study.to_json(), *earlier_identities(study), *getattr(study, "finished_json", tuple)()}
    try:
        with xr.open_dataset(out, engine="netcdf4") as ds:
            if ds.attrs.get("study") in known:
                return ds.load()
    except (OSError, ValueError):
        return None
    return None


def study_flag_attrs(study: Study, names: Optional[Sequence[str]], data: dict[str, NDArray],
                     spans: NDArray, strain_errors: Optional[NDArray] = None) -> dict[str, str]:
    """The dataset's ``warnings`` and ``flag_codes`` (``vbikit.analysis.checks.dataset_flag_attrs``):
    an implausible static deflection in any crossing (``implausible_deflection_dataset_flags``: its
    peak ``max_static_displacement`` against the crossing's longest span ``spans`` [m]), the response
    points whose impact factor rests on a small static reference (``small_static_dataset_flags``)
    crossings whose contact forces did not converge in some steps (``unconverged_dataset_flags``) and crossings
    whose strain is not converged in the modes (``strain_errors``, per crossing and point: ``strain_mode_errors``;
    ``strain_mode_dataset_flags``); each needs its output among the study's outputs (``max_static_displacement``;
    for the second ``impact_factor`` and several points too; ``unconverged_steps``; ``strain_impact_factor``)."""
    from vbikit.analysis.checks import (dataset_flag_attrs, implausible_deflection_dataset_flags,
                                        small_static_dataset_flags, strain_mode_dataset_flags,
                                        unconverged_dataset_flags)

    def describe(index: tuple[int, ...]) -> str:  # (a file by its name, as the coordinate: no folder in a dataset)
        return "the crossing at " + ", ".join(
            f"{a.key} = {a.scenario_value(i) if a.seeds is not None else a.coordinate_values[i]}"
            for a, i in zip(study.axes, index)) if study.axes else "the crossing"

    strain = strain_errors is not None and "strain_impact_factor" in data and bool(np.isfinite(strain_errors).any())
    if "max_static_displacement" not in data and "unconverged_steps" not in data and not strain:
        return {}
    flags = []
    small: list = []
    if "max_static_displacement" in data:
        static = data["max_static_displacement"]
        flags += implausible_deflection_dataset_flags(static, spans, names, describe=describe)
        small = (small_static_dataset_flags(names, static)
                 if names is not None and len(names) > 1 and "impact_factor" in data else [])
    if "unconverged_steps" in data:
        flags += unconverged_dataset_flags(data["unconverged_steps"], describe=describe)
    if strain:
        flags += strain_mode_dataset_flags(strain_errors, names, describe=describe)
    return dataset_flag_attrs(flags + small)


def assemble(study: Study, parts: Path):
    """The study Dataset from the finished-batch files in ``parts`` (all must be present)."""
    import xarray as xr

    from vbikit._version import __version__

    dims = [a.name for a in study.axes]
    shape = study.shape
    batches = study.batches()
    names = point_names(study.base)
    n_points = len(names or [None])
    selected = study.output_names
    data = {o.name: np.full(shape + ((n_points,) if o.scope == "point" else ()), np.nan)
            for o in outputs(names=selected)}
    hist_parts = []
    spans = np.full(shape, np.nan)  # each crossing's longest span [m]
    strain_errors = np.full(shape + (n_points,), np.nan)  # each crossing's strain-mode error per point (NaN: none)
    sums = part_checksums(parts)
    for k in range(len(batches)):
        path = part_path(parts, k)
        part = load_part(parts, k, sums)
        idx = tuple(part["index"].T)
        problem = output_problem(part, len(part["index"]), n_points, selected)
        if problem:  # e.g. an output registered in this process but not in the workers
            raise StudyError(f"batch {k} ({path}): {problem}")
        for name in data:
            values = part_output(part, name, n_points)
            if shape:
                data[name][idx] = values
            else:  # a study without axes: one crossing, 0-d variables
                data[name][()] = values[0]
        if shape:
            spans[idx] = part[LONGEST_SPAN]
        else:
            spans[()] = part[LONGEST_SPAN][0]
        if STRAIN_MODE_ERROR in part:  # (a part of an earlier version has none: not judged)
            errors = np.asarray(part[STRAIN_MODE_ERROR]).reshape(-1, n_points)
            if shape:
                strain_errors[idx] = errors
            else:
                strain_errors[()] = errors[0]
        if study.histories:
            hist_parts.append((idx, part["displacement_history"]))
    variables = output_variables(data, dims, names, selected)
    if study.histories:
        n_t = max(h.shape[1] for _, h in hist_parts)
        hist = np.full(shape + (n_t,), np.nan)
        for idx, h in hist_parts:
            if shape:
                hist[idx + (slice(0, h.shape[1]),)] = h
            else:
                hist[: h.shape[1]] = h[0]
        variables["displacement_history"] = ([*dims, "step"], hist, {
            "units": "m", "long_name": "response-point deflection at t = step * dt (NaN after the crossing ended)"})
    coords = {}
    if names is not None:
        coords["point"] = ("point", np.array(names, dtype=object), {"long_name": "response point ([[response.points]] name)"})
    for a in study.axes:
        values = a.coordinate_values
        text = isinstance(values[0], str)
        unit = "1" if a.is_samples else _cf_unit(key_unit(a.key), text)
        coords[a.name] = (a.name, np.array(values) if not text else np.array(values, dtype=object),
                          {"scenario_key": a.key, "units": unit,
                           "long_name": "sample index" if a.is_samples else f"scenario key {a.key}"})
        if a.is_samples:
            coords[a.key.replace(".", "_")] = (a.name, np.array(a.seeds, np.int64),
                                               {"long_name": f"{a.key} derived from the study seed and the sample index",
                                                "units": "1"})
    attrs = {
        "title": study.name or "vbikit study",
        "study": study.to_json(),
        "vbikit_version": __version__,
        "axes": json.dumps({a.name: a.key for a in study.axes}),
        "Conventions": "CF-1.8",
    }
    attrs |= study_flag_attrs(study, names, data, spans, strain_errors)
    return xr.Dataset(variables, coords=coords, attrs=attrs)
