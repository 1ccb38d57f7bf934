"""The static reference ξ_st(t) a bridge keeps (``vbikit.analysis.impact.static_modal_history``)
against ``vbikit.solve.system.static_modal_history`` computed afresh for each crossing: two
crossings on one deck that differ only in the vehicle's lateral offset (same travel, loads and
number of wheel tracks, so only the wheel lines tell them apart) must not share an entry, and a
result whose kernel data a caller wrote to must not leave a wrong entry for a fresh crossing."""
from __future__ import annotations

import numpy as np

from vbikit.analysis.impact import static_modal_history
from vbikit.bridge import paper_deck
from vbikit.solve import Crossing, VehicleMotion, simulate, system
from vbikit.vehicle import hs20_44


def _crossing(deck, offset):
    return Crossing(deck, vehicles=(VehicleMotion(hs20_44(), 20.0, lateral_offset=offset),), approach=1.0,
                    free_vibration=0.0, dt=4e-3)


def test_kept_static_reference_tells_wheel_lines_apart_and_ignores_written_data():
    deck = paper_deck(2, n_modes=4, use_cache=False, n_elements=14)
    near, far = simulate(_crossing(deck, -1.5)), simulate(_crossing(deck, 1.5))
    xi_near, xi_far = static_modal_history(near), static_modal_history(far)
    fresh_near = system.static_modal_history(near.crossing, near.travel)
    fresh_far = system.static_modal_history(far.crossing, far.travel)
    assert not np.allclose(fresh_near, fresh_far)  # the two lines load the modes differently
    assert np.array_equal(xi_near, fresh_near) and np.array_equal(xi_far, fresh_far)
    other = simulate(_crossing(deck, 0.7))
    other.kernel_data.points.origin[:] += 3.0  # a caller writes to shared data (documented: must not)
    static_modal_history(other)
    again = simulate(_crossing(deck, 0.7))  # a fresh crossing with the same inputs
    assert np.array_equal(static_modal_history(again), system.static_modal_history(again.crossing, again.travel))


def test_a_vehicle_built_from_array_parameters_is_not_kept_under_a_rounded_key():
    """``scenario.build.build_vehicle`` keeps a vehicle per exact parameters: TOML values (lists,
    numbers) are kept and shared, while numpy arrays (whose text form rounds to 8 digits) are not."""
    from vbikit.scenario.build import build_vehicle

    listed = dict(axle_loads=[1e5, 1.2e5], axle_spacings=[4.0])
    assert build_vehicle("axles", listed) is build_vehicle("axles", dict(listed))
    a = build_vehicle("axles", dict(axle_loads=np.array([1e5, 1.2e5]), axle_spacings=np.array([4.0])))
    b = build_vehicle("axles", dict(axle_loads=np.array([1e5, 1.2e5]), axle_spacings=np.array([4.0 + 1e-9])))
    assert a is not b
