"""Kernels compiled ahead and shipped with the package: a first run loads them instead of compiling.

numba compiles a kernel on its first call (seconds to a minute each, ``benchmarks/bench_compile.py``) and
keeps the machine code in its on-disk cache (``vbikit.solve.numba_cache``): one index file per kernel,
``<module>.<function>-<line>.py<XY>.nbi``, holding the source file's stamp (numba ≥ 0.60: the SHA-256 of its
content) and, per compiled variant, the key numba looks it up by — the signature, the code generator's
target (LLVM triple, CPU name, CPU features) and the hashes of the function's bytecode and closure — and the
name of the data file (``.nbc``) with the machine code.  numba loads an entry only when all of that matches
the running process and the file's version is its own.  It does not check the files of the functions a
kernel calls: their code is inside the kernel's.

vbikit ships that cache for every kernel ``vbikit compile`` compiles, in ``ARCHIVE`` (with ``MANIFEST``: the
versions of numba, Python and numpy, numba's target and SVML use, and each kernel source file's SHA-256 and
index files), built by ``tools/build_prebuilt_kernels.py``:

* **for every x86-64 Linux machine since about 2015**: the kernels are compiled for LLVM's ``x86-64-v3``
  CPU model (AVX2, FMA; ``PORTABLE_CPU``), and where the archive can serve a process (``usable``: the
  versions, the LLVM triple and SVML as built, a CPU with the model's features) vbikit has numba compile for
  that model in it too (``portable_codegen``, when the first kernel module is imported and numba's target is
  not yet made; set on numba's configuration, not in the environment: each process, a study's workers
  included, decides for itself).  The model ran the kernels as fast as the host CPU's own
  (benchmarks/README.md, "Kernels shipped compiled");
* **seeded, not trusted**: ``seed`` copies each shipped index and its data files into the folder numba reads
  for that source file (numba's own locator: ``__pycache__`` beside the source, ``NUMBA_CACHE_DIR``, or the
  user's cache folder), once per folder and archive (a marker file), and only when every file whose content
  can change a compiled kernel (the manifest's list, ``kernel_sources``) is the one the archive was built
  from.  The shipped data files have names numba never gives its own and that name the archive
  (``shipped_data_name``), so nothing a process may be reading is replaced; an index the folder had is
  replaced (variants compiled only there compile again when next needed).  numba then checks each entry as
  it checks its own.  Where a source has changed since (an edited or upgraded install), the shipped indexes a
  folder holds are removed (``withdraw``): numba would still accept a kernel whose own file is unchanged,
  with the old code of what it calls inside.
* Anything else — other versions, another architecture or CPU, a process whose numba target was made before
  vbikit's first kernel, ``NUMBA_CPU_NAME`` or ``NUMBA_CPU_FEATURES`` set, ``VBIKIT_HOST_KERNELS=1``, numba's
  JIT disabled — leaves numba as it is: it compiles on first use, for the host CPU, as without the archive.
"""
from __future__ import annotations

import hashlib
import json
import logging
import os
import sys
import tarfile
import types
import uuid
from pathlib import Path

log = logging.getLogger(__name__)

#: LLVM's CPU model the shipped kernels are compiled for (x86-64 microarchitecture level 3: AVX, AVX2, BMI1/2,
#: F16C, FMA, LZCNT, MOVBE), with no features beyond the model's
PORTABLE_CPU = "x86-64-v3"
PORTABLE_FEATURES = ""
#: the host CPU features that model assumes (LLVM's names; level 2's included)
PORTABLE_CPU_NEEDS = ("sse3", "ssse3", "sse4.1", "sse4.2", "popcnt", "cx16", "sahf", "avx", "avx2", "bmi", "bmi2",
                      "f16c", "fma", "lzcnt", "movbe", "xsave")
