"""The run-in (``vbikit.solve.run_in``, ``crossing.run_in``): the vehicles driven alone over the road behind
their start, so that a run starts them settled.  Checked against the coupled kernel over the same distance
(an approach that much longer: the reference, independent of the run-in's linear recursion and its
compiled recursion) on traffic events of Bridge 2, and its compiled recursion, vehicle by vehicle, against the
whole event's recursion step by step in numpy."""
from __future__ import annotations

import dataclasses
import sys
from pathlib import Path

import numpy as np
import pytest

from vbikit.solve import Crossing, simulate

ROOT = Path(__file__).resolve().parents[2]


def _events(n: int, approach: float, run_in: float = 0.0, trucks: int = 1, coherence: float = 1.0):
    sys.path.insert(0, str(ROOT / "benchmarks"))
    from bench_traffic import _stream

    from vbikit.scenario.build import with_scenario_road
    from vbikit.traffic.study import traffic_study

    base = {"bridge": {"model": "paper-bridge-2", "n_modes": 10}, "tire": {"model": "point"},
            "road": {"class": "B", "spacing": 0.01, "right_coherence": coherence}, "crossing": {"approach": approach}}
    job = traffic_study(_stream(4 * n if trucks == 1 else 400, 600.0), base, batch_size=16)
    ctx = job.context()
    out = []
    for e in [e for e in range(job.size) if len(job.events[e]) == trucks][:n]:
        c = dataclasses.replace(job.crossing(e), run_in=run_in, road=None, road_right=None)
        out.append((with_scenario_road(c, ctx.scenario.road, ctx.scenario, job.road_seed(e)), ctx.plan))
    return out


def _im(crossing, plan) -> float:
    from vbikit.analysis.response import reduce_crossing

    return reduce_crossing(simulate(crossing), plan, names=["impact_factor"])[0][0]["impact_factor"]


def test_a_run_in_gives_the_long_approachs_impact_factors():
    """Eight one-truck events: approach 10 m after a 190 m run-in against a 200 m approach run coupled all
    the way (the same road: windows of one realisation) — within 1e-3 on every event, while the default
    start (10 m, no run-in) differs by more than 0.01 root mean square (docs/traffic.md: 0.044 over 300)."""
    long_ = np.array([_im(c, p) for c, p in _events(8, 200.0)])
    run_in = np.array([_im(c, p) for c, p in _events(8, 10.0, 190.0)])
    rest = np.array([_im(c, p) for c, p in _events(8, 10.0)])
    assert np.max(np.abs(run_in - long_)) < 1e-3
    assert np.sqrt(np.mean((rest - long_) ** 2)) > 1e-2


@pytest.mark.parametrize("integrator", ["exact", "newmark", "rk4"])
def test_every_integrator_starts_from_the_run_in_as_from_the_longer_approach(integrator):
    """The HS20-44 on the paper's 16.76 m beam (6 modes), class B, 20 m/s: 10 m approach after a 40 m run-in
    against a 50 m approach (before the bridge the same road), three roads, each integrator: IMs within
    2e-4 for the exact integrator (the run-in begins at rest where the long approach does; with a run-in
    step 2 or 4 times the run's, its IMs moved by up to 7e-4 and 2.5e-3), 5e-4 for Newmark and RK4 (the
    run-in is the exact map with the exact integrator's road rate, theirs differ over the 40 m: 2.2e-4 on
    the third road, whose IM is 0.007; the start at rest: 0.04 root mean square on traffic events)."""
    from vbikit.analysis import point_response
    from vbikit.bridge.presets import paper_beam
    from vbikit.road.psd import RoadPSD, random_profile
    from vbikit.vehicle.presets import hs20_44

    beam = paper_beam(16.76, "II", n_modes=6)
    for seed in (1, 2, 3):
        road = random_profile(RoadPSD.iso("B"), seed=seed)
        ims = [point_response(simulate(Crossing(beam, hs20_44(), road=road, speed=20.0, approach=a, run_in=r,
                                                integrator=integrator)), None, 0.0).displacement_impact.impact_factor
               for a, r in ((50.0, 0.0), (10.0, 40.0))]
        assert abs(ims[1] - ims[0]) < (2e-4 if integrator == "exact" else 5e-4), (seed, ims)


