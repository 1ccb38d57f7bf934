"""Test-wide settings: the slab-on-girder mode cache goes to a throw-away directory, so tests
never read modes cached by an earlier version of the code and never write to the user's home."""
from __future__ import annotations

import atexit
import os
import shutil
import tempfile

_CACHE = tempfile.mkdtemp(prefix="vbikit-test-cache-")
os.environ["VBIKIT_CACHE_DIR"] = _CACHE
atexit.register(shutil.rmtree, _CACHE, ignore_errors=True)
