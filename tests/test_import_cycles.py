"""No import cycle anywhere in the package: a static scan of every ``import`` and ``from … import``
statement in every module of src/vbikit — at module level, inside functions and under
``if TYPE_CHECKING:`` alike — mapped to the package's modules, must give an acyclic graph.  An
annotation-only import never executes, but a loop through one is still a circle of modules that
know each other (the last one, vbikit.solve.crossing ↔ integrators, is gone: the integrator
registry has a module of its own)."""
from __future__ import annotations

import ast
from pathlib import Path

SRC = Path(__file__).resolve().parents[1] / "src"


def package_modules(src: Path | None = None, package: str = "vbikit") -> dict[str, tuple[Path, bool]]:
    """``module name -> (file, is a package __init__)`` of every module under ``src/package`` (src: the repository's)."""
    src = SRC if src is None else src
    out = {}
    for path in sorted((src / package).rglob("*.py")):
        parts = list(path.relative_to(src).with_suffix("").parts)
        is_package = parts[-1] == "__init__"
        out[".".join(parts[:-1] if is_package else parts)] = (path, is_package)
    return out


def _resolve(name: str, modules: dict[str, tuple[Path, bool]]) -> str | None:
    """The module a dotted import target names: itself, or the longest module prefix (an attribute of it)."""
    while name and name not in modules:
        name = name.rpartition(".")[0]
    return name or None


def import_graph(modules: dict[str, tuple[Path, bool]]) -> dict[str, dict[str, int]]:
    """``importer -> {imported module: line of the first such import}`` within the package."""
    graph: dict[str, dict[str, int]] = {}
    for name, (path, is_package) in modules.items():
        here = name if is_package else name.rpartition(".")[0]
        edges = graph.setdefault(name, {})
        tree = ast.parse(path.read_text(encoding="utf-8"), str(path))
        for node in ast.walk(tree):
            if isinstance(node, ast.Import):
                targets = [a.name for a in node.names]
            elif isinstance(node, ast.ImportFrom):
                if node.level:
                    base = here.split(".")[: len(here.split(".")) - (node.level - 1)]
                    mod = ".".join(base + ([node.module] if node.module else []))
                else:
                    mod = node.module or ""
                targets = [f"{mod}.{a.name}" for a in node.names]  # `from pkg import submodule` imports it
            else:
                continue
            for target in targets:
                to = _resolve(target, modules)
                if to is not None and to != name:
                    edges.setdefault(to, node.lineno)
    return graph


def find_cycles(graph: dict[str, dict[str, int]]) -> list[list[str]]:
    """One cycle [a, b, …, a] through every strongly connected component of more than one module."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    components: list[list[str]] = []

    def visit(v: str) -> None:  # Tarjan's algorithm
        index[v] = low[v] = len(index)
        stack.append(v)
        on_stack.add(v)
        for w in graph.get(v, {}):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on_stack.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                components.append(comp)

    for v in sorted(graph):
        if v not in index:
            visit(v)
    cycles = []
    for comp in components:
        members, start = set(comp), min(comp)
        path, seen = [start], {start}
        while True:  # walk within the component until a module repeats
            nxt = min(w for w in graph[path[-1]] if w in members)
            if nxt in seen:
                cycles.append(path[path.index(nxt):] + [nxt])
                break
            path.append(nxt)
            seen.add(nxt)
    return cycles


def _describe(cycle: list[str], graph: dict[str, dict[str, int]], modules: dict[str, tuple[Path, bool]]) -> str:
    return "\n".join(f"  {a} ({modules[a][0].name}:{graph[a][b]}) imports {b}" for a, b in zip(cycle, cycle[1:]))


def test_the_scan_finds_a_cycle(tmp_path):
    pkg = tmp_path / "pkg"
    (pkg / "sub").mkdir(parents=True)
    (pkg / "__init__.py").write_text("")
    (pkg / "sub" / "__init__.py").write_text("")
    (pkg / "a.py").write_text("from pkg.sub import b\n")
    (pkg / "sub" / "b.py").write_text("def f():\n    from .c import g\n")
    (pkg / "sub" / "c.py").write_text("from ..a import x\n")
    (pkg / "d.py").write_text("import pkg.a\n")
    (pkg / "e.py").write_text("from typing import TYPE_CHECKING\nif TYPE_CHECKING:\n    from pkg.d import y\n")
    (pkg / "f.py").write_text("import typing\nfrom pkg import e\nif typing.TYPE_CHECKING:\n    import pkg.f\n")
    modules = package_modules(tmp_path, "pkg")
    graph = import_graph(modules)
    assert graph["pkg.a"] == {"pkg.sub.b": 1} and graph["pkg.d"] == {"pkg.a": 1}
    assert graph["pkg.e"] == {"pkg.d": 3} and graph["pkg.f"] == {"pkg.e": 2}  # annotation-only imports count
    assert find_cycles(graph) == [["pkg.a", "pkg.sub.b", "pkg.sub.c", "pkg.a"]]
    (pkg / "d.py").write_text("import pkg.a\nimport pkg.f\n")  # d → f → (annotations) … : e → d closes a loop
    graph = import_graph(package_modules(tmp_path, "pkg"))
    assert ["pkg.d", "pkg.f", "pkg.e", "pkg.d"] in find_cycles(graph)


def test_no_import_cycle_in_the_package():
    modules = package_modules()
    assert "vbikit.bridge.girder_deck" in modules
    graph = import_graph(modules)
    assert "vbikit.bridge.base" in graph["vbikit.bridge.girder_deck"]  # the scan sees the package's imports
    cycles = find_cycles(graph)
    assert not cycles, "import cycles:\n" + "\n\n".join(_describe(c, graph, modules) for c in cycles)
