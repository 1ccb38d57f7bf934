"""Where numba caches the compiled kernels when it cannot write beside the package.

numba caches ``cache=True`` functions in the package's ``__pycache__`` or, when that is
read-only, in the user's cache directory; with neither writable it refuses to define them
(``RuntimeError: cannot cache function ...``), which would make ``import vbikit`` fail on a
read-only install with no writable home.  The kernels then fall back to a directory in the
system's temporary directory (``vbikit.solve.numba_cache.ensure_cache_location``).  Simulated here
in a fresh interpreter by making numba's two locators fail the way a read-only directory does
(no compilation: only the import and the cache location are checked).
"""
from __future__ import annotations

import json
import os
import subprocess
import sys

import numpy as np

SCRIPT = """
import os, tempfile
from numba.core import caching
def deny(self):
    raise PermissionError(13, "read-only", self.get_cache_path())
caching.InTreeCacheLocator.ensure_cache_path = deny
caching.UserWideCacheLocator.ensure_cache_path = deny
from vbikit.solve import kernels
path = kernels.implicit._cache.cache_path
assert path.startswith(tempfile.gettempdir()), path
print(path)
"""


def test_read_only_install_and_home_fall_back_to_a_temporary_cache(tmp_path):
    env = {k: v for k, v in os.environ.items() if k != "NUMBA_CACHE_DIR"}
    res = subprocess.run([sys.executable, "-c", SCRIPT], env=env, capture_output=True, text=True, timeout=120,
                         cwd=tmp_path)
    assert res.returncode == 0, res.stderr[-2000:]
    assert "vbikit-numba-cache" in res.stdout
    assert "numba cannot write its cache" in res.stderr  # the user is told where it goes


def test_the_temporary_cache_directory_must_be_private(tmp_path):
    """numba's cache files are pickles: a directory someone else can write (mode 0o777 here) is not
    used, a fresh private one instead; one of this user's own with mode 0o700 is kept."""
    import os

    from vbikit.solve.numba_cache import _private_dir

    shared = tmp_path / "shared"
    shared.mkdir()
    os.chmod(shared, 0o777)
    got = _private_dir(str(shared))
    assert got != str(shared) and os.stat(got).st_mode & 0o077 == 0
    own = tmp_path / "own"
    assert _private_dir(str(own)) == str(own) and os.stat(own).st_mode & 0o777 == 0o700


LU_SCRIPT = """
import sys
import numpy as np
from numba import njit
from vbikit.solve.kernels import dense
a = np.array([[1e-6, 2.0], [3.0, 1.0]]); p = np.zeros(2, np.int64)
if sys.argv[1] == "linked":  # ``_lu_factor`` compiled into a caller (as the kernels do), cached
    @njit
    def caller(a, n, p):
        dense._lu_factor(a, n, p)
    caller(a, 2, p)
else:  # the inlined variant, compiled on its own by a call from Python
    dense.lu_factor_inline(a, 2, p)
print(p.tolist(), a.tolist())
"""


def test_the_inlined_lu_variant_does_not_load_the_linked_one_s_cache(tmp_path):
    """``dense.lu_factor_inline`` is made from ``_lu_factor``'s Python function: with ``cache=True`` both
    dispatchers read and write one cache entry (numba names it by the function's module, name and
    line), so a call of the inlined variant from Python loaded the linked one, compiled without the
    wrapper that makes it callable from Python, and crashed the interpreter (segmentation fault) once
    ``_lu_factor`` had been cached for the same types.  The variant is not cached: numba inlines it
    into its callers, which are."""
    env = dict(os.environ, NUMBA_CACHE_DIR=str(tmp_path / "cache"))
    runs = [subprocess.run([sys.executable, "-c", LU_SCRIPT, kind], env=env, capture_output=True, text=True,
                           timeout=300, cwd=tmp_path) for kind in ("linked", "inline")]
    for res in runs:
        assert res.returncode == 0, (res.returncode, res.stderr[-2000:])
    assert runs[0].stdout == runs[1].stdout
    # rows swapped, then L = [[1, 0], [1e-6 / 3, 1]], U = [[3, 1], [0, 2 − 1e-6 / 3]]
    piv, lu = (json.loads(part) for part in runs[1].stdout.replace("] [[", "]\n[[").splitlines())
    assert piv == [1, 1] and np.allclose(lu, [[3.0, 1.0], [1e-6 / 3, 2.0 - 1e-6 / 3]], rtol=1e-15, atol=0)
