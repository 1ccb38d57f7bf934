"""``vbikit lifetime``, ``vbikit driveby`` and ``vbikit rail`` RUN on generated valid-but-extreme
tiny inputs (``fuzz_runs.py``): exit 0 with no undocumented non-finite number in the JSON and
NetCDF outputs, or a clean refusal (exit 2, one ``error:`` line); never a traceback.  Default: one
derandomised input for rail and drive-by (≈ 5 s); ``slow``: 4 random inputs a command."""
from __future__ import annotations

import tempfile
from pathlib import Path

import pytest
from fuzz_commands import fuzz_settings, write_input
from fuzz_runs import extreme_inputs, non_finite
from hypothesis import given
from typer.testing import CliRunner

from vbikit.cli import app

runner = CliRunner()
OPTIONS = {"lifetime": ["--workers", "1"], "driveby": ["--workers", "1"], "rail": []}


def run_and_judge(kind: str, inputs) -> None:
    data, files = inputs
    with tempfile.TemporaryDirectory() as tmp:
        path = write_input(Path(tmp), kind, data, files)
        out = Path(tmp) / "out"
        result = runner.invoke(app, [kind, str(path), "--out-dir", str(out), "--no-figures", "--no-progress",
                                     *OPTIONS[kind]])
        text = path.read_text()
        where = f"\n--- input ---\n{text}\n--- output ---\n{result.output[-2000:]}"
        assert result.exception is None or isinstance(result.exception, SystemExit), f"traceback{where}"
        if result.exit_code == 0:
            problems = non_finite(out, kind)
            assert not problems, f"{kind}: non-finite outputs at exit 0: {problems}{where}"
        else:
            errors = [line for line in result.stderr.splitlines() if line.startswith("error:")]
            assert result.exit_code == 2 and len(errors) == 1, f"{kind}: exit {result.exit_code}{where}"



@pytest.mark.parametrize("kind, n", [("rail", 1), ("driveby", 1),
                                     *(pytest.param(k, 4, marks=pytest.mark.slow) for k in ("lifetime", "driveby", "rail"))])
def test_extreme_inputs_run_to_finite_outputs_or_a_clean_refusal(kind, n):
    @fuzz_settings(n, slow=n > 1)
    @given(extreme_inputs(kind))
    def run(inputs):
        run_and_judge(kind, inputs)

    run()


def test_the_oracle_sees_nan_in_json_and_undocumented_nan_in_netcdf(tmp_path):
    """The judge itself: NaN in a JSON output, inf or an undocumented NaN in a dataset are found;
    a NaN the dataset documents is not."""
    import numpy as np
    import xarray as xr

    (tmp_path / "s.json").write_text('{"a": NaN}')
    xr.Dataset({"max_deck_acceleration": ("speed", [1.0, np.nan]), "frequency": ("mode", [np.inf]),
                "label": ("case", [np.nan], {"long_name": "label (NaN: none)"})}).to_netcdf(tmp_path / "r.nc")
    found = non_finite(tmp_path, "rail")
    assert len(found) == 3, found
    assert any(f.startswith("s.json") for f in found) and "r.nc:frequency: 1 infinite" in found
    assert "r.nc:max_deck_acceleration: 1 NaN" in found
