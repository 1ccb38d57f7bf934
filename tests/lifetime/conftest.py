"""Fixtures the lifetime tests share."""
from __future__ import annotations

from types import SimpleNamespace

import pytest


@pytest.fixture(scope="session")
def finished_cut_down(tmp_path_factory):
    """The cut-down example (``test_cli._cut_down``: 5 days of 60 trucks) run once to the end in-process, for the
    tests that only read a finished run (its dataset, its ``work`` folder, its static pass): ``folder`` (the file
    and its records), ``spec`` (the file), ``out`` (the output folder) and ``ds`` (what ``run_lifetime`` returned).
    Each such test ran the same call itself before (≈ 3 s each); none of them writes to the folder or changes the
    dataset.  A test that resumes or changes the run makes its own (a copy of the folder would not do: the stored
    work names the file it was run from)."""
    from vbikit.lifetime.run import run_lifetime

    from .test_cli import _cut_down

    folder = tmp_path_factory.mktemp("cut-down")
    spec = _cut_down(folder)
    out = folder / "out"
    ds = run_lifetime(spec, out, workers=1, figures=False)
    return SimpleNamespace(folder=folder, spec=spec, out=out, ds=ds)