@pytest.mark.parametrize("chunk", [4096, 333])
def test_the_compiled_recursion_is_the_recursion_step_by_step(chunk, monkeypatch):
    """The run-in's ≈ 2,200 steps in one chunk of road loads, and in chunks of 333 steps (``CHUNK_STEPS``)."""
    from vbikit.solve import run_in

    monkeypatch.setattr(run_in, "CHUNK_STEPS", chunk)
    _compiled_against_numpy()


def _run_in_inputs(trucks: int = 1, every: int = 4, coherence: float = 1.0):
    """The run-in of a ``trucks``-truck traffic event on Bridge 2 (10 m approach, 60 m run-in) at ``every``
    times the run's step: its crossing, kernel data, step map, step, start travel and speeds, and road
    (``coherence``: the right wheel line's, ``road.right_coherence``)."""
    from vbikit.solve.modal_step import vehicle_step
    from vbikit.solve.plan import plan_run
    from vbikit.solve.simulate import _road
    from vbikit.solve.system import point_positions

    (crossing, _), = _events(1, 10.0, 60.0, trucks=trucks, coherence=coherence)
    plan = plan_run(crossing)
    data, dt = plan.kernel_data, every * plan.dt
    travel0, speed0 = np.asarray(plan.grid.travel[0], float), np.asarray(plan.grid.speed[0], float)
    x_back, _ = point_positions(data, travel0 - 60.5 * speed0 / speed0.min(), speed0)
    x0, _ = point_positions(data, travel0, speed0)
    road = _road([crossing], float(min(x_back.min(), x0.min())), float(max(x_back.max(), x0.max())))
    return crossing, data, vehicle_step(data.vehicles, dt), dt, travel0, speed0, road


def _compiled_against_numpy(trucks: int = 1):
    from vbikit.solve.run_in import settled_state, settled_state_by_steps

    inputs = _run_in_inputs(trucks)
    fast, slow = settled_state(*inputs), settled_state_by_steps(*inputs)
    assert fast.shape == (2 * inputs[1].vehicles.gravity.size,)
    assert np.max(np.abs(fast - slow)) <= 1e-9 * np.max(np.abs(slow)) and np.max(np.abs(slow)) > 0


def test_a_several_truck_event_is_stepped_vehicle_by_vehicle():
    """A three-truck event (both directions on Bridge 2): the recursion splits into one group per truck, each
    with its own q and q̇ and wheels (``independent_blocks``), and the groups stepped apart give the recursion
    of the whole event step by step (``settled_state_by_steps``)."""
    from vbikit.solve.run_in import independent_blocks, recursion

    crossing, data, step, *_ = _run_in_inputs(trucks=3)
    a_mat, m0, m1, _ = recursion(data, step)
    groups = independent_blocks(a_mat, m0, m1)
    sizes = [v.vehicle.n_dof for v in crossing.vehicles]
    wheels = [len(v.vehicle.static_wheel_loads()) for v in crossing.vehicles]
    assert [g[0].size for g in groups] == [2 * n for n in sizes]
    assert [g[1].size for g in groups] == wheels
    first = np.cumsum([0, *sizes[:-1]])
    n_d = sum(sizes)
    for (states, _), lo, n in zip(groups, first, sizes):
        assert states.tolist() == [*range(lo, lo + n), *range(n_d + lo, n_d + lo + n)]
    assert {v.direction for v in crossing.vehicles} == {"+x", "-x"}
    _compiled_against_numpy(trucks=3)


