# Traffic streams on a slab-on-girder deck, where a vehicle's lateral position matters.
#
# * A one-record stream in lane n equals `vbikit.run` of the same truck as a [[vehicles]] entry at
#   the lane's centre y (docs/traffic.md: lane n at lanes[n − 1]; the default lanes at ∓ width/4,
#   lane 1 at y < 0).  The truck is built in the test from its documented record columns.
# * Mirror symmetry of the deck (five girders, symmetric section): a truck in lane 1 read at
#   girder 4 gives the same response as the mirrored truck in lane 2 read at girder 2 — a check
#   that holds by geometry alone, and fails if a lane's side or a girder index is wrong.
# * Per-vehicle outputs of a multi-vehicle event against the event simulated here from its
#   records (vehicles in entry order, entry times relative to the first entry, each truck's own
#   wheels: two per axle).
from __future__ import annotations

import tomllib

import numpy as np
import pytest

import vbikit
from vbikit.solve import Crossing, VehicleMotion, simulate
from vbikit.traffic import VehicleRecord
from vbikit.traffic.study import traffic_study
from vbikit.vehicle import axle_truck

WIDTH = 9.75  # paper Bridge 1 deck width [m]
BASE_TOML = ('[bridge]\nmodel = "paper-bridge-1"\nn_modes = 6\n[road]\nclass = "none"\n'
             "[crossing]\napproach = 2.0\nfree_vibration = 0.05\n")
LOADS, SPACINGS = (40e3, 120e3, 110e3), (4.2, 1.3)


def _base(girder):
    text = BASE_TOML
    if girder is not None:
        text += f"[response]\ngirder = {girder}\n"
    return tomllib.loads(text)


def _record(i, time, lane, direction="+x", speed=22.0, loads=LOADS, spacings=SPACINGS, lateral=None):
    return VehicleRecord(time=time, lane=lane if lateral is None else None, lateral_offset=lateral, direction=direction,
                         speed=speed, axle_loads=tuple(loads), axle_spacings=tuple(spacings), id=f"v{i}", line=i + 2)


def _event_row(records, girder=None, lanes=None):
    job = traffic_study(records, _base(girder), lanes=lanes)
    out = job.run_batch(tuple(range(job.size)))
    return job, out


def _run_single(y, girder=None, direction="+x"):
    text = BASE_TOML + (f"[response]\ngirder = {girder}\n" if girder is not None else "")
    text += (f'[[vehicles]]\nmodel = "axles"\naxle_loads = {list(LOADS)}\naxle_spacings = {list(SPACINGS)}\n'
             f'direction = "{direction}"\nspeed = 22.0\nlateral_offset = {y!r}\n')
    return vbikit.run(text).summary


@pytest.mark.parametrize("lane, direction", [(1, "+x"), (2, "-x")])
def test_one_record_equals_run_at_the_lane_offset(lane, direction):
    job, out = _event_row([_record(0, 3.0, lane, direction)])
    y = (-WIDTH / 4, WIDTH / 4)[lane - 1]
    assert job.lanes == pytest.approx((-WIDTH / 4, WIDTH / 4), rel=1e-12)
    s = _run_single(y, direction=direction)
    for key in ("impact_factor", "max_dynamic_displacement", "max_static_displacement"):
        assert float(np.ravel(out[key])[0]) == pytest.approx(s[key], rel=1e-12), key
    # and not the other lane: the deck tells the two apart (girder 4 of 5 is read)
    other = _run_single(-y, direction=direction)
    assert abs(other["max_static_displacement"] - s["max_static_displacement"]) > 0.05 * abs(s["max_static_displacement"])


def test_mirror_symmetry_of_lanes_and_girders():
    _, a = _event_row([_record(0, 0.0, 1)], girder=4)
    _, b = _event_row([_record(0, 0.0, 2)], girder=2)
    for key in ("max_static_displacement", "max_dynamic_displacement", "impact_factor"):
        # the grillage is symmetric to round-off: measured ≤ 1e-9 relative
        assert float(np.ravel(a[key])[0]) == pytest.approx(float(np.ravel(b[key])[0]), rel=1e-7), key


def test_per_vehicle_outputs_of_a_multi_vehicle_event():
    # each vehicle's lightest wheel is lighter than the next vehicle's first wheel is heavy, and the other way
    # round, so a wheel counted with the wrong vehicle changes that vehicle's minimum
    recs = [_record(0, 10.0, 1, speed=20.0, loads=(60e3, 90e3), spacings=(4.5,)),
            _record(1, 10.3, 2, "-x", speed=25.0, loads=(30e3, 110e3, 110e3)),
            _record(2, 10.6, 1, speed=18.0, loads=(50e3, 130e3, 130e3, 120e3, 120e3), spacings=(3.8, 1.3, 8.5, 1.3))]
    job, out = _event_row(recs)
    assert job.events == ((0, 1, 2),)
    # the event simulated here: each truck from its record, lanes at ∓ width/4, entry times from the first entry
    base = job.context().template.crossing
    motions = tuple(VehicleMotion(axle_truck(r.axle_loads, r.axle_spacings), speed=r.speed, direction=r.direction,
                                  entry_time=r.time - 10.0, lateral_offset=(-WIDTH / 4, WIDTH / 4)[r.lane - 1])
                    for r in recs)
    res = simulate(Crossing(base.bridge, vehicles=motions, tire=base.tire, speed=25.0, approach=base.approach,
                            free_vibration=base.free_vibration, dt=base.dt, integrator=base.integrator))
    f = res.wheel_forces
    start = 0
    for j, r in enumerate(recs):
        n_w = 2 * len(r.axle_loads)
        mine = f[:, start:start + n_w]
        start += n_w
        assert out["vehicle_min_wheel_force"][j] == pytest.approx(mine.min(), rel=1e-12)
        assert out["vehicle_contact_loss"][j] == float(np.any(mine <= 0.0))
    assert start == f.shape[1]
    # the vehicles' minimum wheel forces differ (light two-axle truck vs five-axle): an index slip shows
    assert len({round(float(v), 3) for v in out["vehicle_min_wheel_force"]}) == 3
    # the event's peak deflection against the re-simulated one at the default point (girder 4, midspan)
    # (the summary refines the peak between samples with the Hermite cubic of w and ẇ: measured +8e-6)
    peak = float(np.abs(res.displacement()).max())
    assert abs(float(np.ravel(out["max_dynamic_displacement"])[0])) == pytest.approx(peak, rel=5e-5)
    # on the event's clock: t = 0 when its first vehicle enters (record time 10.0 s)
    t_peak = float(res.time[np.argmax(np.abs(res.displacement()))])
    assert float(np.ravel(out["time_of_max_dynamic_displacement"])[0]) == pytest.approx(t_peak, abs=2 * res.dt)
