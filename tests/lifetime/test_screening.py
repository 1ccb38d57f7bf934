"""Screening + dynamics against dynamics on every event: identical block maxima."""
import numpy as np

from vbikit.lifetime.jobs import EVENT_STRIDE
from vbikit.lifetime.run import prepare, screen
from vbikit.lifetime.screening import candidates


def _spec(days=5):
    return {"seed": 5, "days": days, "amplification": 1.0,
            "traffic": {"records": "examples/traffic/stream.csv", "trucks_per_day": 100},
            "bridge": {"model": "paper-bridge-1-beam", "n_modes": 3}, "tire": {"model": "point"},
            "road": {"class": "B"}, "crossing": {"approach": 5},
            "load_effects": [{"kind": "moment", "x": 3.9, "name": "M"}, {"kind": "reaction", "support": 1, "name": "R1"}],
            "block": "day", "distribution": "gumbel"}


def test_screening_gives_the_block_maxima_of_dynamics_on_every_event(tmp_path):
    """One simulated day on the 9.16 m beam, class-B roads, A = 1.25 (event amplifications here reach
    1.11 with the trucks settled by the population's run-in; 0.75 when they started at rest): every event
    simulated vs screening + dynamics.  Each day's maximum total effect (M at 3.9 m, exit reaction) is identical, with a
    fraction of the events simulated; and every event left out satisfies (1 + A)·R_st < D_b
    (the rule), with A bounding every event's amplification (checked on all of them)."""

    spec = _spec()
    prep = prepare(spec, ".")
    static = prep.static_job().run_batch((0,))
    st = static["ev_static"]
    day = static["ev_day"]
    gid = day * EVENT_STRIDE + static["ev_index"]
    job = prep.dynamic_job(gid)
    every = np.stack([job.run_event(int(g))["dyn_peak"] for g in gid])  # dynamics on every event
    signs = np.array([ln.sign for ln in prep.setup.lines])
    amp = every / st - 1.0
    assert np.nanmax(amp) <= 1.25  # the bound A holds for every event here, so the rule is exact
    simulated, dyn, rounds, bound = screen(st, signs, day, 1, 1.25, lambda idx, r: every[idx])
    assert bound == 1.25
    full_max = np.max(every * signs, axis=0)
    screened_max = np.nanmax(np.where(simulated[:, None], dyn * signs, np.nan), axis=0)
    assert np.array_equal(full_max, screened_max)
    assert 0 < simulated.sum() < len(simulated)  # some events screened out (a day of 100 trucks: 37 of 106)
    # events left out cannot reach the block maximum
    left = ~simulated
    assert np.all((2.25 * st[left] * signs) < full_max[None, :])


def test_candidates_rule_by_hand():
    """Two blocks, one effect, A = 0.5: block 0 has D = 10 → events with 1.5·R_st ≥ 10 (R_st ≥ 6.67);
    block 1 has D = 4 → R_st ≥ 2.67 (hand computation)."""
    st = np.array([[9.0], [6.0], [7.0], [2.0], [3.0], [2.5]])
    block = np.array([0, 0, 0, 1, 1, 1])
    thr = np.array([[10.0], [4.0]])
    got = candidates(st, np.array([1.0]), block, thr, 0.5)
    assert got.tolist() == [0, 2, 4]
    got = candidates(st, np.array([1.0]), block, thr, 0.5, simulated=np.array([1, 0, 0, 0, 0, 0], bool), per_round=1)
    assert got.tolist() == [2, 4]


def test_stored_records_are_the_days_vehicles():
    """The static pass stores the records of the events the dynamics may need; they are the
    vehicles of those events as the day's traffic draws them again (times, speeds, lanes, axles)."""
    import xarray as xr

    from vbikit.lifetime.jobs import day_traffic
    from vbikit.lifetime.run import stored_records

    prep = prepare(_spec() | {"fatigue": {"dynamic_sample": 0.1, "details": [
        {"name": "d", "effect": "M", "section_modulus": 0.004, "category": "EN 71"}]}}, ".")
    job = prep.static_job()
    part = job.run_batch((2,))
    static = xr.Dataset({k: ((f"{k}_0",), v) for k, v in part.items() if v.ndim == 1})
    stored = stored_records(static)
    records, events = day_traffic(prep.model, job._digest, prep.setup, 2, prep.spec.seed)
    assert len(stored) >= min(len(events), 1) and part["ev_sample"].sum() > 0
    for g, recs in stored.items():
        day, k = divmod(g, EVENT_STRIDE)
        assert day == 2
        expected = [records[i] for i in events[k]]
        assert [(r.time, r.speed, r.lane, r.direction, r.axle_loads, r.axle_spacings) for r in recs] == \
               [(r.time, r.speed, r.lane, r.direction, r.axle_loads, r.axle_spacings) for r in expected]


def test_trucks_the_multibody_builder_refuses_are_built_rigid_with_exact_loads():
    """A 3-S2 whose tractor cannot carry the semitrailer (150 / 20 / 20 / 60 / 60 kN) and one with
    axles lighter than the default unsprung masses (80 / 5 / 5 / 5 / 5 kN): both are built (rigid,
    lighter unsprung masses) and their static wheel loads sum to the axle loads (statics)."""
    from vbikit.lifetime.jobs import _axle_truck

    for loads in ((150e3, 20e3, 20e3, 60e3, 60e3), (80e3, 5e3, 5e3, 5e3, 5e3)):
        truck = _axle_truck(loads, (5.5, 1.3, 9.5, 1.3))
        wheel = truck.static_wheel_loads()
        assert np.allclose(wheel[0::2] + wheel[1::2], loads, rtol=1e-9)
