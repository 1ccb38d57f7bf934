"""Shared by the docs tests: the scripts under docs/scripts loaded as modules."""
from __future__ import annotations

import importlib.util
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture
def docs_script():
    """``docs_script("generate")``: docs/scripts/generate.py loaded as a module."""
    def load(name: str):
        spec = importlib.util.spec_from_file_location(f"vbikit_docs_{name}", ROOT / "docs" / "scripts" / f"{name}.py")
        module = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(module)
        return module
    return load
