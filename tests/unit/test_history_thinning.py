"""Thinned histories (simulate(..., output_every=k) and the history budget) and the first-run message."""
from __future__ import annotations

import logging

import numpy as np
import pytest

from vbikit.bridge import paper_beam
from vbikit.solve import Crossing, simulate
from vbikit.solve.compile_notice import announce_compile
from vbikit.solve.simulate import history_stride
from vbikit.solve.system import kernel_data
from vbikit.vehicle import hs20_44


@pytest.mark.parametrize("integrator", ["exact", "rk4"])
def test_thinned_history_is_every_kth_state_of_the_full_one(integrator):
    c = Crossing(paper_beam(16.76, "II", n_modes=5), hs20_44(), speed=20.0, approach=2.0, free_vibration=0.05,
                 integrator=integrator)
    full, thin = simulate(c), simulate(c, output_every=3)
    assert thin.integration_dt == full.dt and thin.dt == pytest.approx(3 * full.dt, rel=1e-12)
    n = thin.time.size
    assert n == full.n_steps // 3 + 1
    for name in ("time", "xi", "xi_dot", "xi_ddot", "q", "q_dot", "wheel_forces", "front_position"):
        np.testing.assert_array_equal(getattr(thin, name), getattr(full, name)[::3][:n], err_msg=name)
    # q̈ is not stored by the kernel but computed afterwards as matrix products over the stored rows
    # (``vehicle_accelerations``): BLAS may split a different number of rows differently, so the same
    # row can differ in its last bits (2.8e-14 m/s² of a 0.32 m/s² peak seen on an AMD EPYC); equal to
    # round-off, not bitwise
    qdd = full.q_ddot[::3][:n]
    np.testing.assert_allclose(thin.q_ddot, qdd, rtol=0, atol=1e-11 * np.abs(qdd).max(), err_msg="q_ddot")


def test_budget_sets_the_stride():
    c = Crossing(paper_beam(16.76, "II", n_modes=20), hs20_44(), speed=20.0)
    data = kernel_data(c)
    per_row = 8 * (3 * 20 + 3 * 11 + 2 * 6)  # bytes of one stored time point
    assert history_stride(999, data, budget=1000 * per_row) == 1
    assert history_stride(1000, data, budget=1000 * per_row) == 2
    assert history_stride(9_999, data, budget=1000 * per_row) == 10  # 10,000 states → 1000
    assert history_stride(10_000, data, budget=1000 * per_row) == 11  # every 10th would keep 1001
    small = simulate(Crossing(paper_beam(16.76, "II", n_modes=5), hs20_44(), speed=20.0, approach=2.0,
                              free_vibration=0.0), history_budget=50 * 8 * (3 * 5 + 3 * 11 + 2 * 6))
    assert small.time.size <= 50 and small.integration_dt < small.dt


def test_bad_output_every_is_refused():
    c = Crossing(paper_beam(16.76, "II", n_modes=5), hs20_44(), speed=20.0)
    with pytest.raises(ValueError, match="output_every"):
        simulate(c, output_every=0)


def test_compile_message_only_without_compiled_kernels(caplog, monkeypatch):
    from vbikit.solve import compile_notice

    monkeypatch.setattr(compile_notice, "_ANNOUNCED", set())  # not yet announced in this process

    class Fresh:  # a dispatcher with nothing compiled and no on-disk cache
        overloads: dict = {}

    with caplog.at_level(logging.INFO, logger="vbikit.solve.compile"):
        announce_compile(Fresh())
    assert "compiling the kernel Fresh, first run only" in caplog.text
    caplog.clear()
    monkeypatch.setattr(compile_notice, "_ANNOUNCED", set())

    class Ready:
        overloads = {"(float64,)": None}

    with caplog.at_level(logging.INFO, logger="vbikit.solve.compile"):
        announce_compile(Ready())
    assert caplog.text == ""