#: an environment variable; "1": compile vbikit's kernels for this machine's CPU (no shipped kernels used)
HOST_KERNELS_VARIABLE = "VBIKIT_HOST_KERNELS"
#: an environment variable; "0": put no shipped kernels into numba's cache (the archive's build compiles afresh)
SHIPPED_KERNELS_VARIABLE = "VBIKIT_SHIPPED_KERNELS"
#: the folder of the shipped kernels, the archive of their cache files and its manifest
PREBUILT_DIR = Path(__file__).resolve().with_name("prebuilt")
ARCHIVE = PREBUILT_DIR / "kernels.tar.xz"
MANIFEST = PREBUILT_DIR / "manifest.json"
#: the package folder: the manifest names source files relative to it
PACKAGE = Path(__file__).resolve().parents[1]
#: a file numba's cache folder gets once a source file's shipped kernels are in it (then the folder is not
#: read again): the prefix, the archive's build and the source file's name follow
MARKER_PREFIX = "vbikit-prebuilt-"
#: what every shipped data file's name holds (``shipped_data_name``), and only theirs
SHIPPED_MARK = ".vbikit-"

_state: dict[str, object] = {}


def python_tag() -> str:
    """The Python version as numba's cache file names carry it (``py311``)."""
    return f"py{sys.version_info[0]}{sys.version_info[1]}"


def shipped_data_name(index: str, build: str, number: int) -> str:
    """The name the shipped data file ``number`` of the kernel index ``index`` gets in the archive ``build``:
    one numba never gives its own data files (``<base>.<n>.nbc``) and no other archive gives its files, so that
    seeding never replaces a file a process may be reading."""
    return f"{index[:-len('.nbi')]}{SHIPPED_MARK}{build}-{number}.nbc"


def manifest() -> dict | None:
    """The shipped kernels' manifest (None: none shipped)."""
    if "manifest" not in _state:
        try:
            _state["manifest"] = json.loads(MANIFEST.read_text(encoding="utf-8"))
        except (OSError, ValueError):
            _state["manifest"] = None
    return _state["manifest"]  # type: ignore[return-value]


def environment() -> dict[str, object]:
    """What of this process the shipped kernels must match, as the manifest records it (numba imported)."""
    import llvmlite.binding as llvm
    import numba
    import numpy

    return {"numba": numba.__version__, "python": python_tag(), "numpy": ".".join(numpy.__version__.split(".")[:2]),
            "triple": llvm.get_process_triple(), "svml": bool(numba.config.USING_SVML)}


def usable(shipped: dict | None) -> str | None:
    """Why the shipped kernels ``shipped`` (a manifest) cannot serve this process (None: they can): no archive,
    another numba, Python, numpy, LLVM triple or SVML use, or a CPU without the model's features."""
    if shipped is None or not ARCHIVE.exists():
        return "none are shipped"
    here = environment()
    for key, value in here.items():
        if shipped.get(key) != value:
            return f"they were built for {key} {shipped.get(key)}, this process has {value}"
    import llvmlite.binding as llvm

    features = llvm.get_host_cpu_features()
    missing = [f for f in PORTABLE_CPU_NEEDS if not features.get(f)]
    if missing:
        return f"this CPU lacks {', '.join(missing)}, which the {PORTABLE_CPU} model they were compiled for assumes"
    return None


def portable_codegen() -> bool:
    """Have numba compile for the shipped kernels' model (``PORTABLE_CPU``, ``PORTABLE_FEATURES``) in this
    process where they can serve it (``usable``) and numba's CPU target is not yet made (numba makes it when
    the process's first numba function is defined, for good), unless ``VBIKIT_HOST_KERNELS=1``, the user set
    ``NUMBA_CPU_NAME`` or ``NUMBA_CPU_FEATURES``, or numba's JIT is disabled.  Set on numba's configuration (not
    in the environment: numba would then read all its settings again, losing those set at run time).  Returns
    whether numba's target in this process is that model; decided once."""
    if "portable" in _state:
        return bool(_state["portable"])
    import numba
    from numba.core.registry import cpu_target

    config = numba.core.config
    why = None
    if os.environ.get(HOST_KERNELS_VARIABLE, "").strip() not in ("", "0"):
        why = f"{HOST_KERNELS_VARIABLE} asks for this machine's CPU"
    elif "NUMBA_CPU_NAME" in os.environ or "NUMBA_CPU_FEATURES" in os.environ:
        why = "NUMBA_CPU_NAME or NUMBA_CPU_FEATURES is set"
    elif config.DISABLE_JIT:
        why = "numba's JIT is disabled"
    else:
        why = usable(manifest())
    made = "_toplevel_target_context" in vars(cpu_target)
    if why is None and made:
        why = "numba's CPU target was made before vbikit's first kernel was defined"
    portable = why is None
    if portable:
        config.CPU_NAME, config.CPU_FEATURES = PORTABLE_CPU, PORTABLE_FEATURES
    else:
        log.info("the kernels shipped compiled are not used (%s): vbikit compiles them on first use", why)
    portable = portable or (made and list(target()[1:]) == [PORTABLE_CPU, PORTABLE_FEATURES])
    _state["portable"] = portable
    return portable


