"""Test-wide settings: the slab-on-girder mode cache goes to a throw-away directory, so tests
never read modes cached by an earlier version of the code and never write to the user's home.

In a distributed run (pytest-xdist, the default) the workers first share the kernel compilation
out (``_share_the_kernel_compilation``): each has some of the groups of
``vbikit.solve.warmup.kernel_groups`` (and the pseudo-excitation, load-effect, static-history,
exact-peak and drive-by kernels) compiled
in a child process — the static start's kernels first, which the integrators' kernels call and then
load instead of each compiling them again (``_AFTER``) — and every test process then loads them from
numba's disk cache, instead of
every worker compiling each kernel its tests meet; numba's cache writes are serialised between the
processes (``_lock_numba_cache_writes``).  When the cache already holds them as an earlier run of the
suite left it (``_cache_is_warm``: a stamp of the sources and of the cache files, written once every
group is in the cache), or holds the kernels vbikit ships compiled (``vbikit.solve.prebuilt.in_cache``: a fresh
clone on a machine they serve), there is nothing to share out and the tests start at once."""
from __future__ import annotations

import atexit
import contextlib
import fcntl
import json
import logging
import os
import shutil
import tempfile
import time
from collections.abc import Callable, Iterator

import pytest

from vbikit.solve.prebuilt import portable_codegen

# numba's code generator as vbikit's processes make it (for the portable CPU model, vbikit.solve.prebuilt), before
# any test module defines a numba function: the test processes and the workers they start compile alike
portable_codegen()

_CACHE = tempfile.mkdtemp(prefix="vbikit-test-cache-")
os.environ["VBIKIT_CACHE_DIR"] = _CACHE
atexit.register(shutil.rmtree, _CACHE, ignore_errors=True)

#: a folder shared by the whole run: made by the process pytest was started in (before it starts the
#: xdist workers, which inherit the variable) and removed when that process exits; for the workers'
#: lock files and for what they build once for all (the kernels, the strict docs site)
RUN_DIR_VARIABLE = "VBIKIT_TEST_RUN_DIR"
if RUN_DIR_VARIABLE not in os.environ or "PYTEST_XDIST_WORKER" not in os.environ:
    os.environ[RUN_DIR_VARIABLE] = tempfile.mkdtemp(prefix="vbikit-test-run-")
    atexit.register(shutil.rmtree, os.environ[RUN_DIR_VARIABLE], ignore_errors=True)
RUN_DIR = os.environ[RUN_DIR_VARIABLE]


def _silence_process_exit() -> None:
    devnull = os.open(os.devnull, os.O_WRONLY)
    os.dup2(devnull, 1)
    os.dup2(devnull, 2)


def pytest_unconfigure(config) -> None:
    """Keep pytest's summary the last line of the run: OpenSees (optional cross-check) prints
    "Process 0 Terminating" from its exit handler after pytest has finished, so once pytest is
    done (and its output capture restored) the process's stdout/stderr go to /dev/null."""
    import sys

    if any(name.startswith("openseespy") for name in sys.modules):
        sys.stdout.flush()
        sys.stderr.flush()
        atexit.register(_silence_process_exit)


def _study_toml(d: dict) -> str:
    """A study file's text from its dict form (name, seed, batch_size, base sections, axes)."""
    lines = [f"name = {json.dumps(d['name'])}", f"seed = {d['seed']}", f"batch_size = {d['batch_size']}"]
    for section, table in d["base"].items():
        lines.append(f"[base.{section}]")
        lines += [f"{k} = {json.dumps(v)}" for k, v in table.items()]
    lines.append("[axes]")
    for k, v in d["axes"].items():
        lines.append(f'"{k}" = ' + (f"{{samples = {v['samples']}}}" if isinstance(v, dict) else json.dumps(v)))
    return "\n".join(lines) + "\n"


@pytest.fixture
def linear_wheel_loads(monkeypatch):
    """The exact integrator's wheel loads held linear on every step (``builtin_integrators.QUADRATIC_WHEEL_LOADS``
    = False), for tests of the kernels' machinery that compare a lean run with the full kernel, which holds them
    linear: with the default quadratic hold on the lean steps the two differ by the hold's own error, not by
    round-off.  (tests/unit/test_wheel_load_hold.py checks the quadratic hold against both.)"""
    monkeypatch.setattr("vbikit.solve.builtin_integrators.QUADRATIC_WHEEL_LOADS", False)


