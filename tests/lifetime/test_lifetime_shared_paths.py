"""A lifetime run's shared files (lifetime.nc, summary.json, report.txt) carry no folder of the machine it
ran on: the lifetime file's absolute paths are stored by their file names."""
from __future__ import annotations

import json
import shutil
from pathlib import Path

import xarray as xr


def test_the_lifetime_files_name_no_folder(tmp_path):
    """``traffic.records`` and ``base`` given as absolute paths under a project folder: lifetime.nc's
    ``lifetime`` attribute keeps ``wim.csv`` and ``base.toml`` (before 2026-12-06 the whole paths, the
    spec being stored as written), and no attribute, variable text, summary or report line holds the folder."""
    from vbikit.lifetime.run import run_lifetime

    project = tmp_path / "project"
    project.mkdir()
    shutil.copy(Path("examples/lifetime/wim.csv"), project / "wim.csv")
    (project / "base.toml").write_text('[bridge]\nmodel = "paper-bridge-1-beam"\nn_modes = 3\n[tire]\nmodel = "point"\n'
                                       '[road]\nclass = "none"\n')
    spec = {"name": "shared", "seed": 4, "days": 5, "amplification": 0.05,
            "traffic": {"records": str(project / "wim.csv"), "trucks_per_day": 16, "speed_kmh": 5.0},
            "vehicle_model": "moving-forces", "base": str(project / "base.toml"),
            "load_effects": [{"kind": "deflection", "x": 4.58, "name": "w"}]}
    out = tmp_path / "out"
    run_lifetime(spec, out, base_dir=project, workers=1, figures=False)
    with xr.open_dataset(out / "lifetime.nc") as ds:
        stored = json.loads(ds.attrs["lifetime"])
        texts = [str(v) for v in ds.attrs.values()]
        for v in ds.variables.values():
            texts += [str(a) for a in v.attrs.values()]
            if v.dtype.kind in "OUS":
                texts += [str(x) for x in v.values.ravel()]
    assert stored["traffic"]["records"] == "wim.csv" and stored["base"] == "base.toml"
    assert stored["traffic"]["trucks_per_day"] == 16 and stored["load_effects"][0]["name"] == "w"  # the rest as given
    # moving constant forces have no vibration to build up on the approach: no start_from_rest flag
    with xr.open_dataset(out / "lifetime.nc") as ds:
        assert ds.attrs["vehicle_model"] == "moving-forces" and ds.attrs["approach_m"] == 10.0
        assert "start_from_rest" not in ds.attrs.get("flag_codes", "")
    texts += [(out / "summary.json").read_text(), (out / "report.txt").read_text()]
    assert not [t for t in texts if str(tmp_path) in t]
