"""BatchSolver: the batched crossing equals vbikit.solve.simulate — to the last bit for one road
(the same one-lane kernel call), to round-off for roads run together as lanes (the per-lane
arithmetic is the same, but the compiler orders the sums of a vectorised lane loop differently
from the one-lane variant)."""
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


def assert_roundoff(got, ref, name=""):
    """Equal to round-off: every entry within 1e-10 of the array's largest magnitude."""
    scale = max(float(np.abs(ref).max()), 1e-300)
    np.testing.assert_allclose(got, ref, rtol=0, atol=1e-10 * scale, err_msg=name)


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
    two_threads = solver.run_many(roads, threads=2)  # two kernel calls on threads (GIL released)
    for road, got, got2 in zip(roads, one_thread, two_threads):
        ref = simulate(dataclasses.replace(template, road=road))
        assert got.dt == ref.dt == got2.dt
        for name in FIELDS:
            assert_roundoff(getattr(got, name), getattr(ref, name), name)
            assert_roundoff(getattr(got2, name), getattr(ref, name), name)


def test_other_road_spacing_and_smooth_road_get_their_own_step():
    template = Crossing(paper_beam(16.76, "II", n_modes=4), two_axle_truck(), PointTire(), _roads(1)[0], speed=25.0)
    solver = BatchSolver(template)
    for road in (_roads(1, spacing=0.05)[0], None):
        got, ref = solver.run(road), simulate(dataclasses.replace(template, road=road))
        assert got.dt == ref.dt
        np.testing.assert_array_equal(got.xi, ref.xi)


def test_many_roads_mixed_steps_chunked_and_padded():
    """35 roads: more than one kernel call of MAX_LANES lanes, a padded last call, and roads of
    another spacing (the same step: one call reads both stations) and a smooth road (another step) in
    between; the order is kept."""
    from vbikit.solve.simulate import MAX_LANES

    roads = _roads(33)
    roads[5] = _roads(1, spacing=0.05)[0]
    roads[17] = None
    assert len(roads) > MAX_LANES
    template = Crossing(paper_beam(16.76, "II", n_modes=4), two_axle_truck(), PointTire(), roads[0], speed=25.0)
    results = BatchSolver(template).run_many(roads)
    for k in (0, 5, 16, 17, 31, 32):
        ref = simulate(dataclasses.replace(template, road=roads[k]))
        assert results[k].dt == ref.dt
        assert_roundoff(results[k].xi, ref.xi)
        assert_roundoff(results[k].wheel_forces, ref.wheel_forces)


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
        assert_roundoff(got.xi, ref.xi)
        assert_roundoff(got.wheel_forces, ref.wheel_forces)
