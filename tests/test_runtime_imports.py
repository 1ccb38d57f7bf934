"""Every module-level import of the package is the standard library, vbikit itself, or a runtime
dependency declared in pyproject.toml — so that `pip install .` (the README's demo command,
without the test extras) has everything the package imports on start-up. Optional packages
(dask, openseespy, ospgrillage, pycba, …) may only be imported inside functions."""
from __future__ import annotations

import ast
import re
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
#: import names of distributions whose name differs, and packages that come with a declared one
IMPORT_NAMES = {"netcdf4": "netCDF4", "pyyaml": "yaml"}
BUNDLED = {"pandas"}  # a dependency of xarray (CrossingResult.to_dataframe)


def _declared() -> set[str]:
    text = (ROOT / "pyproject.toml").read_text()
    block = re.search(r"^dependencies = \[(.*?)^\]", text, re.S | re.M).group(1)
    names = {re.match(r"[A-Za-z0-9_.\-]+", d).group(0).lower() for d in re.findall(r'"([^"]+)"', block)}
    return {IMPORT_NAMES.get(n, n.replace("-", "_")) for n in names} | BUNDLED


def _top_level_imports(path: Path) -> set[str]:
    found = set()
    for node in ast.parse(path.read_text(encoding="utf-8")).body:  # module level only
        if isinstance(node, ast.Import):
            found |= {a.name.split(".")[0] for a in node.names}
        elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
            found.add(node.module.split(".")[0])
        elif isinstance(node, ast.If):  # e.g. `if sys.version_info < (3, 11): import tomli`
            for sub in ast.walk(node):
                if isinstance(sub, ast.Import):
                    found |= {a.name.split(".")[0] for a in sub.names}
                elif isinstance(sub, ast.ImportFrom) and sub.level == 0 and sub.module:
                    found.add(sub.module.split(".")[0])
    return found


def test_module_level_imports_are_declared_runtime_dependencies():
    allowed = _declared() | set(sys.stdlib_module_names) | {"vbikit", "__future__"}
    stray = {}
    for path in sorted((ROOT / "src" / "vbikit").rglob("*.py")):
        extra = {m for m in _top_level_imports(path) if m not in allowed and m.lower() not in allowed}
        if extra:
            stray[str(path.relative_to(ROOT))] = sorted(extra)
    assert not stray, f"module-level imports not among the runtime dependencies: {stray}"
