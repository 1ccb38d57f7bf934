"""The implicit step evaluates the contact law once a step on the common path (vbikit.solve.kernels).

On the `vbikit demo` crossing (HS20-44, 36 contact points, ISO class C, loss of contact allowed)
no contact opens or closes, so every step must settle with one evaluation of the law and exact
increments (before: 3.24 evaluations a step), holding the law to the same tolerance: the contact
forces of each step are checked here against the law evaluated afresh at the stored end state by
the library's own ``contact_forces`` (the kernel's iterate and the law must agree to
IMPLICIT_TOLERANCE of the largest static wheel load).
"""
from __future__ import annotations

import logging
import re

import numpy as np

from vbikit.scenario import demo_scenario_text, scenario_from_toml
from vbikit.scenario.preflight import preflight
from vbikit.solve import simulate
from vbikit.solve import integrators
from vbikit.solve.integrators import IMPLICIT_TOLERANCE


def test_demo_settles_with_one_contact_evaluation_a_step(caplog, monkeypatch):
    from vbikit.solve import kernels

    crossing = preflight(scenario_from_toml(demo_scenario_text(), source="demo.toml")).built.crossing
    calls = []
    original = kernels.implicit

    def kernel(*args):
        calls.append(args)
        return original(*args)

    monkeypatch.setattr(kernels, "implicit", kernel)
    monkeypatch.setattr(integrators, "USE_LEAN", False)  # implicit itself (the lean kernel: test_lean_kernel.py)
    with caplog.at_level(logging.DEBUG, logger="vbikit.solve.integrators"):
        simulate(crossing)
    per_step = [float(m.group(1)) for r in caplog.records
                if (m := re.search(r"([0-9.]+) contact-law evaluations per step", r.getMessage()))]
    assert per_step and per_step[-1] == 1.0  # 3.24 before the one-evaluation step
    assert not [r for r in caplog.records if "did not converge" in r.getMessage()]
    # the stored wheel forces hold the law, evaluated afresh at the stored end states (every 35th row)
    (dt, motion, modes, vehicles, points, road, unilateral, step, vstep, xi, dxi, q, dq, ddxi, ddq, wheel_force,
     wheel_len, past_p, past_g, resume, x_past, tol, max_iterations, lanes, stride, span) = calls[-1]
    assert not resume  # the run's start: the hold's loads before it are the start's own
    # the secant road rate (vbikit.solve.kernels, "the road rate"), negative: the call starts at the run's
    # start, whose state reads the road ahead only; every step end the secant over ±dt/2
    assert span == -0.5 * dt
    n_cp, n_m, n_d, n_w = points.origin.size, xi.shape[2], q.shape[2], wheel_force.shape[2]
    worst = 0.0
    rows = range(1, xi.shape[1], 35)
    for i in rows:
        cache = kernels.new_cache(n_cp, n_m, 1)
        work = kernels.new_work(n_cp, n_d, 1)
        wf, wl = np.zeros((n_w, 1)), np.zeros((n_w, 1))
        kernels.point_kinematics(motion, 2 * i * stride, points, cache.x, cache.vx)
        state = [np.ascontiguousarray(a[0, i].reshape(-1, 1)) for a in (xi, dxi, q, dq)]
        kernels.contact_forces(*state, modes, vehicles, points, road, unilateral, cache, work, wf, wl,
                               kernels.MANY_LANES, abs(span))
        worst = max(worst, float(np.abs(wf[:, 0] - wheel_force[0, i]).max()))
    assert len(rows) > 30
    assert tol == IMPLICIT_TOLERANCE * float(np.abs(crossing.vehicle.static_wheel_loads()).max())
    assert worst <= 6 * tol  # a wheel's six points, each within the tolerance