@pytest.fixture
def summary_on_stdout():
    """The check of a folder command's ``--json`` (traffic, lifetime, driveby, rail; docs/cli.md): the command
    ``args`` run again in this process with ``--json`` prints one JSON object on standard output and nothing else,
    the object of ``summary_file`` as that run wrote it, while its report and ``wrote`` lines go to standard
    error, and names the vbikit version that wrote it.  Returns the run's result (``stdout``, ``stderr``)."""
    def check(args: list[str], summary_file):
        from typer.testing import CliRunner

        from vbikit.cli import app

        res = CliRunner().invoke(app, [*args, "--json"])
        assert res.exit_code == 0, res.output
        assert json.loads(res.stdout) == json.loads(summary_file.read_text(encoding="utf-8"))
        assert res.stdout.lstrip().startswith("{") and res.stdout.rstrip().endswith("}")
        assert f"wrote {summary_file}" in res.stderr.splitlines()
        from vbikit import __version__

        assert json.loads(res.stdout)["vbikit_version"] == __version__  # (which version wrote it, as `run`'s inputs say)
        return res
    return check


@pytest.fixture
def study_toml():
    """The function writing a study dict as study-file text (shared by the study and trust tests)."""
    return _study_toml


#: a distributed run of fewer tests than this compiles only what its tests use (on first use), as
#: a run of a few test files should; the whole suite (about 2,400 tests) shares the compilation out
SHARED_COMPILE_MIN_TESTS = 500

log = logging.getLogger(__name__)


@contextlib.contextmanager
def _flock(path: str, blocking: bool = True) -> Iterator[bool]:
    """An exclusive ``flock`` on ``path`` (created) for the block; yields whether it was taken (always
    when ``blocking``).  The lock goes with the process, so a worker that dies releases it."""
    fd = os.open(path, os.O_RDWR | os.O_CREAT, 0o600)
    try:
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | (0 if blocking else fcntl.LOCK_NB))
        except BlockingIOError:
            yield False
            return
        yield True
    finally:
        os.close(fd)  # closing releases the lock


def _lock_numba_cache_writes() -> None:
    """numba adds a compiled variant to a kernel's cache by reading the kernel's index file, adding an
    entry with the first free data-file number and writing both files back (each write atomic, the
    whole not): two processes adding different variants of one kernel at the same time can both
    take number 1, and the index can then name the other variant's data (numba issues #4807,
    #10128).  In this test run, each such read-modify-write holds a lock on the index file."""
    from numba.core import caching

    save = caching.IndexDataCacheFile.save
    if getattr(save, "vbikit_locked", False):
        return

    def locked_save(self, key, data):
        with _flock(self._index_path + ".lock"):
            save(self, key, data)

    locked_save.vbikit_locked = True
    caching.IndexDataCacheFile.save = locked_save


def _compile_groups() -> dict[str, Callable[[], object]]:
    """What the workers share out, in the order they take it (``_AFTER``: which wait for which), and the
    CPU seconds of each child process (its ≈ 1.5 s start included) in the compile phase as the test run's
    4 workers run it on the 2-core machine, four runs measured 2026-12-06/07: static-starts 15–17, implicit-full
    38–39, rk4 31–33, implicit-lanes 30–32, implicit-lean with the run-in's loops 12–13,
    effects-histories-driveby 9–10, random 7–9, moving-loads 7–8 (148–157 in all, against 167–187 for the
    groups before, the run-in's crossing a group of its own, nothing waiting: implicit-full 53–56, rk4 37–41,
    implicit-lanes 41–44, implicit-lean 16, run-in 5, the small ones 27–28): ``kernel_groups`` and the
    pseudo-excitation, load-effect, static-history and exact-peak, and drive-by kernels (kernels of their
    own)."""
    from vbikit.analysis.warmup import compile_effect_kernels, compile_history_kernels
    from vbikit.driveby.warmup import compile_driveby_kernels
    from vbikit.random.warmup import compile_random_kernels
    from vbikit.solve.warmup import SHARED_GROUP, kernel_groups

    groups: dict[str, Callable[[], object]] = dict(kernel_groups())
    groups["random"] = compile_random_kernels

    def effects_histories_driveby() -> None:  # one child process for three small groups (≈ 2 s of CPU each to start)
        compile_effect_kernels()
        compile_history_kernels()
        compile_driveby_kernels()

    groups["effects-histories-driveby"] = effects_histories_driveby
    first = [SHARED_GROUP, "implicit-full", "rk4", "implicit-lanes", "implicit-lean"]
    return {k: groups[k] for k in sorted(groups, key=lambda k: first.index(k) if k in first else len(first))}


