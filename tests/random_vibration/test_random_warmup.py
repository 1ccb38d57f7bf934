"""`vbikit compile` also compiles the pseudo-excitation kernel: after ``compile_random_kernels`` in
one process, a second process with the same numba cache runs a pseudo-excitation analysis
without compiling ``vbikit.random.kernel`` again.  Both processes compile for this machine's CPU
(``VBIKIT_HOST_KERNELS=1``): the kernels shipped compiled (``vbikit.solve.prebuilt``) would otherwise spare the
first one its compilation too (tests/unit/test_prebuilt_kernels.py)."""
from __future__ import annotations

import os
import subprocess
import sys

from vbikit.solve.prebuilt import HOST_KERNELS_VARIABLE

SCRIPT = """
import numba.core.event as ev
from vbikit.random.warmup import compile_random_kernels
compiled = []
class Listener(ev.Listener):
    def on_start(self, event):
        if event.kind == "numba:compile":
            compiled.append(event.data["dispatcher"].py_func.__module__)
    def on_end(self, event):
        pass
with ev.install_listener("numba:compile", Listener()):
    compile_random_kernels()
print("RANDOM", sum(m == "vbikit.random.kernel" for m in compiled))
"""


def test_second_process_loads_the_random_kernel_from_the_cache(tmp_path):
    env = dict(os.environ, NUMBA_CACHE_DIR=str(tmp_path), **{HOST_KERNELS_VARIABLE: "1"})
    env.pop("NUMBA_CPU_NAME", None)
    first = subprocess.run([sys.executable, "-c", SCRIPT], env=env, capture_output=True, text=True, check=True)
    second = subprocess.run([sys.executable, "-c", SCRIPT], env=env, capture_output=True, text=True, check=True)
    assert int(first.stdout.split("RANDOM")[1]) >= 1  # cold: the kernel was compiled
    assert int(second.stdout.split("RANDOM")[1]) == 0  # warm: loaded from the cache
