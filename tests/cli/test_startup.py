"""Start-up: `vbikit --version`, `--help`, completion and `vbikit validate`'s command line load no
numerics they do not use; package namespaces resolve their names on first use (vbikit._lazy)."""
from __future__ import annotations

import importlib
import json
import os
import pkgutil
import subprocess
import sys
from pathlib import Path

import pytest

import vbikit

ROOT = Path(__file__).resolve().parents[2]
HEAVY = ("numba", "xarray", "matplotlib", "scipy", "pandas")

#: run the command line in-process with ``argv``, then print the heavy modules it loaded as JSON on stderr
WRAPPER = """
import json, sys
sys.argv = ["vbikit", *json.loads(sys.argv[1])]
try:
    from vbikit.cli import main
    main()
except SystemExit:
    pass
finally:
    print(json.dumps(sorted(m for m in {heavy!r} if m in sys.modules)), file=sys.stderr)
"""


def _loaded(argv: list[str], **env: str) -> list[str]:
    res = subprocess.run([sys.executable, "-c", WRAPPER.format(heavy=HEAVY), json.dumps(argv)], capture_output=True,
                         text=True, env={**os.environ, "PYTHONPATH": str(ROOT / "src"), **env}, timeout=120)
    return json.loads(res.stderr.strip().splitlines()[-1])


def test_importing_the_cli_loads_no_numerics():
    code = f"import sys, vbikit.cli; print(','.join(m for m in {HEAVY!r} if m in sys.modules))"
    res = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True,
                         env={**os.environ, "PYTHONPATH": str(ROOT / "src")}, timeout=120)
    assert res.stdout.strip() == ""


@pytest.mark.parametrize("argv", [["--version"], ["--help"], [], ["run", "--help"], ["validate", "--help"],
                                  ["study", "--help"], ["study", "paper-fig6", "--help"], ["traffic", "--help"],
                                  ["field", "--help"]], ids=" ".join)
def test_version_and_help_load_no_numerics(argv):
    assert _loaded(argv) == []


def test_completion_loads_no_numerics():
    assert _loaded([], _VBIKIT_COMPLETE="complete_bash", COMP_WORDS="vbikit study pa", COMP_CWORD="2") == []


@pytest.mark.parametrize("example", ["traffic/two_trucks.toml", "paper/bridge2_hs20_girder4.toml", "traffic/base/bridge2.toml",
                                     "bridges/three_span_continuous_hs20.toml"])
def test_validate_loads_no_kernels_plots_or_datasets(example):
    """`vbikit validate` builds the models (scipy) and the run plan of the default integrator, but
    never loads the compiled kernels (numba), xarray, pandas or matplotlib."""
    loaded = _loaded(["validate", str(ROOT / "examples" / example)])
    assert set(loaded) <= {"scipy"}, loaded


def _packages() -> list[str]:
    return ["vbikit"] + [f"vbikit.{m.name}" for m in pkgutil.iter_modules(vbikit.__path__) if m.ispkg]


@pytest.mark.parametrize("package", _packages())
def test_every_public_name_resolves_to_its_object(package):
    """`from vbikit.solve import simulate` is the function, also after the submodule of the same
    name was imported; every name of `__all__` resolves and is listed by dir()."""
    pkg = importlib.import_module(package)
    for info in pkgutil.iter_modules(pkg.__path__):  # import every submodule first (binds them on the package)
        if not info.ispkg and info.name != "__main__":
            importlib.import_module(f"{package}.{info.name}")
    for name in getattr(pkg, "__all__", []):
        value = getattr(pkg, name)
        assert name in dir(pkg)
        assert not (type(value).__name__ == "module" and name != "__version__"), f"{package}.{name} is a module"
        defining = getattr(value, "__module__", None)
        if defining and defining.startswith("vbikit.") and callable(value):
            assert getattr(sys.modules[defining], name, value) is value
    with pytest.raises(AttributeError):
        getattr(pkg, "no_such_name")