#: the groups of ``_compile_groups`` a worker takes only once the group named is done: their kernels call
#: kernels that ``static-starts`` (``vbikit.solve.warmup.SHARED_GROUP``) compiles (the contact law with
#: many lanes, ≈ 10 s of CPU, which RK4's many-lane kernel and the full implicit kernel call; the road
#: reading; the lean law), and after it they load those from numba's cache instead of each compiling them
#: again (≈ 35 s of CPU in all, for ≈ 15 s of its own); the small groups keep the other core busy meanwhile
_AFTER = {name: "static-starts" for name in ("implicit-full", "rk4", "implicit-lanes", "implicit-lean")}


def _compile_in_subprocess(name: str) -> bool:
    """Compile group ``name`` of ``_compile_groups`` in a child process, which writes the kernels to
    numba's disk cache: every test process then loads the same cache-built machine code.  A kernel
    compiled inside a test process can differ from the same kernel loaded from the cache at round-off
    (seen in this suite: 7e-10 N·m in a moment of 1.3e6 N·m), and tests that compare a run in this
    process with one in a Dask or study worker (which loads from the cache) assert identity."""
    import subprocess
    import sys
    from pathlib import Path

    code = ("import logging, sys; sys.path.insert(0, sys.argv[1]); import conftest; "
            "conftest._lock_numba_cache_writes(); conftest._compile_groups()[sys.argv[2]]()")
    res = subprocess.run([sys.executable, "-c", code, str(Path(__file__).parent), name], capture_output=True,
                         text=True, env=os.environ.copy())
    if res.returncode != 0:  # a kernel that fails to compile fails the tests that run it
        log.error("kernel group %s did not compile: %s", name, res.stderr[-2000:])
    return res.returncode == 0


def _share_the_kernel_compilation(folder: str) -> bool:
    """Each worker takes the first group of ``_compile_groups`` that nobody has taken and whose
    prerequisite (``_AFTER``) is done (a lock file per group in ``folder``, held while the group compiles,
    and a marker once done), has it compiled in a child process (``_compile_in_subprocess``: numba
    writes it to its disk cache), and looks again from the top; when every group left waits for a
    prerequisite still compiling, it waits for that, and at the end for the groups the others are still
    compiling; the tests then load every kernel from the cache.  Returns whether every group compiled
    (a group that failed leaves a ``.failed`` marker; the groups after it compile its kernels themselves)."""
    names = list(_compile_groups())

    def lock(name: str) -> str:
        return os.path.join(folder, name + ".lock")

    def done(name: str) -> bool:
        return os.path.exists(os.path.join(folder, name + ".done"))

    waiting: set[str] = set()
    while True:
        blocked = None
        for name in names:
            if done(name):
                continue
            before = _AFTER.get(name)
            if before in names and not done(before):
                blocked = blocked or before
                continue
            with _flock(lock(name), blocking=False) as mine:
                if not mine:
                    waiting.add(name)
                    continue
                if done(name):  # done by another worker since the check above
                    continue
                t0 = time.perf_counter()
                if not _compile_in_subprocess(name):
                    open(os.path.join(folder, name + ".failed"), "w").close()
                open(os.path.join(folder, name + ".done"), "w").close()
                log.info("kernel group %s compiled or loaded (%.1f s)", name, time.perf_counter() - t0)
            break  # look again from the top: a prerequisite may be done now
        else:
            if blocked is None:
                break
            with _flock(lock(blocked)):  # held by the worker compiling it (or free: taken next time round)
                pass
    for name in waiting:
        with _flock(lock(name)):
            pass
    return not any(f.endswith(".failed") for f in os.listdir(folder))


#: the file, in numba's cache folder for vbikit's kernels, holding the stamp of the cache as it was
#: when every group of ``_compile_groups`` had been compiled or loaded into it
WARM_STAMP_FILE = "vbikit-tests-warm-cache.txt"


