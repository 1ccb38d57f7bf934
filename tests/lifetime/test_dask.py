"""A lifetime run on a local Dask cluster gives the dataset of a local run."""
import numpy as np
import pytest

from vbikit.lifetime.run import run_lifetime

distributed = pytest.importorskip("distributed")


@pytest.mark.slow
def test_dask_local_cluster_equals_local_run(tmp_path):
    spec = {"seed": 9, "days": 5, "amplification": 0.6,
            "traffic": {"records": "examples/lifetime/wim.csv", "trucks_per_day": 40},
            "bridge": {"model": "paper-bridge-1-beam", "n_modes": 3}, "tire": {"model": "point"}, "road": {"class": "B"},
            "load_effects": [{"kind": "moment", "x": 4.0, "name": "M"}, {"kind": "reaction", "support": 0, "name": "R"}],
            "fatigue": {"dynamic_sample": 0.1,
                        "details": [{"name": "d", "effect": "M", "section_modulus": 0.004, "category": "EN 71"}]}}
    local = run_lifetime(spec, tmp_path / "local", base_dir=".", workers=1, figures=False)
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, host="127.0.0.1", dashboard_address=None,
                                  processes=True) as cluster:
        remote = run_lifetime(spec, tmp_path / "dask", base_dir=".", scheduler=cluster.scheduler_address, figures=False)
    for name in local.data_vars:
        np.testing.assert_array_equal(local[name].values, remote[name].values, err_msg=name)
    assert local.attrs["n_dynamic_events"] == remote.attrs["n_dynamic_events"] > 0