def target() -> list[str]:
    """numba's code-generation target in this process: LLVM triple, CPU name, CPU features (made here if it was
    not yet, after ``portable_codegen``)."""
    from numba.core.registry import cpu_target

    if "portable" not in _state and "_toplevel_target_context" not in vars(cpu_target):
        portable_codegen()
    return [str(part) for part in cpu_target.target_context.codegen().magic_tuple()]


def file_sha256(path: Path) -> str:
    return hashlib.sha256(path.read_bytes()).hexdigest()


def cache_folder(source: Path) -> Path:
    """The folder numba keeps the kernels of ``source`` (a file of the package) in: numba's own locator, asked
    with a function placed in that file."""
    from numba.core.caching import FunctionCache

    def probe() -> None:
        """A function standing for the kernels of ``source``."""

    placed = types.FunctionType(probe.__code__.replace(co_filename=str(source)), {})
    return Path(FunctionCache(placed).cache_path)


def stale_sources(shipped: dict) -> list[str]:
    """The source files of the manifest whose content is not the one the kernels were built from (or that
    are gone).  (That the manifest lists every file that can change a kernel, ``kernel_sources``, is checked
    when the archive is built and by the tests: parsing the package costs seconds.)"""
    return [rel for rel, entry in shipped.get("sources", {}).items()
            if not (PACKAGE / rel).exists() or file_sha256(PACKAGE / rel) != entry["sha256"]]


def seed(throwaway: bool = False) -> int:
    """Put the shipped kernels into numba's cache where they serve this process (see the module docstring;
    ``portable_codegen`` first), once per process; returns the number of kernel variants added.  Where a kernel
    source has changed since the archive was built, withdraw the shipped indexes seeded before (``withdraw``).
    ``throwaway``: the cache folder is this process's own (nothing seeded: no later process would read it).
    Never raises: a shipped kernel that cannot be seeded is compiled on first use (logged)."""
    if "seeded" in _state:
        return 0
    _state["seeded"] = 0
    if os.environ.get(SHIPPED_KERNELS_VARIABLE, "").strip() == "0" or throwaway or not portable_codegen():
        return 0
    shipped = manifest()
    try:
        stale = stale_sources(shipped)  # type: ignore[arg-type]
        if stale:  # (a kernel's machine code holds what it calls and the constants it reads: all or nothing)
            log.info("the kernels shipped compiled are not used: %s differ(s) from the sources they were built "
                     "from; vbikit compiles them on first use (tools/build_prebuilt_kernels.py builds them again)",
                     ", ".join(stale[:3]) + (" …" if len(stale) > 3 else ""))
            withdraw(shipped)  # type: ignore[arg-type]
            return 0
        added = _seed(shipped)  # type: ignore[arg-type]
    except Exception as err:  # (a damaged archive, a read-only folder, no lzma: compiling is always possible)
        log.warning("the kernels shipped compiled could not be put in numba's cache (%s: %s): vbikit compiles them "
                    "on first use", type(err).__name__, err)
        return 0
    _state["seeded"] = added
    _state["in_cache"] = True
    if added:
        log.info("%d compiled kernel variants shipped with vbikit put in numba's cache", added)
    return added


def in_cache() -> bool:
    """Whether every shipped kernel is in numba's cache for this process (``seed`` put them there, now or in an
    earlier process): nothing ``vbikit compile`` compiles is left to compile."""
    return bool(_state.get("in_cache"))


def _seed(shipped: dict) -> int:
    build = shipped["build"]
    archive: dict[str, bytes] | None = None
    added = 0
    for rel, entry in shipped["sources"].items():
        if not entry["indexes"]:
            continue
        source = PACKAGE / rel
        folder = cache_folder(source)
        marker = folder / f"{MARKER_PREFIX}{build}-{source.stem}"  # (this archive's kernels of this file are in)
        if marker.exists():
            continue
        if archive is None:
            archive = _read_archive()
        member_dir = Path(rel).parent.as_posix()
        for index in entry["indexes"]:
            for name in entry["data"][index]:  # data first: an index never names a file not yet written
                _write(folder / name, archive[f"{member_dir}/{name}"])
            _write(folder / index, archive[f"{member_dir}/{index}"])
            added += len(entry["data"][index])
        _write(marker, b"")
    return added


