"""Drive-by datasets at scale: what makes a pass cheap must not change it.

* ``check_cases`` builds one pass per sweep combination and scour class (not every pass) and
  bounds the budget from both ends of the drawn speed range (each end's steps from its own crossing);
* a pass's random road is generated only over the range its wheels touch, and equals there the
  whole-period road of ``vbikit.road.random_profile`` with the same seed;
* the decoupled recursion run on one eigen-coordinate of each conjugate pair equals the plain
  state-space loop;
* one BLAS thread inside ``single_thread_blas``, the previous count after.
"""
from __future__ import annotations

import tomllib
from pathlib import Path

import numpy as np
import pytest

import vbikit.driveby.study as study
from vbikit.driveby.spec import DriveByError, parse_driveby
from vbikit.solve.timestep import EXACT_ROAD_LENGTH_PER_STEP

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "driveby" / "scour_1800.toml"


def _spec(passes: int, **variability):
    data = tomllib.loads(EXAMPLE.read_text())
    data["variability"]["passes"] = passes
    data["variability"].update(variability)
    return parse_driveby(data, EXAMPLE.parent)


def test_check_cases_builds_a_few_passes_and_bounds_the_budget_by_the_speed_range(monkeypatch):
    # a speed range across which the automatic step (EXACT_ROAD_LENGTH_PER_STEP / v) passes the 1 ms sample
    # period: the step, a whole fraction of it, jumps from 1 ms to 0.5 ms inside the range
    jump = EXACT_ROAD_LENGTH_PER_STEP / 1e-3
    v_slow, v_fast = 0.93 * jump, 1.07 * jump
    spec = _spec(40, speed=[v_slow, v_fast])            # 3 classes × 40 passes
    built = []
    real = study.case_crossing

    def counting(s, case):
        built.append(case)
        return real(s, case)

    monkeypatch.setattr(study, "case_crossing", counting)
    study._BUILT.clear()
    total = study.check_cases(spec)
    assert len(spec.cases) == 120 and len(built) <= 8, len(built)   # main built all 120
    # each end of the speed range on its own crossing (no draw): the slow end runs longest, the fast
    # one needs the smaller step (1 ms at the slow end, 0.5 ms at the fast one: the step jumps inside the
    # range, so neither end's steps bound a pass; the slow end's duration / the fast end's step does)
    slow, fast = (real(spec, {"speed": v}) for v in (v_slow, v_fast))
    assert slow.duration > fast.duration and fast.dt < slow.dt
    per_pass = slow.duration / fast.dt
    assert total == pytest.approx(120 * per_pass, rel=1e-12)
    steps = [real(spec, spec.cases[i]) for i in range(0, 120, 7)]
    steps = [c.duration / c.dt for c in steps]
    assert max(steps) <= per_pass * (1 + 1e-12)
    assert max(steps) > max(slow.duration / slow.dt, fast.duration / fast.dt)   # a pass beyond both ends' steps


def test_a_temperature_range_that_makes_ei_negative_is_refused_before_running():
    spec = _spec(2, temperature=[0.0, 80.0], temperature_reference=-30.0, temperature_coefficient=0.01)
    with pytest.raises(DriveByError, match=r"variability\.temperature"):
        study.check_cases(spec)


def test_a_pass_road_is_the_whole_period_road_where_the_wheels_go():
    from vbikit.road.psd import RoadPSD, random_profile
    from vbikit.study.spec import derive_seed

    spec = _spec(2)
    study._BUILT.clear()
    c = study.case_crossing(spec, spec.cases[1])
    lo, hi = c.road_extent()
    assert c.road.x[0] <= lo and c.road.x[-1] >= hi
    assert c.road.x[-1] - c.road.x[0] < 60.0            # ≈ 45 m used, not the 1,310.72 m period
    whole = random_profile(RoadPSD.iso("A"), derive_seed(spec.seed, 1))   # the scenario's defaults
    x = np.linspace(lo, hi, 2001)
    rms = float(np.sqrt(np.mean(whole.z ** 2)))
    assert np.max(np.abs(c.road.elevation(x) - whole.elevation(x))) < 1e-12 * rms


def test_single_thread_blas_sets_one_thread_and_restores():
    from threadpoolctl import threadpool_info, threadpool_limits

    from vbikit._blas import single_thread_blas

    def blas_threads() -> list[int]:
        return [i["num_threads"] for i in threadpool_info() if i["user_api"] == "blas"]

    if not blas_threads():
        pytest.skip("no BLAS thread pool found")
    with threadpool_limits(limits=2, user_api="blas"):  # a count other than 1 to restore
        wanted = blas_threads()
        with single_thread_blas():
            inside = blas_threads()
        assert inside == [1] * len(wanted)
        assert blas_threads() == wanted


