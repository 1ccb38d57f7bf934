# Reference: superposition (linearity of the modal bridge equations, Frýba 1972 ch. 1) and the
# paper's Eq. 6 ("A Multi-Point Tire Model for Studying Bridge–Vehicle Coupled Vibration"):
# n points of weight 1/n at offsets ξ_p; n = 1 is the single-point model (docs/model-data.md §3).
# For a moving force the multi-point bridge response is therefore exactly the average of n
# single-point responses whose paths are shifted by ξ_p; no number here comes from vbikit.
from __future__ import annotations

import numpy as np
import pytest

from vbikit.bridge import paper_beam
from vbikit.contact import MultiPointTire, PointTire
from vbikit.road import RoadPSD, random_profile
from vbikit.solve import Crossing, simulate
from vbikit.vehicle import hs20_44, moving_force

DT = 2e-4  # fixed, so that every run uses the same time grid t_k = k·dt
APPROACH = 2.0


@pytest.mark.parametrize("layout_rule", ["ends", "cells"])
@pytest.mark.parametrize("n", [3, 6])
def test_multipoint_moving_force_is_average_of_shifted_point_forces(n, layout_rule):
    beam = paper_beam(16.76, "II", n_modes=10)
    tire = MultiPointTire(n_points=n, layout_rule=layout_rule)
    offsets, weights = tire.layout()
    assert np.allclose(weights, 1.0 / n)
    multi = simulate(Crossing(beam, moving_force(1e5), tire=tire, speed=20.0, approach=APPROACH,
                              free_vibration=0.1, dt=DT))
    # a point ξ_p ahead of the wheel is a point force whose front starts at −(approach − ξ_p)
    singles = [simulate(Crossing(beam, moving_force(1e5), tire=PointTire(), speed=20.0, approach=APPROACH - xi,
                                 free_vibration=0.1, dt=DT)) for xi in offsets]
    n_t = min([multi.time.size] + [s.time.size for s in singles])  # durations differ by ≤ a/v
    for s in singles:
        assert np.array_equal(s.time[:n_t], multi.time[:n_t])
    for field in ("xi", "xi_dot", "xi_ddot"):
        avg = sum(getattr(s, field)[:n_t] for s in singles) / n
        got = getattr(multi, field)[:n_t]
        # Same arithmetic up to summation order and rounding of x_p: round-off; measured ≤ 2e-15
        # relative, 1e-13 leaves room for fastmath reassociation over ~5000 steps.
        assert np.abs(got - avg).max() <= 1e-13 * np.abs(avg).max()
    # the points really are spread (otherwise the test would be trivial)
    assert np.ptp(offsets) == pytest.approx(tire.contact_length if layout_rule == "ends" else tire.contact_length * (n - 1) / n)


def test_one_point_multipoint_is_point_tire_bit_for_bit():
    beam = paper_beam(16.76, "II", n_modes=10)
    road = random_profile(RoadPSD.iso("C"), seed=3)
    runs = [simulate(Crossing(beam, hs20_44(), tire=tire, road=road, speed=20.0, approach=10.0))
            for tire in (PointTire(), MultiPointTire(n_points=1))]
    for field in ("time", "xi", "xi_dot", "xi_ddot", "q", "q_dot", "q_ddot", "wheel_forces", "contact_lengths"):
        assert np.array_equal(getattr(runs[0], field), getattr(runs[1], field)), field
    assert runs[0].dt == runs[1].dt
