"""The Dask path: the same study on a local distributed cluster (loopback) gives the same dataset."""
from __future__ import annotations

import pytest
import xarray as xr

from vbikit.study import StudyError, parse_study, run_study

distributed = pytest.importorskip("distributed")


def test_dask_local_cluster_equals_local_run(tmp_path, small_study_dict):
    study = parse_study(small_study_dict)
    local = run_study(study, tmp_path / "local.nc", workers=1)
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, host="127.0.0.1", dashboard_address=None,
                                  processes=True) as cluster:
        seen = []
        remote = run_study(study, tmp_path / "dask.nc", scheduler=cluster.scheduler_address,
                           progress=lambda d, t: seen.append(d))
    xr.testing.assert_identical(local, remote)
    assert seen[-1] == study.size


def test_unreachable_scheduler_is_a_clear_error(tmp_path, small_study_dict):
    with pytest.raises(StudyError, match="cannot connect"):
        run_study(parse_study(small_study_dict), tmp_path / "x.nc", scheduler="tcp://127.0.0.1:1",
                  connect_timeout=1.0)