def test_the_road_loads_are_the_road_read_as_the_step_loops_read_it():
    """The run-in's wheel loads (``kernels.run_in_loads``: one reading a half step, shared by two steps)
    against the same loads by numpy's linear interpolation, point by point, the rate the secant over
    ±|v| dt/2 (the step loops' reading, ``kernels.road_point``): a three-truck event in both directions on
    both wheel lines of Bridge 2 (right_coherence 0.5: the lines differ), within 1e-9 of the largest load."""
    from vbikit.solve.run_in import road_loads, run_in_steps

    crossing, data, _, dt, travel0, speed0, road = _run_in_inputs(trucks=3, every=1, coherence=0.5)
    n = run_in_steps(crossing, dt, speed0)
    pts = data.points
    t = dt * (np.arange(n + 1) - n)
    x = pts.origin[None, :] + pts.direction[None, :] * (travel0[pts.vehicle][None, :] + speed0[pts.vehicle][None, :] * t[:, None])
    vx = pts.direction * speed0[pts.vehicle]
    half = np.abs(vx) * 0.5 * dt
    lines = np.minimum(pts.line, road.elevations.shape[0] - 1)
    assert set(lines.tolist()) == {0, 1}
    expected = np.zeros((n + 1, data.vehicles.wheel_rows.shape[0]))
    for p in range(x.shape[1]):
        z = road.elevations[lines[p], :, 0]
        r = np.interp(x[:, p], road.stations, z)
        rate = (np.interp(x[:, p] + half[p], road.stations, z) - np.interp(x[:, p] - half[p], road.stations, z)) \
            * vx[p] / (2 * half[p])
        expected[:, pts.wheel[p]] += pts.stiffness[p] * (r - pts.gap[p]) + pts.damping[p] * rate + pts.fixed_load[p]
    got = np.vstack([road_loads(data, dt, travel0, speed0, road, n, 0, 99), road_loads(data, dt, travel0, speed0, road, n, 100, n)])
    assert np.max(np.abs(got - expected)) <= 1e-9 * np.max(np.abs(expected))


def test_bad_run_ins_are_refused():
    from vbikit.bridge.beam import EulerBernoulliBeam
    from vbikit.vehicle import quarter_car

    beam = EulerBernoulliBeam(20.0, 2e9, 5000.0, n_modes=2)
    for bad in (-1.0, 1000.5, float("nan")):  # (MAX_RUN_IN: 1000 m)
        with pytest.raises(ValueError, match="crossing.run_in must be 0 … 1000 m"):
            Crossing(beam, quarter_car(), run_in=bad)
    with pytest.raises(ValueError, match="a contact point is on the deck"):
        simulate(Crossing(beam, quarter_car(), approach=0.0, run_in=20.0))


def test_the_scenario_key_reaches_the_crossing():
    from vbikit.scenario import build, scenario_from_toml

    text = ('[bridge]\nmodel = "paper-bridge-1-beam"\nn_modes = 3\n[vehicle]\nmodel = "quarter-car"\n'
            '[road]\nclass = "B"\n[crossing]\nspeed_kmh = 60\nrun_in = 90\n')
    assert build(scenario_from_toml(text, source="s.toml")).crossing.run_in == 90.0


def test_groups_merge_where_anything_couples_them():
    """``independent_blocks`` on hand-made patterns (2 DOFs a vehicle, z = (q, q̇)): three vehicles apart give
    three groups with their own wheels; a wheel loading DOFs of two vehicles, or a stiffness between them,
    merges them; a wheel without DOFs belongs to none."""
    from vbikit.solve.run_in import independent_blocks

    n_d, n_w = 6, 4
    a_mat = np.zeros((2 * n_d, 2 * n_d))
    for lo in (0, 2, 4):  # each vehicle's q and q̇ coupled among themselves
        for r in (lo, lo + 1, n_d + lo, n_d + lo + 1):
            for c in (lo, lo + 1, n_d + lo, n_d + lo + 1):
                a_mat[r, c] = 0.1
    m0 = np.zeros((2 * n_d, n_w))
    m0[n_d + 0, 0] = m0[n_d + 3, 1] = m0[n_d + 5, 2] = 1.0  # wheel 3: no DOF
    groups = independent_blocks(a_mat, m0, np.zeros_like(m0))
    assert [g[0].tolist() for g in groups] == [[0, 1, 6, 7], [2, 3, 8, 9], [4, 5, 10, 11]]
    assert [g[1].tolist() for g in groups] == [[0], [1], [2]]
    m0[n_d + 2, 0] = 1.0  # wheel 0 now loads vehicles 0 and 1
    assert [g[1].tolist() for g in independent_blocks(a_mat, m0, np.zeros_like(m0))] == [[0, 1], [2]]
    m0[n_d + 2, 0] = 0.0
    a_mat[n_d + 5, 2] = 0.1  # vehicle 2's q̇ reads vehicle 1's q
    assert [g[0].size for g in independent_blocks(a_mat, m0, np.zeros_like(m0))] == [4, 8]
