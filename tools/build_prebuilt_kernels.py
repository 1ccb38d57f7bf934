#!/usr/bin/env python3
"""Build the kernels vbikit ships compiled (``src/vbikit/solve/prebuilt/``: ``kernels.tar.xz`` and
``manifest.json``; ``vbikit.solve.prebuilt`` explains how they are used).

    python tools/build_prebuilt_kernels.py          # ≈ 2 min on 2 cores

Runs ``vbikit compile`` in a fresh process with an empty numba cache folder (``NUMBA_CACHE_DIR``, a temporary
folder), numba set to LLVM's ``x86-64-v3`` CPU model with no further features (``NUMBA_CPU_NAME``,
``NUMBA_CPU_FEATURES``: ``prebuilt.PORTABLE_CPU``) and no shipped kernels seeded (``VBIKIT_SHIPPED_KERNELS=0``),
so that every kernel variant vbikit runs is compiled for every machine of that model; then archives each kernel
source file's index and data files (``.nbi``, ``.nbc``; the data files renamed after the build,
``prebuilt.shipped_data_name``) and writes the manifest: numba's, Python's and numpy's versions, the LLVM triple,
SVML use, numba's target, and the SHA-256 of every file whose content can change a compiled kernel
(``prebuilt.kernel_sources``, hashed before the compile and checked unchanged after it).  Run it
after changing any of those files: ``tests/unit/test_prebuilt_kernels.py`` fails until the archive matches the
sources (the kernels then compile on first use, correctly but slowly).  Writes the two files only (each whole,
then renamed into place).
"""
from __future__ import annotations

import hashlib
import io
import json
import os
import subprocess
import sys
import tarfile
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "src"))

from vbikit.solve import prebuilt  # noqa: E402

COMPILE = "import sys; from vbikit.cli import main; sys.argv[0] = 'vbikit'; main()"
TARGET = "import json; import vbikit.solve.kernels; from vbikit.solve.prebuilt import target; print(json.dumps(target()))"


def _index_entries(folder: Path, stem: str, build: str) -> dict[str, tuple[bytes, dict[str, bytes]]]:
    """The index files of the kernels of the source file ``stem`` in the cache folder ``folder``, by name: the
    index (rewritten with the data files under their shipped names, ``prebuilt.shipped_data_name``) and its
    data files by those names."""
    import pickle

    from numba.core.serialize import dumps

    out = {}
    for index in sorted(folder.glob(f"{stem}.*.nbi")):
        stream = io.BytesIO(index.read_bytes())
        version = pickle.load(stream)
        stamp, overloads = pickle.loads(stream.read())
        names = {old: prebuilt.shipped_data_name(index.name, build, k)
                 for k, old in enumerate(sorted(set(overloads.values())), 1)}
        data = {new: (folder / old).read_bytes() for old, new in names.items()}
        rewritten = io.BytesIO()
        pickle.dump(version, rewritten, protocol=-1)
        rewritten.write(dumps((stamp, {key: names[name] for key, name in overloads.items()})))
        out[index.name] = (rewritten.getvalue(), data)
    return out


def main() -> None:
    from numba.core.caching import _CacheLocator

    os.environ[prebuilt.HOST_KERNELS_VARIABLE] = "1"  # (this process reads the indexes: it seeds nothing itself)
    t0 = time.perf_counter()
    sources_before = {rel: prebuilt.file_sha256(prebuilt.PACKAGE / rel) for rel in prebuilt.kernel_sources()}
    here = prebuilt.environment()
    build = hashlib.sha256(json.dumps([sources_before, here, prebuilt.PORTABLE_CPU], sort_keys=True).encode()).hexdigest()[:10]
    with tempfile.TemporaryDirectory(prefix="vbikit-prebuilt-") as cache:
        env = dict(os.environ, NUMBA_CACHE_DIR=cache, NUMBA_CPU_NAME=prebuilt.PORTABLE_CPU,
                   NUMBA_CPU_FEATURES=prebuilt.PORTABLE_FEATURES, **{prebuilt.SHIPPED_KERNELS_VARIABLE: "0"},
                   PYTHONPATH=os.pathsep.join([str(ROOT / "src"), os.environ.get("PYTHONPATH", "")]))
        env.pop(prebuilt.HOST_KERNELS_VARIABLE, None)
        subprocess.run([sys.executable, "-c", COMPILE, "compile"], env=env, check=True)
        target = json.loads(subprocess.run([sys.executable, "-c", TARGET], env=env, check=True, capture_output=True,
                                           text=True).stdout.strip().splitlines()[-1])
        if target != [here["triple"], prebuilt.PORTABLE_CPU, prebuilt.PORTABLE_FEATURES]:
            raise SystemExit(f"the kernels were compiled for {target}, not for {prebuilt.PORTABLE_CPU}")
        sources: dict[str, dict] = {}
        members: list[tuple[str, bytes]] = []
        if {rel: prebuilt.file_sha256(prebuilt.PACKAGE / rel) for rel in prebuilt.kernel_sources()} != sources_before:
            raise SystemExit("a kernel source changed while the kernels compiled: run the build again")
        for rel, sha in sources_before.items():
            path = prebuilt.PACKAGE / rel
            folder = Path(cache) / _CacheLocator.get_suitable_cache_subpath(str(path))
            entries = _index_entries(folder, path.stem, build) if folder.is_dir() else {}
            sources[rel] = {"sha256": sha, "indexes": sorted(entries),
                            "data": {index: sorted(data) for index, (_, data) in entries.items()}}
            member_dir = Path(rel).parent.as_posix()
            for index, (index_bytes, data) in entries.items():
                members.append((f"{member_dir}/{index}", index_bytes))
                members += [(f"{member_dir}/{name}", content) for name, content in sorted(data.items())]
        left = sorted(p.name for p in Path(cache).rglob("*.nbi")
                      if not any(p.name in e["indexes"] for e in sources.values()))
        if left:  # (a module defining kernels that prebuilt.kernel_sources does not recognise)
            raise SystemExit(f"kernels compiled but not archived (their source files are not in "
                             f"prebuilt.kernel_sources()): {', '.join(left)}")
    buffer = io.BytesIO()
    with tarfile.open(fileobj=buffer, mode="w:xz", preset=9) as tar:
        for name, data in members:
            info = tarfile.TarInfo(name)
            info.size = len(data)
            tar.addfile(info, io.BytesIO(data))
    manifest = {**here, "build": build, "cpu": prebuilt.PORTABLE_CPU, "target": target,
                "built": time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime()), "sources": sources}
    prebuilt.PREBUILT_DIR.mkdir(exist_ok=True)
    prebuilt._write(prebuilt.ARCHIVE, buffer.getvalue())
    prebuilt._write(prebuilt.MANIFEST, (json.dumps(manifest, indent=1, sort_keys=True) + "\n").encode())
    n_index = sum(len(e["indexes"]) for e in sources.values())
    print(f"{prebuilt.ARCHIVE.relative_to(ROOT)}: {n_index} kernels, {len(members) - n_index} compiled variants, "
          f"{prebuilt.ARCHIVE.stat().st_size / 1e6:.2f} MB; {len(sources)} source files; "
          f"{time.perf_counter() - t0:.0f} s")


if __name__ == "__main__":
    main()