def _cache_folders() -> list[str] | None:
    """Where numba keeps vbikit's compiled kernels: its cache folder (``NUMBA_CACHE_DIR``, or the one
    ``vbikit.solve.numba_cache.ensure_cache_location`` chose), else the ``__pycache__`` folders
    beside vbikit's sources.  None when numba may have put them elsewhere (a read-only package
    folder without a cache folder set: numba's user-wide folder), where no stamp is kept."""
    import numba

    import vbikit
    from vbikit.solve.numba_cache import ensure_cache_location

    ensure_cache_location()
    if numba.config.CACHE_DIR:
        return [str(numba.config.CACHE_DIR)]
    package = os.path.dirname(os.path.abspath(vbikit.__file__))
    if not os.access(package, os.W_OK):
        return None
    return [os.path.join(root, d) for root, dirs, _ in os.walk(package) for d in dirs if d == "__pycache__"]


def _warm_cache_stamp(folders: list[str]) -> str:
    """A digest of everything numba's cache of the kernels depends on: numba's and Python's versions,
    the host CPU (numba keys its cache by it), each vbikit source file (path, modification time, size: what numba checks a cached kernel's
    source against) and each file of the cache (index ``.nbi`` and data ``.nbc``: path, time, size).
    Any change to a source or to the cache changes it."""
    import hashlib
    import sys

    import numba

    import vbikit

    from llvmlite import binding

    entries = [numba.__version__, sys.version, binding.get_host_cpu_name(), binding.get_host_cpu_features().flatten(),
               repr(sorted(folders))]
    package = os.path.dirname(os.path.abspath(vbikit.__file__))
    for root in [package, *folders]:
        for path, _, files in sorted(os.walk(root)):
            for f in sorted(files):
                if f.endswith((".py", ".nbi", ".nbc")):
                    st = os.stat(os.path.join(path, f))
                    entries.append(f"{os.path.join(path, f)} {st.st_mtime_ns} {st.st_size}")
    return hashlib.sha256("\n".join(entries).encode()).hexdigest()


def _cache_is_warm(folders: list[str] | None) -> bool:
    """Whether the cache holds every group of ``_compile_groups`` as an earlier run of the suite left
    it (its stamp unchanged since): then there is nothing to share out, and each test process loads
    the kernels from the cache as it would after sharing (a fresh clone or a changed source or cache
    shares them out again)."""
    if folders is None:
        return False
    try:
        with open(os.path.join(folders[0], WARM_STAMP_FILE), encoding="utf-8") as f:
            return f.read().strip() == _warm_cache_stamp(folders)
    except OSError:
        return False


def _stamp_the_warm_cache(folders: list[str] | None) -> None:
    """Record the cache's stamp (``_warm_cache_stamp``) once every group is in it."""
    if folders is None:
        return
    path = os.path.join(folders[0], WARM_STAMP_FILE)
    try:
        os.makedirs(folders[0], exist_ok=True)
        tmp = f"{path}.{os.getpid()}"
        with open(tmp, "w", encoding="utf-8") as f:
            f.write(_warm_cache_stamp(folders) + "\n")
        os.replace(tmp, path)
    except OSError as err:  # a read-only cache: the next run shares the compilation out again
        log.info("no stamp of the warm kernel cache written: %s", err)


#: the suite's longest tests (``--durations``, measured 2026-12-06 on the 2-core machine: 30–95 s each while other
#: work ran, a third of that alone), started first: pytest-xdist hands tests out in collection order, so a long test
#: collected late can leave one worker running it alone at the end of the run
RUN_FIRST = (
    "tests/study/test_cli.py::test_paper_all_runs_every_figure",
    "tests/lifetime/test_cli.py::test_cli_cut_down_example_and_resume",
    "tests/lifetime/test_adr.py::test_impact_factor_statistics_of_the_sample_by_hand",
    "tests/lifetime/test_report_wording.py::test_a_missing_total_pot_value_says_the_screening_set_its_threshold",
    "tests/random_vibration/test_random_warmup.py::test_second_process_loads_the_random_kernel_from_the_cache",
    "tests/rail/test_run.py::test_example_cut_down_through_the_cli",
    "tests/trust/test_fuzz.py::test_fuzz_scenarios",
    "tests/random_vibration/test_pem_tire_filter.py::test_multipoint_tire_filter_matches_monte_carlo",
    "tests/traffic/test_docs_example.py::test_the_example_stream_numbers_of_the_page",
    "tests/verification/test_field_calibration.py::test_reported_sigma_matches_the_scatter_over_noise_seeds",
)


