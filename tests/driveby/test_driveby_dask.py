"""A drive-by sweep on a local Dask cluster (loopback) gives the same dataset as in one process."""
from __future__ import annotations

from pathlib import Path

import pytest
import xarray as xr

from vbikit.driveby.spec import DriveByError, parse_driveby
from vbikit.driveby.study import run_driveby

distributed = pytest.importorskip("distributed")
EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "driveby" / "DRIVEBY.toml"


def test_dask_local_cluster_equals_one_process(tmp_path):
    from vbikit._toml import read_toml

    data = read_toml(EXAMPLE, DriveByError)
    data["sweep"].update(speed=[8.0], road_class=["none"])  # two cases: healthy and damaged
    data["batch_size"] = 1
    spec = parse_driveby(data, EXAMPLE.parent)
    local = run_driveby(spec, tmp_path / "local", figures=False)
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, host="127.0.0.1", dashboard_address=None,
                                  processes=True) as cluster:
        remote = run_driveby(spec, tmp_path / "dask", scheduler=cluster.scheduler_address, figures=False)
    assert local.sizes["case"] == 2
    xr.testing.assert_identical(local, remote)
