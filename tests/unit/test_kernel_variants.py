"""The compiled variants of the kernels (``vbikit.solve.kernels``, "Lanes"): the full implicit kernel,
the general contact law called from Python and the road lookup run only in their many-lane variant
(``MANY_LANES``), one lane too, and no kernel is compiled again for a literal-typed argument."""
from __future__ import annotations

import json
import os
import subprocess
import sys
from dataclasses import replace

import pytest

from vbikit.contact import RigidDiskTire
from vbikit.solve import kernels, simulate
from vbikit.solve.integrators import without_lean
from vbikit.solve.warmup import _tiny_crossing


def _recording(monkeypatch, name: str, position: int, calls: list) -> None:
    """Replace ``kernels.<name>`` by a wrapper recording its ``lanes`` argument (at ``position``)."""
    kernel = getattr(kernels, name)

    def wrapper(*args):
        calls.append((name, args[position]))
        return kernel(*args)

    monkeypatch.setattr(kernels, name, wrapper)


@pytest.mark.parametrize("case", ["rigid-disk", "without-lean"])
def test_one_lane_runs_the_many_lane_variant_of_the_full_kernel(monkeypatch, case):
    """A single rigid-disk crossing (general static start, road at t = 0, full kernel) and a single
    crossing with the lean kernel switched off call ``implicit``, ``contact_forces`` and ``road_at``
    with ``MANY_LANES`` only (the one-lane variants are no longer compiled)."""
    calls: list = []
    _recording(monkeypatch, "implicit", 23, calls)
    _recording(monkeypatch, "contact_forces", 13, calls)
    _recording(monkeypatch, "road_at", 7, calls)
    crossing = _tiny_crossing("exact")
    if case == "rigid-disk":
        simulate(replace(crossing, tire=RigidDiskTire()))
        assert {name for name, _ in calls} == {"implicit", "contact_forces", "road_at"}
    else:
        with without_lean():
            simulate(crossing)
        assert {name for name, _ in calls} == {"implicit"}
    assert all(lanes == kernels.MANY_LANES == (0, 0) for _, lanes in calls)


_SIGNATURES = """
import json, numba, importlib, pkgutil
from vbikit.solve.warmup import compile_kernels
compile_kernels()
import vbikit.solve.kernels as K
out = {}
for m in pkgutil.iter_modules(K.__path__):
    mod = importlib.import_module("vbikit.solve.kernels." + m.name)
    for n, obj in vars(mod).items():
        if isinstance(obj, numba.core.registry.CPUDispatcher) and obj.__module__ == mod.__name__:
            out[m.name + "." + n] = [str(s) for s in obj.signatures]
print(json.dumps(out))
"""


@pytest.mark.slow
def test_every_kernel_variant_compiled_cold(tmp_path):
    """``compile_kernels`` in a fresh process with an empty numba cache (≈ 100 s of CPU): the full
    kernel, the contact law and the road lookup have the many-lane variant only (``contact_forces``
    also RK4's one-lane one), and no kernel has a variant for a literal ``0`` argument (numba compiles
    one for an argument written ``0`` or a counter still typed by its first ``= 0``)."""
    env = {**os.environ, "NUMBA_CACHE_DIR": str(tmp_path)}
    res = subprocess.run([sys.executable, "-c", _SIGNATURES], capture_output=True, text=True, env=env, check=True)
    sigs = json.loads(res.stdout.strip().splitlines()[-1])
    assert len(sigs["implicit_step.implicit"]) == 1 and "UniTuple(int64, 2)" in sigs["implicit_step.implicit"][0]
    assert len(sigs["contact.road_at"]) == 1 and "UniTuple(int64, 2)" in sigs["contact.road_at"][0]
    assert sorted("UniTuple(int64, 2)" in s for s in sigs["contact.contact_forces"]) == [False, True]
    literal_zero = {name: s for name, ss in sigs.items() for s in ss if "Literal[int](0)" in s}
    assert literal_zero == {}
