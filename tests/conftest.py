"""Test-wide settings: the slab-on-girder mode cache goes to a throw-away directory, so tests
never read modes cached by an earlier version of the code and never write to the user's home."""
from __future__ import annotations

import os
import tempfile

os.environ["VBIKIT_CACHE_DIR"] = tempfile.mkdtemp(prefix="vbikit-test-cache-")
