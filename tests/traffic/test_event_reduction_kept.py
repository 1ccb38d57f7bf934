"""The per-stream stores of a traffic event's reduction (``vbikit.analysis.response``: the plan's
points and the weighted mode tables of ``static_point_histories``): the static reference at a point
against the modal static deflection summed from the bridge's own mode shapes, and events run one
after another in one process against each run in a fresh context (no stale value served)."""
from __future__ import annotations

import numpy as np
import pytest

from vbikit._kept import forget_kept
from vbikit.analysis import response
from vbikit.solve import simulate
from vbikit.traffic import LaneTraffic, synthetic_stream
from vbikit.traffic import study as traffic
from vbikit.traffic.study import traffic_study

#: a small, fast base: Bridge 2 beam with 4 modes, ISO B road of 200 m, point tires
BASE = {"bridge": {"model": "paper-bridge-2-beam", "n_modes": 4}, "road": {"class": "B", "length": 200.0},
        "crossing": {"approach": 5.0, "free_vibration": 0.1}}


@pytest.fixture(scope="module")
def stream():
    return synthetic_stream([LaneTraffic(1, "+x", 900, 80, 5), LaneTraffic(2, "-x", 900, 70, 5)], 24, seed=2)


def _fresh_context(monkeypatch) -> None:
    """Forget every event context and kept value of this process (the bridges' stores, the weighted
    tables among them)."""
    traffic._CONTEXTS.clear()
    forget_kept()


def _flat(event) -> dict[str, float]:
    """An event's output rows (``run_event``) as one name → value map (None as NaN)."""
    (points, row), per_vehicle = event
    out = {f"p{i}.{k}": v for i, p in enumerate(points) for k, v in p.items()} | dict(row)
    out |= {f"v{i}.{k}": v for i, v_ in enumerate(per_vehicle) for k, v in v_.items()}
    return {k: np.nan if v is None else float(v) for k, v in out.items()}


def test_static_point_history_is_the_modal_static_deflection(stream):
    """Expected value, independent of the tables and the compiled pass: the modal static deflection
    at the point, R_st(t) = −Σ_p P_p Σ_m φ_m(x_p(t)) φ_m(x_r) / ω_m² (ξ_st,m = −Σ_p φ_m(x_p) P_p / ω_m²,
    projected on φ(x_r)), with φ_m evaluated by the bridge itself at every contact point's position
    (not interpolated from tables): equal up to the tables' cubic interpolation (≪ 1e-6 of the peak)."""
    job = traffic_study(stream, BASE, lanes=[0.0, 0.0], seed=5)
    result = simulate(job.crossing(1))
    bridge, crossing = result.crossing.bridge, result.crossing
    x_r = 0.3 * bridge.span
    (disp, _), = response.static_point_histories(result, [(x_r, 0.0)])
    cp = crossing.contact
    loads = cp.weight * crossing.vehicle.static_wheel_loads()[cp.wheel]
    origin, direction, y = crossing.point_kinematics()
    x = origin + direction * np.asarray(result.travel).reshape(len(result.time), -1)[:, crossing.point_vehicle]
    on = (x >= 0.0) & (x <= bridge.span)
    phi_r = np.asarray(bridge.mode_shapes([x_r], [0.0])[0], float)
    shapes = np.asarray(bridge.mode_shapes(np.clip(x, 0.0, bridge.span).ravel(), np.broadcast_to(y, x.shape).ravel()),
                        float).reshape(*x.shape, -1)
    expected = -np.einsum("tpm,m,tp->t", shapes, phi_r / bridge.omega**2, on * loads)
    assert np.max(np.abs(expected)) > 0
    np.testing.assert_allclose(disp, expected, rtol=0, atol=1e-6 * np.max(np.abs(expected)))


def test_events_in_one_process_equal_each_event_in_a_fresh_context(stream, monkeypatch):
    """Events with other vehicles, speeds and road seeds one after another in one process, then each
    alone after everything kept was forgotten: the same numbers bit for bit (a kept value served to the
    wrong event would change them); the same bridge and tables read at another point give that
    point's static references (ξ_st·φ and ξ_st·ε of ``static_modal_history``, an independent path),
    not the kept tables of the first point."""
    job = traffic_study(stream, BASE, lanes=[-1.8, 1.8], seed=5, batch_size=4)
    single = next(e for e in range(job.size) if len(job.events[e]) == 1)
    several = next(e for e in range(job.size) if len(job.events[e]) > 1)
    in_turn = [_flat(job.run_event(e)) for e in (single, several, single + 1)]
    assert in_turn[0]["p0.max_static_displacement"] != in_turn[1]["p0.max_static_displacement"]
    for k, e in enumerate((single, several, single + 1)):
        _fresh_context(monkeypatch)
        alone = _flat(traffic_study(stream, BASE, lanes=[-1.8, 1.8], seed=5, batch_size=4).run_event(e))
        np.testing.assert_equal(alone, in_turn[k])

    result = simulate(job.crossing(several))
    response.static_point_histories(result, response.plan_points(result, job.context().plan))  # midspan's tables kept
    (disp, strain), = response.static_point_histories(result, [(5.0, 0.0)])  # the same mode tables, another point
    xi_st = response.static_modal_history(result)
    phi, eps = response.point_shapes(result.crossing.bridge, 5.0, 0.0)
    np.testing.assert_allclose(disp, xi_st @ phi, rtol=0, atol=1e-12 * np.max(np.abs(xi_st @ phi)))
    np.testing.assert_allclose(strain, xi_st @ eps, rtol=0, atol=1e-12 * np.max(np.abs(xi_st @ eps)))
    assert np.min(disp) != pytest.approx(in_turn[1]["p0.max_static_displacement"], rel=1e-3)
