"""BatchSolver: the batched crossing equals vbikit.solve.simulate to the last bit."""
from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from vbikit.bridge.presets import paper_beam
from vbikit.contact import MultiPointTire, PointTire
from vbikit.road.psd import RoadPSD, random_profile
from vbikit.solve import Crossing, simulate
from vbikit.solve.batch import BatchSolver
from vbikit.vehicle.presets import hs20_44, two_axle_truck

FIELDS = ("time", "xi", "xi_dot", "xi_ddot", "q", "q_dot", "q_ddot", "wheel_forces", "contact_lengths")


def _roads(n, spacing=0.01):
    return [random_profile(RoadPSD.iso("C"), seed, spacing=spacing, length=200) for seed in range(n)]


@pytest.mark.parametrize("integrator", ["rk4", "newmark"])
@pytest.mark.parametrize("vehicle, tire", [(two_axle_truck, PointTire()), (hs20_44, MultiPointTire(4))])
def test_batched_equals_simulate(integrator, vehicle, tire):
    roads = _roads(3)
    template = Crossing(paper_beam(16.76, "II", n_modes=4), vehicle(), tire, roads[0], speed=25.0,
                        integrator=integrator)
    solver = BatchSolver(template)
    one_thread = solver.run_many(roads)  # the kernels called directly
    two_threads = solver.run_many(roads, threads=2)  # through the nogil wrappers
    for road, got, got2 in zip(roads, one_thread, two_threads):
        ref = simulate(dataclasses.replace(template, road=road))
        assert got.dt == ref.dt == got2.dt
        for name in FIELDS:
            np.testing.assert_array_equal(getattr(got, name), getattr(ref, name), err_msg=name)
            np.testing.assert_array_equal(getattr(got2, name), getattr(ref, name), err_msg=name)


def test_other_road_spacing_and_smooth_road_get_their_own_step():
    template = Crossing(paper_beam(16.76, "II", n_modes=4), two_axle_truck(), PointTire(), _roads(1)[0], speed=25.0)
    solver = BatchSolver(template)
    for road in (_roads(1, spacing=0.05)[0], None):
        got, ref = solver.run(road), simulate(dataclasses.replace(template, road=road))
        assert got.dt == ref.dt
        np.testing.assert_array_equal(got.xi, ref.xi)


def test_static_reference_is_shared_and_equal():
    from vbikit.analysis.impact import static_modal_history

    template = Crossing(paper_beam(16.76, "II", n_modes=4), two_axle_truck(), PointTire(), _roads(1)[0], speed=25.0)
    solver = BatchSolver(template)
    res = solver.run(template.road)
    np.testing.assert_array_equal(solver.static_modal(res.dt), static_modal_history(simulate(template)))


def test_right_wheel_line_profile_equals_simulate():
    from vbikit.road.psd import correlated_profile

    left = _roads(2)
    rights = [correlated_profile(road, RoadPSD.iso("C"), seed, 0.5, spacing=0.01, length=200)
              for seed, road in enumerate(left)]
    template = Crossing(paper_beam(16.76, "II", n_modes=4), hs20_44(), PointTire(), left[0], speed=25.0,
                        road_right=rights[0])
    solver = BatchSolver(template)
    for road, right, got in zip(left, rights, solver.run_many(list(zip(left, rights)))):
        ref = simulate(dataclasses.replace(template, road=road, road_right=right))
        np.testing.assert_array_equal(got.xi, ref.xi)
        np.testing.assert_array_equal(got.wheel_forces, ref.wheel_forces)
