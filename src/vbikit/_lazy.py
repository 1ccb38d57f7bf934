"""Lazy package namespaces (PEP 562): a package's public names are imported from their modules
on first use, so that importing a package — or ``vbikit`` itself, as the command line does —
does not load numba, scipy, xarray or matplotlib until a name that needs them is used.

A package lists its names once per module and keeps ``__all__`` and the static imports (under
``TYPE_CHECKING``, for type checkers and the API reference) beside them::

    __all__ = ["Crossing", "simulate"]
    __getattr__, __dir__ = lazy_exports(globals(), {"vbikit.solve.crossing": ["Crossing"],
                                                    "vbikit.solve.simulate": ["simulate"]})
"""
from __future__ import annotations

import importlib
import sys
import types
from typing import Any, Callable


class _Package(types.ModuleType):
    """A package module whose exported function may share its name with the submodule that defines
    it (``vbikit.solve.simulate``): importing that submodule binds the function, not the module,
    as the package's attribute — what an eager ``from .simulate import simulate`` did."""

    _vbikit_shadowed: frozenset[str] = frozenset()

    def __setattr__(self, name: str, value: Any) -> None:
        if (name in self._vbikit_shadowed and isinstance(value, types.ModuleType)
                and value.__name__ == f"{self.__name__}.{name}" and hasattr(value, name)):
            value = getattr(value, name)
        super().__setattr__(name, value)


def lazy_exports(namespace: dict[str, Any], modules: dict[str, list[str]]) -> tuple[Callable[[str], Any], Callable[[], list[str]]]:
    """``__getattr__`` and ``__dir__`` of the package whose globals are ``namespace``: each name of
    ``modules[module]`` is imported from ``module`` when first asked for, then kept in the package.

    Raises ``ValueError`` (at import of the package) if a name is listed twice or is not in the
    package's ``__all__``.
    """
    package = namespace["__name__"]
    where: dict[str, str] = {}
    for module, names in modules.items():
        for name in names:
            if name in where:
                raise ValueError(f"{package}: {name!r} listed for both {where[name]} and {module}")
            where[name] = module
    public = set(namespace.get("__all__", where))
    differ = (set(where) - public) | (public - set(where) - set(namespace))
    if differ:
        raise ValueError(f"{package}: __all__ and the lazy exports differ in {sorted(differ)}")

    shadowed = frozenset(n for n, module in where.items() if module == f"{package}.{n}")
    if shadowed:
        module_object = sys.modules[package]
        module_object.__class__ = _Package
        object.__setattr__(module_object, "_vbikit_shadowed", shadowed)

    def __getattr__(name: str) -> Any:
        module = where.get(name)
        if module is None:
            raise AttributeError(f"module {package!r} has no attribute {name!r}")
        value = getattr(importlib.import_module(module), name)
        namespace[name] = value
        return value

    def __dir__() -> list[str]:
        return sorted(set(namespace) | set(where))

    return __getattr__, __dir__
