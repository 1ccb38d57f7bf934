"""The kernels shipped compiled (``vbikit.solve.prebuilt``): built from the present sources, loaded by a
fresh install without compiling, never used where a source differs, and the codegen choice they need.

A fresh process with an empty ``NUMBA_CACHE_DIR`` stands for a fresh install: numba's compile events are
counted over the demo crossing as ``vbikit run`` computes it (``simulate`` and the impact factor), and over
everything ``vbikit compile`` compiles (``warmup.compile_kernels``' tiny crossing of every integrator and
tire path, and the random, load-effect, static-history and drive-by kernels).
"""
from __future__ import annotations

import json
import os
import subprocess
import sys

import pytest

from vbikit.solve import prebuilt

REBUILD = "run `python tools/build_prebuilt_kernels.py` (about 2 minutes) and commit src/vbikit/solve/prebuilt/"

COUNT_COMPILES = """
import json, sys
from numba.core import event
count = []
class Compiles(event.Listener):
    def on_start(self, ev): pass
    def on_end(self, ev): count.append(getattr(ev.data.get("dispatcher"), "py_func", None).__name__)
event.register("numba:compile", Compiles())
from vbikit.analysis import point_response
from vbikit.scenario import demo_scenario_text, scenario_from_toml
from vbikit.scenario.preflight import preflight
from vbikit.solve import simulate
built = preflight(scenario_from_toml(demo_scenario_text(), source="demo.toml")).built
im = point_response(simulate(built.crossing), built.response_x, built.response_y).displacement_impact.impact_factor
if sys.argv[1] == "all":  # (everything `vbikit compile` compiles, which the test workers then need not share out)
    from vbikit.analysis.warmup import compile_effect_kernels, compile_history_kernels
    from vbikit.driveby.warmup import compile_driveby_kernels
    from vbikit.random.warmup import compile_random_kernels
    from vbikit.solve.warmup import compile_kernels
    compile_kernels(); compile_random_kernels(); compile_effect_kernels(); compile_history_kernels()
    compile_driveby_kernels()
from vbikit.solve.prebuilt import target
print(json.dumps({"compiled": count, "im": im, "target": target()}))
"""


def _fresh_process(tmp_path, *args: str, **env_changes: str | None) -> dict:
    env = {k: v for k, v in os.environ.items() if k not in ("NUMBA_CPU_NAME", prebuilt.HOST_KERNELS_VARIABLE)}
    env["NUMBA_CACHE_DIR"] = str(tmp_path / "numba-cache")
    for k, v in env_changes.items():
        if v is None:
            env.pop(k, None)
        else:
            env[k] = v
    res = subprocess.run([sys.executable, "-c", COUNT_COMPILES, *args], env=env, capture_output=True, text=True,
                         timeout=600, cwd=tmp_path, check=False)
    assert res.returncode == 0, res.stderr[-3000:]
    return json.loads(res.stdout.strip().splitlines()[-1])


def _usable() -> None:
    shipped = prebuilt.manifest()
    assert shipped is not None, f"no kernels shipped compiled: {REBUILD}"
    why = prebuilt.usable(shipped)
    if why is not None:  # (the environment, not the code: another numba, Python, numpy or CPU)
        pytest.skip(f"the kernels shipped compiled do not serve this environment: {why}")


def test_the_shipped_kernels_are_built_from_the_present_sources():
    shipped = prebuilt.manifest()
    assert shipped is not None, f"no kernels shipped compiled: {REBUILD}"
    stale = prebuilt.stale_sources(shipped)
    assert not stale, f"the kernels shipped compiled are older than {', '.join(stale)}: {REBUILD}"
    assert set(shipped["sources"]) == set(prebuilt.kernel_sources())
    kernels = [rel for rel, entry in shipped["sources"].items() if entry["indexes"]]
    assert "solve/kernels/lean.py" in kernels and "solve/kernels/assembly.py" in kernels  # (njit and bundles._flat)


@pytest.fixture(scope="module")
def fresh_install(built_once, tmp_path_factory) -> dict:
    """A fresh install with the shipped kernels (``_fresh_process(…, "all")``): the demo's impact factor, then
    everything ``vbikit compile`` compiles, with every compile event counted.  Made once for the run
    (``built_once``): two tests read it, the one below and the host-kernel comparison (which ran the demo alone in
    a fresh process of its own before: the same demo, the same count of compile events over it and more)."""
    _usable()
    return built_once("prebuilt-fresh-install", lambda: _fresh_process(tmp_path_factory.mktemp("fresh-install"), "all"))


def test_a_fresh_install_runs_the_demo_and_every_integrator_without_compiling(fresh_install):
    out = fresh_install
    assert out["target"][1:] == [prebuilt.PORTABLE_CPU, prebuilt.PORTABLE_FEATURES]
    assert out["compiled"] == [], f"compiled on a fresh install: {sorted(set(out['compiled']))}: {REBUILD}"
    assert out["im"] == pytest.approx(0.2451, abs=5e-5)  # (the demo's IM, README "Quick start")