def withdraw(shipped: dict) -> int:
    """Remove, from the cache folders of the manifest's kernel sources, the index files that name shipped data
    files (and the folders' markers): after a source changed, numba would still load a shipped kernel whose own
    file is unchanged, with the old code of the functions it calls inside.  Returns the indexes removed."""
    removed = 0
    for rel, entry in shipped.get("sources", {}).items():
        if not entry.get("indexes") or not (PACKAGE / rel).exists():
            continue
        folder = cache_folder(PACKAGE / rel)
        for index in entry["indexes"]:
            path = folder / index
            try:
                if SHIPPED_MARK.encode() in path.read_bytes():
                    path.unlink()
                    removed += 1
            except OSError:
                pass
        for marker in folder.glob(f"{MARKER_PREFIX}*-{Path(rel).stem}"):
            marker.unlink(missing_ok=True)
    if removed:
        log.info("%d kernel indexes seeded from an older archive removed from numba's cache", removed)
    return removed


def kernel_sources() -> list[str]:
    """The package's files (relative paths) whose content can change a compiled kernel: those that define
    numba functions (a function decorated with numba's ``njit`` or with a decorator imported from a module that
    imports numba, such as ``bundles._flat``, or made by ``njit(...)(function)``) and, transitively, the package
    modules they import at module level (a kernel's machine code holds the functions it calls and the values of
    the globals it reads).  Parses the whole package: for the archive's build and the tests."""
    import ast

    trees = {".".join(p.relative_to(PACKAGE.parent).with_suffix("").parts).removesuffix(".__init__"):
             (p, ast.parse(p.read_text(encoding="utf-8"))) for p in PACKAGE.rglob("*.py")}

    def imports(tree: ast.Module) -> list[tuple[str, str]]:
        """(module, name) of each module-level import (name "" for ``import module``)."""
        out = []
        for node in tree.body:
            if isinstance(node, ast.ImportFrom) and node.module and node.level == 0:
                out += [(node.module, a.asname or a.name) for a in node.names]
            elif isinstance(node, ast.Import):
                out += [(a.name, "") for a in node.names]
        return out

    uses_numba = {m for m, (_, tree) in trees.items() if any(mod.split(".")[0] == "numba" for mod, _ in imports(tree))}

    def named(node: ast.AST, names: set[str]) -> bool:
        return isinstance(node, ast.Name) and node.id in names or isinstance(node, ast.Attribute) and node.attr == "njit"

    def defines_kernels(tree: ast.Module) -> bool:
        names = {"njit"} | {name for mod, name in imports(tree) if mod in uses_numba and name}
        for node in ast.walk(tree):
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)) and any(
                    named(d.func if isinstance(d, ast.Call) else d, names) for d in node.decorator_list):
                return True
            if isinstance(node, ast.Call) and isinstance(node.func, ast.Call) and named(node.func.func, names):
                return True
        return False

    todo = [m for m, (_, tree) in trees.items() if defines_kernels(tree)]
    seen: set[str] = set()
    while todo:
        m = todo.pop()
        if m not in seen:
            seen.add(m)
            todo += [x for mod, name in imports(trees[m][1]) for x in (mod, f"{mod}.{name}") if x in trees]
    return sorted(trees[m][0].relative_to(PACKAGE).as_posix() for m in seen)


def _read_archive() -> dict[str, bytes]:
    with tarfile.open(ARCHIVE, "r:xz") as tar:
        return {m.name: tar.extractfile(m).read() for m in tar.getmembers() if m.isfile()}  # type: ignore[union-attr]


def _write(path: Path, data: bytes) -> None:
    """``data`` into ``path``, whole or not at all (a temporary file renamed into place)."""
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_name(f"{path.name}.tmp.{uuid.uuid4().hex[:16]}")
    try:
        tmp.write_bytes(data)
        os.replace(tmp, path)
    finally:
        if tmp.exists():
            tmp.unlink()
