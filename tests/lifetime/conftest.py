"""Fixtures the lifetime tests share."""
from __future__ import annotations

import os
import shutil
from pathlib import Path
from types import SimpleNamespace

import pytest


@pytest.fixture(scope="session")
def finished_cut_down(built_once):
    """The cut-down example (``test_cli._cut_down``: 5 days of 60 trucks) run once to the end, for the tests that
    only read a finished run (its dataset, its ``work`` folder, its static pass): ``folder`` (the file and its
    records), ``spec`` (the file), ``out`` (the output folder) and ``ds`` (its lifetime.nc, loaded).  Each such test
    ran the same call itself before (≈ 3 s each); none of them writes to the folder or changes the dataset.  Made
    once for the whole test run (``built_once``: by the first process to ask, in the run's shared folder; the others
    read it).  A test that resumes or changes the run makes its own (a copy of the folder would not do: the stored
    work names the file it was run from)."""
    import xarray as xr

    def build() -> dict:
        from vbikit.lifetime.run import run_lifetime

        from .test_cli import _cut_down

        folder = Path(os.environ["VBIKIT_TEST_RUN_DIR"]) / "lifetime-cut-down"
        shutil.rmtree(folder, ignore_errors=True)  # (what a build that failed left)
        folder.mkdir()
        run_lifetime(_cut_down(folder), folder / "out", workers=1, figures=False)
        return {"folder": str(folder)}

    folder = Path(built_once("lifetime-cut-down", build)["folder"])
    with xr.open_dataset(folder / "out" / "lifetime.nc") as ds:
        ds = ds.load()
    return SimpleNamespace(folder=folder, spec=folder / "lifetime.toml", out=folder / "out", ds=ds)
