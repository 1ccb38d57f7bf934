"""Kernels compiled ahead and shipped with the package: a first run loads them instead of compiling.

numba compiles a kernel on its first call (seconds to a minute each, ``benchmarks/bench_compile.py``) and
keeps the machine code in its on-disk cache (``vbikit.solve.numba_cache``): one index file per kernel,
``<module>.<function>-<line>.py<XY>.nbi``, holding the source file's stamp (numba ≥ 0.60: the SHA-256 of its
content) and, per compiled variant, the key numba looks it up by — the signature, the code generator's
target (LLVM triple, CPU name, CPU features) and the hashes of the function's bytecode and closure — and the
name of the data file (``.nbc``) with the machine code.  numba loads an entry only when all of that matches
the running process and the file's version is its own.

vbikit ships that cache for every kernel ``vbikit compile`` compiles, in ``ARCHIVE`` (with ``MANIFEST``:
numba's and Python's versions, the target, each source file's SHA-256 and its index files), built by
``tools/build_prebuilt_kernels.py``:

* **for every machine of the architecture**: the kernels are compiled for LLVM's *generic* CPU model
  (x86-64: SSE2, no AVX or FMA), and vbikit has numba compile its kernels for that model too
  (``portable_codegen``: ``NUMBA_CPU_NAME=generic`` before the process's first numba function is defined; the
  process's child processes inherit it).  On the kernels' short scalar loops the generic code ran as fast as
  the host CPU's (benchmarks/README.md, "Kernels shipped compiled");
* **seeded, not trusted**: ``seed`` copies each shipped index and its data files into the folder numba reads
  for that source file (numba's own locator: ``__pycache__`` beside the source, ``NUMBA_CACHE_DIR``, or the
  user's cache folder), once per folder and archive (a marker file), and only when every file whose content can
  change a compiled kernel (``kernel_sources``: a kernel's machine code holds the functions it calls and the
  constants it reads) is the one the archive was built from, and numba's and Python's versions and the target
  are the running process's.  The shipped data files have names numba never gives its own
  (``shipped_data_name``), so nothing a process may be reading is replaced; an index the folder had is replaced
  (variants compiled only there compile again when next needed).  numba then checks each entry as it checks its
  own.  Anything else — an edited kernel, other versions, another architecture, a process whose numba target
  was made before vbikit's first kernel, ``VBIKIT_HOST_KERNELS=1`` (compile for this machine's CPU),
  ``NUMBA_CPU_NAME`` set — compiles on first use, as without the archive.
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

#: LLVM's CPU model the shipped kernels are compiled for, and vbikit's kernels in every process
PORTABLE_CPU = "generic"
#: an environment variable; "1": compile vbikit's kernels for this machine's CPU (no shipped kernels loaded)
HOST_KERNELS_VARIABLE = "VBIKIT_HOST_KERNELS"
#: the folder of the shipped kernels, the archive of their cache files and its manifest
PREBUILT_DIR = Path(__file__).resolve().with_name("prebuilt")
ARCHIVE = PREBUILT_DIR / "kernels.tar.xz"
MANIFEST = PREBUILT_DIR / "manifest.json"
#: the package folder: the manifest names source files relative to it
PACKAGE = Path(__file__).resolve().parents[1]

#: a file numba's cache folder gets once a source file's shipped kernels are in it (then the folder is not
#: read again): the prefix, the manifest's digest and the source file's name follow
MARKER_PREFIX = "vbikit-prebuilt-"

_seeded: dict[str, int] = {}


def python_tag() -> str:
    """The Python version as numba's cache file names carry it (``py311``)."""
    return f"py{sys.version_info[0]}{sys.version_info[1]}"


def host_kernels_asked() -> bool:
    """Whether ``VBIKIT_HOST_KERNELS`` asks for kernels compiled for this machine's CPU."""
    return os.environ.get(HOST_KERNELS_VARIABLE, "").strip() not in ("", "0")


def portable_codegen() -> bool:
    """Have numba compile for ``PORTABLE_CPU`` in this process (and its child processes, by the environment)
    unless ``VBIKIT_HOST_KERNELS`` asks otherwise, the user set ``NUMBA_CPU_NAME`` or ``NUMBA_CPU_FEATURES``, or
    numba's CPU target exists already (a numba function defined before vbikit's first kernel: its code
    generator is made for this machine's CPU, and a name changed afterwards would mislabel its code).  Returns
    whether numba's target is the portable one."""
    name = os.environ.get("NUMBA_CPU_NAME")
    if name is not None:
        return name == PORTABLE_CPU
    if host_kernels_asked() or "NUMBA_CPU_FEATURES" in os.environ:
        return False
    import numba
    from numba.core.registry import cpu_target

    if "_toplevel_target_context" in vars(cpu_target):  # (numba makes it at the first function defined)
        log.info("numba's CPU target was made before vbikit's kernels were defined: vbikit compiles them for this "
                 "machine's CPU instead of loading the kernels shipped compiled")
        # (the child processes compile for the same CPU: a study's workers give this process's numbers exactly)
        os.environ["NUMBA_CPU_NAME"] = str(cpu_target.target_context.codegen().magic_tuple()[1])
        numba.core.config.reload_config()
        return False
    os.environ["NUMBA_CPU_NAME"] = PORTABLE_CPU
    numba.core.config.reload_config()  # (numba reads its settings from the environment)
    return True