def pytest_collection_modifyitems(session, config, items) -> None:
    """``RUN_FIRST`` to the front, in that order, the rest as collected (the same order in every worker, as
    xdist requires).  A name of ``RUN_FIRST`` that a run of the whole suite does not collect (a renamed test)
    is said in a warning."""
    rank = {name: k for k, name in enumerate(RUN_FIRST)}
    first = sorted((item for item in items if item.nodeid in rank), key=lambda item: rank[item.nodeid])
    if not first:
        return
    found = {item.nodeid for item in first}
    items[:] = first + [item for item in items if item.nodeid not in found]
    missing = [name for name in RUN_FIRST if name not in found]
    if missing and len(items) >= SHARED_COMPILE_MIN_TESTS:
        config.issue_config_time_warning(pytest.PytestConfigWarning(
            f"tests/conftest.py RUN_FIRST names tests the run did not collect: {', '.join(missing)}"), stacklevel=2)


def pytest_collection_finish(session) -> None:
    """In an xdist worker of a distributed run of the whole suite (or most of it): share the kernel
    compilation out before the first test (``_share_the_kernel_compilation``)."""
    workers = int(os.environ.get("PYTEST_XDIST_WORKER_COUNT", "1"))
    if "PYTEST_XDIST_WORKER" not in os.environ or workers < 2 or len(session.items) < SHARED_COMPILE_MIN_TESTS:
        return
    _lock_numba_cache_writes()
    folder = os.path.join(RUN_DIR, "kernels")
    os.makedirs(folder, exist_ok=True)
    cache = _cache_folders()
    from vbikit.solve.prebuilt import in_cache

    if in_cache():  # the kernels vbikit ships compiled are in the cache: every group's kernels (nothing to share out)
        return
    with _flock(os.path.join(folder, "stamp.lock")):  # one worker reads the stamp while none writes it
        warm = _cache_is_warm(cache)
    if warm:  # every kernel is in the cache already (about 14 s of child processes loading them saved)
        return
    if _share_the_kernel_compilation(folder):
        with _flock(os.path.join(folder, "stamp.lock")):
            _stamp_the_warm_cache(cache)


@pytest.fixture(scope="session")
def built_once() -> Callable[[str, Callable[[], dict]], dict]:
    """``get(name, build)``: the JSON object ``build()`` returns, built once for the whole run under ``name`` — by the
    first process that asks (under a lock in ``RUN_DIR``; the others wait and read the same object), as
    ``strict_site`` does for the docs site.  For expensive results that several tests only read, which may run in
    different workers.  A ``build`` that raises leaves nothing: the next process to ask builds it again (and fails
    alike)."""
    def get(name: str, build: Callable[[], dict]) -> dict:
        result = os.path.join(RUN_DIR, f"built-{name}.json")
        with _flock(result + ".lock"):
            if not os.path.exists(result):
                value = build()
                with open(result + ".tmp", "w", encoding="utf-8") as f:
                    json.dump(value, f)
                os.replace(result + ".tmp", result)
            with open(result, encoding="utf-8") as f:
                return json.load(f)
    return get


@pytest.fixture(scope="session")
def strict_site() -> dict:
    """The documentation site built once for the whole run with ``mkdocs build --strict`` (from this
    tree's ``src``), by the first worker that asks, under a lock; the others wait and read the same
    build: ``{"site": folder, "returncode": …, "output": stdout + stderr}``."""
    import subprocess
    import sys
    from pathlib import Path

    root = Path(__file__).resolve().parents[1]
    site, result = os.path.join(RUN_DIR, "site"), os.path.join(RUN_DIR, "site.json")
    with _flock(os.path.join(RUN_DIR, "site.lock")):
        if not os.path.exists(result):
            env = {**os.environ, "NO_MKDOCS_2_WARNING": "1",
                   "PYTHONPATH": os.pathsep.join(filter(None, [str(root / "src"), os.environ.get("PYTHONPATH")]))}
            res = subprocess.run([sys.executable, "-m", "mkdocs", "build", "--strict", "-d", site], cwd=root,
                                 capture_output=True, text=True, env=env)
            with open(result, "w", encoding="utf-8") as f:
                json.dump({"site": site, "returncode": res.returncode, "output": res.stdout + res.stderr}, f)
        with open(result, encoding="utf-8") as f:
            return json.load(f)
