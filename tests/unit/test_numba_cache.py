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

import os
import subprocess
import sys

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