def target() -> list[str]:
    """numba's code-generation target in this process: LLVM triple, CPU name, CPU features (numba's target is
    made here if it was not yet: for the portable CPU model, ``portable_codegen``)."""
    from numba.core.registry import cpu_target

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


def manifest() -> dict | None:
    """The shipped kernels' manifest (None: none shipped)."""
    try:
        return json.loads(MANIFEST.read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return None


def mismatch(shipped: dict) -> str | None:
    """Why the shipped kernels cannot serve this process (None: they can): numba's or Python's version, or
    numba's target."""
    import numba

    if shipped.get("numba") != numba.__version__:
        return f"they were built with numba {shipped.get('numba')}, this is numba {numba.__version__}"
    if shipped.get("python") != python_tag():
        return f"they were built for Python {shipped.get('python')}, this is {python_tag()}"
    here = target()
    if shipped.get("target") != here:
        return f"they were compiled for the target {shipped.get('target')}, numba's here is {here}"
    return None


def seed() -> int:
    """Copy the shipped kernels that can serve this process into numba's cache (see the module docstring),
    once per process; returns the number of kernel variants added.  Never raises: a shipped kernel that cannot
    be seeded is compiled on first use (logged)."""
    if "done" in _seeded:
        return 0
    _seeded["done"] = 0
    shipped = manifest()
    if shipped is None or not ARCHIVE.exists():
        return 0
    try:
        why = mismatch(shipped)
        if why is not None:
            log.info("the kernels shipped compiled are not used (%s): vbikit compiles them on first use", why)
            return 0
        added = _seed(shipped)
    except Exception as err:  # (a damaged archive, a read-only folder: compiling is always possible)
        log.warning("the kernels shipped compiled could not be put in numba's cache (%s: %s): vbikit compiles them "
                    "on first use", type(err).__name__, err)
        return 0
    _seeded["done"] = added
    if added:
        log.info("%d compiled kernel variants shipped with vbikit put in numba's cache", added)
    return added


def stale_sources(shipped: dict) -> list[str]:
    """The source files of the manifest whose content is not the one the kernels were built from (or that
    are gone), and the kernel sources of the package the manifest does not list (``kernel_sources``)."""
    listed = shipped.get("sources", {})
    changed = [rel for rel, entry in listed.items()
               if not (PACKAGE / rel).exists() or file_sha256(PACKAGE / rel) != entry["sha256"]]
    return changed + [rel for rel in kernel_sources() if rel not in listed]


def _seed(shipped: dict) -> int:
    stale = stale_sources(shipped)
    if stale:  # (a kernel's machine code holds what it calls and the constants it reads: all or nothing)
        log.info("the kernels shipped compiled are not used: %s differ(s) from the sources they were built from; "
                 "vbikit compiles them on first use (tools/build_prebuilt_kernels.py builds them again)",
                 ", ".join(stale[:3]) + (" …" if len(stale) > 3 else ""))
        return 0
    tag = hashlib.sha256(MANIFEST.read_bytes()).hexdigest()[:16]
    archive: dict[str, bytes] | None = None
    added = 0
    for rel, entry in shipped["sources"].items():
        if not entry["indexes"]:
            continue
        source = PACKAGE / rel
        folder = cache_folder(source)
        marker = folder / f"{MARKER_PREFIX}{tag}-{source.stem}"  # (this archive's kernels of this file are in)
        if marker.exists():
            continue
        if archive is None:
            archive = _read_archive()
        member_dir = Path(rel).parent.as_posix()
        for index in entry["indexes"]:
            for name in entry["data"][index]:  # (names numba never gives its own files: nothing it reads is replaced)
                _write(folder / name, archive[f"{member_dir}/{name}"])
            _write(folder / index, archive[f"{member_dir}/{index}"])
            added += len(entry["data"][index])
        _write(marker, b"")
    return added


def kernel_sources() -> list[str]:
    """The package's files (relative paths) whose content can change a compiled kernel: those that define
    numba functions (a function decorated with numba's ``njit`` or with a decorator imported from a module that
    imports numba, such as ``bundles._flat``, or made by ``njit(...)(function)``) and, transitively, the package
    modules they import at module level (a kernel's machine code holds the functions it calls and the values of
    the globals it reads)."""
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
        return {m.name: tar.extractfile(m).read() for m in tar.getmembers() if m.isfile()}


def shipped_data_name(index: str, number: int) -> str:
    """The name a shipped data file of the kernel index ``index`` gets: one numba never gives its own data files
    (``<base>.<number>.nbc``), so that seeding never replaces a file a process may be reading."""
    return f"{index[:-len('.nbi')]}.vbikit{number}.nbc"


def _write(path: Path, data: bytes) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_name(f"{path.name}.tmp.{uuid.uuid4().hex[:16]}")
    try:
        tmp.write_bytes(data)
        os.replace(tmp, path)
    finally:
        if tmp.exists():
            tmp.unlink()
