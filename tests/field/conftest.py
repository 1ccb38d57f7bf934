"""A synthetic field test with known truth, generated once per test session (≈ 4 s), and a
writable copy of the field example."""
from __future__ import annotations

import shutil
from pathlib import Path

import pytest

from vbikit.field.synthetic import write_synthetic_case


@pytest.fixture(scope="session")
def synthetic(tmp_path_factory):
    out = tmp_path_factory.mktemp("field")
    truth = write_synthetic_case(out, cases=("case1",))
    return out, truth


@pytest.fixture
def example(tmp_path: Path) -> Path:
    """A copy of examples/field (its FIELD.toml and CSV files) in a temporary folder."""
    for f in (Path(__file__).resolve().parents[2] / "examples" / "field").glob("*"):
        if f.suffix in (".csv", ".toml"):
            shutil.copy(f, tmp_path / f.name)
    return tmp_path