def _traffic_spec(passes: int = 2, **extra):
    data = tomllib.loads(EXAMPLE.read_text())
    data["variability"] = {"passes": passes, "speed": [19.0, 21.0], "traffic_flow": 1500.0, **extra}
    data["bridge"]["support_stiffness"] = 2.0e8
    return parse_driveby(data, EXAMPLE.parent)


def test_background_traffic_joins_the_crossing_and_keeps_the_other_draws():
    from vbikit.driveby.variability import draw, parse_variability
    from vbikit.traffic.stream import LaneTraffic, synthetic_stream
    from vbikit.vehicle.model import GRAVITY

    base = parse_variability({"speed": [19.0, 21.0], "vehicle_spread": 0.1})
    more = parse_variability({"speed": [19.0, 21.0], "vehicle_spread": 0.1, "traffic_flow": 1500.0})
    for i in range(3):  # the traffic seed draws last: speed and vehicle factors as without traffic
        a, b = draw(base, 5, i, 4, 2), draw(more, 5, i, 4, 2)
        assert {k: b[k] for k in a} == a and "traffic_seed" in b and "traffic_seed" not in a
    spec = _traffic_spec(6)
    study._BUILT.clear()
    counts = []
    for case in spec.cases:
        c = study.case_crossing(spec, case)
        d = study.case_draw(spec, case)
        # the trucks of the stream generator entering while the instrumented vehicle's front axle is on the deck
        trucks = synthetic_stream([LaneTraffic(2, "-x", 1500.0, 80.0, 8.0)], 0, seed=d["traffic_seed"],
                                  duration=25.0 / d["speed"])
        assert c.n_vehicles == 1 + len(trucks)
        assert [m.direction for m in c.vehicles[1:]] == ["-x"] * len(trucks)
        assert sum(m.vehicle.total_weight for m in c.vehicles[1:]) == pytest.approx(
            sum(sum(t.axle_loads) for t in trucks), rel=1e-9)
        assert c.vehicles[0].speed == pytest.approx(d["speed"]) and c.vehicles[0].direction == "+x"
        counts.append(len(trucks))
    assert max(counts) >= 1                              # at 1500 trucks/h some pass meets one
    i = int(np.argmax(counts))
    row = study.run_case(spec, i)
    assert row["background_vehicles"] == counts[i]
    assert row["background_mass_kg"] == pytest.approx(sum(m.vehicle.total_weight for m in
                                                          study.case_crossing(spec, spec.cases[i]).vehicles[1:]) / GRAVITY)
    # the same pass (same speed, road and noise: the traffic seed draws last) without the trucks
    quiet = _traffic_spec(6)
    object.__setattr__(quiet, "variability", parse_variability({"passes": 6, "speed": [19.0, 21.0]}))
    alone = study.run_case(quiet, i)
    assert alone["background_vehicles"] == 0
    on = slice(int(row["on_bridge_start_sample"]), int(row["on_bridge_end_sample"]))
    h, h0 = row["history"][0, on], alone["history"][0, on]
    assert np.sqrt(np.mean((h - h0) ** 2)) > 0.05 * np.sqrt(np.mean(h0 ** 2))   # more than the 5 % noise


def test_background_traffic_needs_the_coupled_mode():
    data = tomllib.loads(EXAMPLE.read_text())
    data["variability"] = {"passes": 2, "traffic_flow": 600.0}
    data["coupling"] = "decoupled"
    with pytest.raises(DriveByError, match=r"variability\.traffic_flow"):
        study.check_cases(parse_driveby(data, EXAMPLE.parent))


def test_decoupled_pass_merges_the_wheels_of_an_axle_on_a_beam_without_changing_it(monkeypatch):
    from vbikit.bridge.continuous import ContinuousBeam
    from vbikit.driveby.decoupled import simulate_decoupled

    spec = _spec(2)
    study._BUILT.clear()
    crossing = study.case_crossing(spec, spec.cases[1])
    bridge = crossing.bridge
    assert isinstance(bridge, ContinuousBeam) and bridge.lateral_invariant
    x = np.linspace(-1.0, 26.0, 55)
    assert np.array_equal(bridge.mode_shapes(x, np.full(x.size, 0.9)), bridge.mode_shapes(x, np.full(x.size, -0.9)))
    merged = simulate_decoupled(crossing)
    monkeypatch.setattr(ContinuousBeam, "lateral_invariant", property(lambda self: False))
    wheel_by_wheel = simulate_decoupled(crossing)
    for a, b in ((merged.xi, wheel_by_wheel.xi), (merged.q_ddot, wheel_by_wheel.q_ddot)):
        assert np.max(np.abs(a - b)) < 1e-10 * np.max(np.abs(b))
