"""docs/traffic.md's example stream: the numbers the page quotes are those of the example run again
(examples/traffic/stream.csv over examples/traffic/base/bridge2.toml, --seed 1)."""
from __future__ import annotations

from pathlib import Path

import pytest
import xarray as xr
from typer.testing import CliRunner

from vbikit.cli import app

ROOT = Path(__file__).resolve().parents[2]


def test_the_example_stream_numbers_of_the_page(tmp_path):
    res = CliRunner().invoke(app, ["traffic", str(ROOT / "examples/traffic/stream.csv"), "--bridge",
                                   str(ROOT / "examples/traffic/base/bridge2.toml"), "--seed", "1", "--out",
                                   str(tmp_path / "s.nc"), "--workers", "1", "--no-progress"])
    assert res.exit_code == 0, res.output
    page = " ".join((ROOT / "docs/traffic.md").read_text().split())
    with xr.open_dataset(tmp_path / "s.nc") as ds:
        a = dict(ds.attrs)
        starts = ds["event_start"].values
        signed_mm = 1e3 * (ds.isel(point=0)["max_static_displacement"].values if "point" in ds.dims
                           else ds["max_static_displacement"].values)
        static_mm = abs(signed_mm)
    n_loaded = a["n_events"] - a["n_small_static_events"]
    quoted = [
        f"{a['n_events']} events, {a['n_multiple_presence_events']} of them with two or more trucks",
        f"The {n_loaded} events that load Girder 4's midspan",
        f"have a mean IM of {a['im_mean_loaded']:.3f} (95 % quantile {a['im_q95_loaded']:.3f}); all events together "
        f"{a['im_mean']:.3f} ({a['im_mean_single']:.3f} for one truck, {a['im_mean_multiple']:.3f} for several; 95 % "
        f"quantile {a['im_q95']:.3f}), raised by the other {a['n_small_static_events']},",
        f"has a dynamic amplification of {a['governing_static_amplification']:.3f}",
        f"{a['governing_dynamic_amplification']:.2f} × the largest static effect",
        f"`mean {a['im_mean_loaded']:.4f} (95 % CI {a['im_mean_loaded_ci_lower']:.4f} – {a['im_mean_loaded_ci_upper']:.4f}), "
        f"95th percentile {a['im_q95_loaded']:.4f} (95 % CI {a['im_q95_loaded_ci_lower']:.4f} – {a['im_q95_loaded_ci_upper']:.4f})` "
        f"over its {n_loaded} events",
    ]
    for text in quoted:
        assert text in page, text
    g = int(a["governing_static_event"])  # named by its dataset index and when it starts in the stream
    # the governing event is the largest magnitude; its deflection keeps the dataset's sign (z up: downward < 0)
    assert signed_mm[g] < 0.0
    assert (f"largest static deflection: {signed_mm[g]:.3f} mm, event {g} (starts at t = {starts[g]:.1f} s), dynamic "
            "amplification") in res.output
    assert static_mm[g] == static_mm.max() and a["governing_static_deflection"] == pytest.approx(signed_mm[g] / 1e3, rel=1e-12)
    assert "deflection impact factors at girder 4, midspan of the first span (the stream's statistics are of this point)" \
        in res.output  # (the base scenario's [response] girder = 4, x default)
    assert quoted[-1][1:].split("` over")[0] in res.output  # (the printed line itself)
    # a dataset written before the intervals (the finished-run path reads it as it is): the statistics without them
    with xr.open_dataset(tmp_path / "s.nc") as ds:
        old = ds.load()
    old.attrs = {k: v for k, v in old.attrs.items() if "_ci_" not in k}
    old.to_netcdf(tmp_path / "old.nc")
    (tmp_path / "old.nc").replace(tmp_path / "s.nc")
    again = CliRunner().invoke(app, ["traffic", str(ROOT / "examples/traffic/stream.csv"), "--bridge",
                                     str(ROOT / "examples/traffic/base/bridge2.toml"), "--seed", "1", "--out",
                                     str(tmp_path / "s.nc"), "--workers", "1", "--no-progress"])
    assert again.exit_code == 0, again.output
    assert "already holds this finished run" in again.output and "CI" not in again.output
    assert f"mean {a['im_mean_loaded']:.4f}, 95th percentile {a['im_q95_loaded']:.4f}" in again.output
