"""Fatigue across days: the days' rainflow counts joined equal the whole period's count."""
import numpy as np
import pytest

from vbikit.fatigue import miner_damage, rainflow, sn_curve
from vbikit.lifetime.influence import event_static
from vbikit.lifetime.jobs import day_traffic
from vbikit.lifetime.results import fatigue_results
from vbikit.lifetime.run import prepare


def test_static_damage_of_the_period_equals_the_whole_history_count():
    """Three days counted day by day on the static pass (each day's closed cycles, its residual
    joined to the next day's) give the Miner damage of the three days' stress history counted at
    once with vbikit.fatigue.rainflow (ASTM E1049-85), to 1e-12 relative; EN 71 curve."""
    import xarray as xr

    spec = {"days": 5, "traffic": {"records": "examples/lifetime/wim.csv", "trucks_per_day": 300},
            "bridge": {"model": "paper-bridge-1-beam", "n_modes": 3}, "tire": {"model": "point"},
            "load_effects": [{"kind": "moment", "x": 4.1, "name": "M"}],
            "fatigue": {"details": [{"name": "d", "effect": "M", "section_modulus": 0.004, "category": "EN 71"}]}}
    prep = prepare(spec, ".")
    job = prep.static_job()
    parts = [job.run_batch((d,)) for d in range(3)]
    cat = {k: np.concatenate([p[k] for p in parts], axis=0) for k in parts[0]}
    static = xr.Dataset({k: (tuple(f"{k}_{i}" for i in range(v.ndim)), v) for k, v in cat.items()})
    # the whole history: every event's static history between zeros, day after day
    setup = prep.setup
    whole = []
    for d in range(3):
        records, events = day_traffic(prep.model, job._digest, setup, d, prep.spec.seed)
        es = event_static(records, events, setup.lines, setup.span, setup.lanes, setup.pattern, prep.spec.ds,
                          setup.tables, keep_histories=True)
        h = es.histories[0] / 0.004
        for e in range(len(events)):
            whole += [0.0, *h[es.offsets[0][e]:es.offsets[0][e + 1]], 0.0]
    cycles = rainflow(np.array(whole))
    expected = miner_damage([c[0] for c in cycles], [c[1] for c in cycles], sn_curve("EN 71"))
    prep.spec = prep.spec.model_copy(update={"days": 3})
    got = fatigue_results(prep, static, {"sample": np.zeros(0, np.int64), "gid": np.zeros(0), "results": {}})
    damage = got["variables"]["fatigue_damage_static"][1][0]
    assert expected > 0
    assert damage == pytest.approx(expected, rel=1e-12)
