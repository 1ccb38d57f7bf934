"""A synthetic field test with known truth, generated once per test session (≈ 4 s)."""
from __future__ import annotations

import pytest

from vbikit.field.synthetic import write_synthetic_case


@pytest.fixture(scope="session")
def synthetic(tmp_path_factory):
    out = tmp_path_factory.mktemp("field")
    truth = write_synthetic_case(out, cases=("case1",))
    return out, truth
