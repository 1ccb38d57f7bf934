"""A railway sweep on a local Dask cluster (loopback, 2 worker processes) gives the same dataset
as the same sweep in one process (``vbikit rail --scheduler``)."""
from __future__ import annotations

import numpy as np
import pytest

from vbikit.rail.run import run_rail
from vbikit.rail.spec import RailSpecError

distributed = pytest.importorskip("distributed")

SPEC = {"bridge": {"span": 15.0, "EI": 6.0e9, "mass_per_length": 12000.0, "damping": 0.01},
        "trains": {"presets": ["hslm-a1", "hslm-a4"]},
        "speeds": {"min": 150.0, "max": 250.0, "step": 25.0},
        "run": {"workers": 1}}


def test_dask_cluster_equals_one_process():
    local = run_rail(SPEC, figures=False).dataset
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, host="127.0.0.1", dashboard_address=None,
                                  processes=True) as cluster:
        remote = run_rail(SPEC, figures=False, scheduler=cluster.scheduler_address).dataset
    assert list(remote.train.values) == ["HSLM-A1", "HSLM-A4"]
    for name in ("max_deck_acceleration", "max_deflection"):
        np.testing.assert_array_equal(local[name].values, remote[name].values)  # the same arithmetic, elsewhere


@pytest.mark.slow  # waits for the 30 s connection timeout
def test_unreachable_scheduler_is_a_clear_error():
    with pytest.raises(RailSpecError, match=r"--scheduler tcp://127\.0\.0\.1:9: cannot connect"):
        run_rail(SPEC, figures=False, scheduler="tcp://127.0.0.1:9")
