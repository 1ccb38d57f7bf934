"""Peer: pybtls (BTLS, Caprani; PyPI 1.0.1) on the same traffic and influence line."""
import numpy as np
import pytest

pybtls = pytest.importorskip("pybtls")


def btls_traffic(days):
    """The vehicle records of ``days`` as a BTLS traffic loader (two lanes, one per direction;
    kN, m, m/s, s; axle widths 1.8 m) — also used by benchmarks/bench_static_screening.py."""
    vehicles = []
    for recs in days:
        for r in recs:
            v = pybtls.Vehicle(len(r.axle_loads))
            v.set_axle_weights([p / 1e3 for p in r.axle_loads])  # kN
            v.set_axle_spacings(list(r.axle_spacings) + [0.0])  # m
            v.set_axle_widths([1.8] * len(r.axle_loads))
            v.set_velocity(r.speed)  # m/s
            v.set_time(r.time)  # s
            v.set_direction(1 if r.direction == "+x" else 2)
            v.set_local_lane(1)
            v.set_trans(0.0)
            vehicles.append(v)
    loader = pybtls.TrafficLoader(no_lane=2)
    loader.add_traffic(vehicles)
    return loader


def test_static_daily_maxima_and_characteristic_value_match_pybtls(tmp_path):
    """Six days of generated two-direction traffic on a 16.76 m simply supported span, midspan
    moment: vbikit's daily maxima (convolution with peak refinement) against BTLS's block maxima
    (built-in influence line 1, time step 1 ms) within 0.1 % (BTLS writes 0.1 kN m), and the
    1,000-year Gumbel return level of each within 0.1 %."""
    from vbikit.extremes import fit_block_maxima, return_level
    from vbikit.lifetime.influence import event_static
    from vbikit.lifetime.setup import build_setup, day_events, setup_key
    from vbikit.lifetime.traffic import fit_traffic
    from vbikit.traffic.records import read_records

    L, n_days = 16.76, 6
    model = fit_traffic(read_records("examples/lifetime/wim.csv")).scaled(0.15)
    days = [model.day(d, 1) for d in range(n_days)]
    loader = btls_traffic(days)
    il = pybtls.InfluenceLine("built-in")
    il.set_IL(id=1, length=L)
    bridge = pybtls.Bridge(length=L, no_lane=2)
    bridge.add_load_effect(il)
    config = pybtls.OutputConfig()
    config.set_BM_output(write_summary=True, block_size_days=1)
    sim = pybtls.Simulation(tmp_path)
    sim.add_sim(bridge=bridge, traffic=loader, no_day=n_days, output_config=config, time_step=0.001, tag="peer")
    sim.run(no_core=1)
    text = next((tmp_path / "peer").glob("BM_S_*_Eff_1.txt")).read_text()
    # block, then the block's maximum of events of 1, 2, … trucks [kN m]: the day's maximum is the largest
    btls = np.array([max(float(v) for v in line.split()[1:]) for line in text.splitlines() if line.strip()]) * 1e3
    key = setup_key({"bridge": {"model": "paper-bridge-2-beam", "n_modes": 3}, "tire": {"model": "point"},
                     "road": {"class": "none"}}, ".", [{"kind": "moment", "x": L / 2}], None, 2, 0.01)
    setup = build_setup(key)
    ours = np.array([event_static(r, day_events(setup, r), setup.lines, setup.span, setup.lanes, setup.pattern,
                                  ds=0.05, tables=setup.tables).peaks.max() for r in days])
    assert btls.shape == ours.shape
    assert np.allclose(ours, btls, rtol=1e-3), np.c_[ours, btls]
    rl = [return_level(fit_block_maxima(x, "gumbel", 365), 1000) for x in (ours, btls)]
    assert rl[0] == pytest.approx(rl[1], rel=1e-3)
