"""``kernels.contact.road_cells``: the road cells of the secant rate's two readings and of the point
itself, found through one ``road_cell`` call site.  Expected cells and in-cell fractions worked out by
hand on the stations 0, 1, 2, 4 m (cell i holds stations[i] ≤ x < stations[i + 1]; the last cell's
line extended beyond the road's end)."""
from __future__ import annotations

import numpy as np
import pytest

from vbikit.solve.kernels.contact import road_cells

STATIONS = np.array([0.0, 1.0, 2.0, 4.0])


def _cells(x: float, a: float, vx: float = 10.0, start: int = -1):
    """``road_cells`` with the secant's ends x ∓ a (``secant_ends`` with a positive span)."""
    idx = np.array([start], np.int64)
    return road_cells(STATIONS, x - a, x + a, x, vx, idx, 0), int(idx[0])


def test_secant_readings_and_the_point_cell():
    """x = 1.5, a = 0.75: x − a = 0.75 in cell 0 at t = 0.75; x + a = 2.25 in cell 2 at
    t = (2.25 − 2) / 2 = 0.125; x in cell 1, where the pointer is left."""
    (ia, ta, ib, tb, i), pointer = _cells(1.5, 0.75)
    assert (ia, ib, i, pointer) == (0, 2, 1, 1)
    assert ta == 0.75 and tb == 0.125


def test_beyond_the_road_end_the_last_cell_is_extended():
    """x = 3.5, a = 1.0: x + a = 4.5 lies past the last station, so cell 2 with
    t = (4.5 − 2) / 2 = 1.25; x − a = 2.5 in cell 2 at t = 0.25; x in cell 2."""
    (ia, ta, ib, tb, i), pointer = _cells(3.5, 1.0)
    assert (ia, ib, i, pointer) == (2, 2, 2, 2)
    assert ta == pytest.approx(0.25, abs=1e-15) and tb == pytest.approx(1.25, abs=1e-15)


@pytest.mark.parametrize("start", [-1, 0, 2])
def test_without_a_span_only_the_point_cell(start):
    """a = 0 (the cell's slope, no secant): only the cell of x = 1.5 (1), the secant outputs 0,
    from any station pointer."""
    (ia, ta, ib, tb, i), pointer = _cells(1.5, 0.0, start=start)
    assert (ia, ta, ib, tb, i, pointer) == (0, 0.0, 0, 0.0, 1, 1)


def test_on_a_station_driving_minus_x_the_cell_behind():
    """x = 2 exactly (a station), a = 0: driving +x the cell ahead (2), driving −x the one behind (1)."""
    assert _cells(2.0, 0.0, vx=10.0)[0][4] == 2
    assert _cells(2.0, 0.0, vx=-10.0)[0][4] == 1