def test_without_the_shipped_kernels_numba_compiles_for_this_machine_and_gets_the_same_result(tmp_path, fresh_install):
    """``VBIKIT_HOST_KERNELS=1``: numba's target is the host CPU, the shipped kernels are not put in the cache,
    and the demo's impact factor is the same to round-off as a fresh install's with the shipped kernels
    (``fresh_install``, which compiled nothing) (the generic and the host code differ in
    instruction selection only: fused multiply-adds, vector width)."""
    _usable()
    host = _fresh_process(tmp_path, "demo", VBIKIT_HOST_KERNELS="1")
    assert host["target"][1] != prebuilt.PORTABLE_CPU
    assert "lean_quadratic" in host["compiled"]
    shipped = fresh_install
    assert shipped["compiled"] == []
    assert host["im"] == pytest.approx(shipped["im"], rel=1e-9)


def test_a_user_cpu_name_is_kept(tmp_path):
    """``NUMBA_CPU_NAME`` set by the user: vbikit does not change it, and puts none of the shipped kernels
    (compiled for another model) into the cache."""
    _usable()
    code = ("import vbikit.solve.kernels; from vbikit.solve import prebuilt; "
            "print(prebuilt.target()[1], prebuilt._state['seeded'], len(list(__import__('pathlib').Path('c').rglob('*.nbi'))))")
    env = {k: v for k, v in os.environ.items() if k != prebuilt.HOST_KERNELS_VARIABLE}
    env.update(NUMBA_CPU_NAME="x86-64", NUMBA_CACHE_DIR=str(tmp_path / "c"))
    res = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, timeout=300, check=False,
                         cwd=tmp_path)
    assert res.returncode == 0, res.stderr[-2000:]
    assert res.stdout.split() == ["x86-64", "0", "0"]


def _changed(rel: str) -> dict:
    shipped = prebuilt.manifest()
    assert shipped is not None, REBUILD
    changed = json.loads(json.dumps(shipped))
    changed["sources"][rel]["sha256"] = "0" * 64
    return changed


def test_a_changed_kernel_source_seeds_nothing_and_withdraws_what_was_seeded(monkeypatch):
    """One kernel file differing from the one the archive was built from: no kernel of the archive is put in
    the cache, and the shipped indexes seeded before are withdrawn (a kernel's machine code holds the functions
    it calls and the constants it reads, from other files too: numba checks only the kernel's own file)."""
    changed = _changed("solve/kernels/newton.py")
    assert prebuilt.stale_sources(changed) == ["solve/kernels/newton.py"]
    written, withdrawn = [], []
    monkeypatch.setattr(prebuilt, "_state", {"portable": True, "manifest": changed})
    monkeypatch.setattr(prebuilt, "_write", lambda path, data: written.append(path))
    monkeypatch.setattr(prebuilt, "withdraw", lambda shipped: withdrawn.append(shipped))
    assert prebuilt.seed() == 0
    assert written == [] and withdrawn == [changed]


def test_withdraw_removes_the_seeded_indexes_only(tmp_path, monkeypatch):
    shipped = prebuilt.manifest()
    assert shipped is not None, REBUILD
    rel, entry = next((rel, e) for rel, e in shipped["sources"].items() if len(e["indexes"]) >= 2)
    seeded, own = entry["indexes"][:2]
    (tmp_path / seeded).write_bytes(b"index naming " + prebuilt.shipped_data_name(seeded, "b", 1).encode())
    (tmp_path / own).write_bytes(b"index naming " + own.replace(".nbi", ".1.nbc").encode())
    stem = rel.rsplit("/", 1)[-1].removesuffix(".py")
    (tmp_path / f"{prebuilt.MARKER_PREFIX}b-{stem}").write_bytes(b"")
    monkeypatch.setattr(prebuilt, "cache_folder", lambda source: tmp_path)
    prebuilt.withdraw({"sources": {rel: entry}})
    assert sorted(p.name for p in tmp_path.iterdir()) == [own]


def test_the_codegen_choice_leaves_numba_s_other_settings_and_the_environment_alone(tmp_path):
    """numba's settings made at run time before vbikit's first kernel stay (numba reads them all again from the
    environment when a variable of its own changes there); no variable is exported to child processes."""
    code = ("import os, numba; numba.config.BOUNDSCHECK = 1; numba.config.CACHE_DIR = os.getcwd(); "
            "import vbikit.solve.kernels; from vbikit.solve.prebuilt import target; "
            "print(numba.config.BOUNDSCHECK, numba.config.CACHE_DIR == os.getcwd(), "
            "os.environ.get('NUMBA_CPU_NAME'), target()[1])")
    env = {k: v for k, v in os.environ.items() if k not in ("NUMBA_CPU_NAME", "NUMBA_CACHE_DIR")}
    res = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, timeout=300, check=False,
                         cwd=tmp_path)
    assert res.returncode == 0, res.stderr[-2000:]
    bounds, cache_kept, exported, cpu = res.stdout.split()
    assert (bounds, cache_kept, exported) == ("1", "True", "None")
    assert cpu == (prebuilt.PORTABLE_CPU if prebuilt.usable(prebuilt.manifest()) is None else cpu)


def test_shipped_data_files_never_take_a_name_numba_gives_its_own():
    """numba numbers its data files ``<base>.<n>.nbc``; a shipped one written over such a file (or over another
    archive's) while another process reads the index that names it would hand that process another kernel's
    code."""
    shipped = prebuilt.manifest()
    assert shipped is not None, REBUILD
    names = [name for entry in shipped["sources"].values() for files in entry["data"].values() for name in files]
    assert names and all(f"{prebuilt.SHIPPED_MARK}{shipped['build']}-" in name for name in names)
    assert prebuilt.shipped_data_name("lean._law-68.py311.nbi", "ab12", 3) == "lean._law-68.py311.vbikit-ab12-3.nbc"
