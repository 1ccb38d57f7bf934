"""A lifetime file's ``base = "…/scenario.toml"``: the files that base scenario names (a measured road
profile here) are read from the base file's own folder, as `vbikit traffic --bridge` and `vbikit run`
read them — not from the lifetime file's folder."""
from __future__ import annotations

import shutil
from pathlib import Path

import numpy as np
import pytest

from vbikit.lifetime.spec import LifetimeError

ROOT = Path(__file__).resolve().parents[2]


def _project(tmp_path: Path) -> tuple[Path, dict]:
    project = tmp_path / "project"
    (project / "bridges").mkdir(parents=True)
    shutil.copy(ROOT / "examples/lifetime/wim.csv", project / "wim.csv")
    shutil.copy(ROOT / "examples/field/profile_left.csv", project / "bridges" / "road.csv")
    (project / "bridges" / "base.toml").write_text(
        '[bridge]\nmodel = "paper-bridge-1-beam"\nn_modes = 3\n[tire]\nmodel = "point"\n'
        '[road]\nprofile_file = "road.csv"\n')
    spec = {"name": "base folder", "seed": 4, "days": 5, "amplification": 0.05,
            "traffic": {"records": "wim.csv", "trucks_per_day": 16, "speed_kmh": 5.0},
            "vehicle_model": "moving-forces", "base": "bridges/base.toml",
            "load_effects": [{"kind": "deflection", "x": 4.58, "name": "w"}]}
    return project, spec


def test_the_base_scenarios_files_are_read_from_its_own_folder(tmp_path):
    """road.csv lies beside bridges/base.toml only: the run's set-up finds it there (it looked for
    project/road.csv before, and failed)."""
    from vbikit.lifetime.run import prepare

    project, spec = _project(tmp_path)
    prep = prepare(spec, project, workers=1)
    road = prep.setup.context.road(0)[0]  # the events' road: the measured file's, not a random one
    x, z = np.loadtxt(project / "bridges" / "road.csv", delimiter=",", comments="#", skiprows=2, unpack=True)
    assert road is not None and np.allclose(road.x[[0, -1]], x[[0, -1]])
    assert np.allclose(np.interp(x[::50], road.x, road.z), z[::50], atol=1e-9)

def test_a_file_missing_beside_the_base_is_named_with_its_folder(tmp_path):
    from vbikit.lifetime.run import prepare

    project, spec = _project(tmp_path)
    (project / "bridges" / "road.csv").rename(project / "road.csv")  # beside the lifetime file only
    with pytest.raises(LifetimeError) as err:
        prepare(spec, project, workers=1)
    assert "road.csv" in str(err.value) and "bridges" in str(err.value)
