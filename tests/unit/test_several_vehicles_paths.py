"""Several vehicles: the labelled results and the automatic time step agree with the analysis path
and with the step rule evaluated at the speeds the vehicles actually reach."""
from __future__ import annotations

import numpy as np
import pytest

from vbikit.analysis import point_response
from vbikit.analysis.impact import static_modal_history
from vbikit.bridge import EulerBernoulliBeam
from vbikit.road import RoadProfile
from vbikit.solve import Crossing, VehicleMotion, choose_time_step, simulate
from vbikit.solve.timestep import EXACT_ROAD_FEATURES_PER_STEP, EXACT_ROUGH_ROAD_LENGTH_PER_STEP
from vbikit.vehicle import hs20_44


@pytest.fixture(scope="module")
def beam():
    return EulerBernoulliBeam(30.0, 2e10, 8000.0, n_modes=10)


@pytest.fixture(scope="module")
def opposing(beam):
    """Two HS20-44 in opposite directions (the case of the bug report) and a third one behind the first."""
    vehicles = (VehicleMotion(hs20_44(), 80 / 3.6, direction="+x", entry_time=0.0),
                VehicleMotion(hs20_44(), 70 / 3.6, direction="-x", entry_time=0.3),
                VehicleMotion(hs20_44(), 60 / 3.6, direction="+x", entry_time=0.9))
    return simulate(Crossing(beam, vehicles=vehicles[:2])), simulate(Crossing(beam, vehicles=vehicles))


def test_to_xarray_static_matches_point_response(opposing):
    two, three = opposing
    assert point_response(two, 10.0).static_displacement.min() == pytest.approx(-11.71e-3, abs=0.01e-3)
    for result in (two, three):
        points = [(10.0, 0.0), (15.0, 0.0), (22.5, 0.0)]
        ds = result.to_xarray(points=points)
        for k, (x, _) in enumerate(points):
            expected = point_response(result, x).static_displacement
            got = ds["static_displacement"].values[:, k]
            np.testing.assert_allclose(got, expected, rtol=0, atol=1e-12 * np.abs(expected).max())
            np.testing.assert_allclose(ds["static_strain"].values[:, k], point_response(result, x).static_strain,
                                       rtol=1e-12, atol=1e-18)


def test_to_xarray_static_is_the_static_modal_history(opposing):
    _, three = opposing
    ds = three.to_xarray(points=[(12.0, 0.0)])
    phi = three.crossing.bridge.mode_shapes([12.0], [0.0])[0]
    np.testing.assert_array_equal(ds["static_displacement"].values[:, 0], static_modal_history(three) @ phi)


def _road(spacing: float) -> RoadProfile:
    x = np.arange(-200.0, 300.0 + spacing, spacing)
    return RoadProfile(x, 1e-4 * np.sin(x), "ripple")


@pytest.mark.parametrize("integrator", ["exact", "newmark"])
def test_auto_step_uses_fastest_vehicle(beam, integrator):
    """Accelerating vehicles: the road term of the step rule uses the largest speed any vehicle reaches."""
    road = _road(0.05)
    few = EulerBernoulliBeam(30.0, 2e10, 8000.0, n_modes=2)
    vehicles = (VehicleMotion(hs20_44(), 25.0, acceleration=1.5, direction="+x", entry_time=0.0),
                VehicleMotion(hs20_44(), 15.0, acceleration=-1.0, direction="-x", entry_time=0.5))
    crossing = Crossing(few, vehicles=vehicles, road=road, integrator=integrator)
    t = np.array([crossing.start_time, crossing.start_time + crossing.duration])
    v_true = max(float(np.max(m.velocity(t))) for m in vehicles)
    assert v_true > 28.0  # the first vehicle speeds up to ≈ 29.7 m/s by the end of the run
    dt = choose_time_step(crossing)
    if integrator == "exact":
        # a road given as arrays (its stations may be edges): 2 cm and two stations a step
        expected = min(EXACT_ROUGH_ROAD_LENGTH_PER_STEP, EXACT_ROAD_FEATURES_PER_STEP * road.spacing) / v_true
    else:
        expected = road.spacing / v_true
    assert dt == pytest.approx(expected, rel=1e-12)
