"""Numbers of docs/driveby.md, "Where a pass starts": what starting the instrumented vehicle settled
(``crossing.run_in``) instead of at rest changes in a drive-by sweep on rough roads.

    python docs/scripts/driveby_start_numbers.py    # writes docs/figures/driveby-start-numbers.json (about a minute)

A pass starts its vehicle at rest in static equilibrium ``crossing.approach`` (5 m here) before the span,
as the paper's crossings do; a real instrumented vehicle arrives having driven the road before it.  The
example's bridge (25 m, 5.62 Hz) is crossed at 5 and 8 m/s on ISO class A and B roads (six seeds each)
by two damped vehicles: the test cart with 10 % damping (3.2 Hz; method "contact") and the two-axle car
(method "sensor", three accelerometers); and, where single passes are reliable, the roughness cancellation
of examples/driveby/ROUGH.toml (the damped cart and an identical one 4 m behind, method "residual") at 5, 8
and 10 m/s on class A (six seeds).  Each sweep runs once at rest (``run_in = 0``) and once settled by a 95 m run-in
(100 m driven in all, ``vbikit.solve.run_in.SETTLED_APPROACH``).  Reported per vehicle: the passes, those
whose identified frequency moved and by how much at most (Hz, and in units of the pass's resolution
1/T), those whose reliability flag changed, and how much the sensor records differ while the vehicle is
on the deck (root mean square of the difference over that of the settled record, median and largest
over the passes and sensors).
"""
from __future__ import annotations

import datetime
import json
import tempfile
from pathlib import Path

import numpy as np

from vbikit._toml import read_toml
from vbikit.driveby.spec import DriveByError, parse_driveby
from vbikit.driveby.study import run_driveby

ROOT = Path(__file__).resolve().parents[2]
FIG = ROOT / "docs" / "figures"
EXAMPLES = ROOT / "examples" / "driveby"
#: the run-in [m] of the settled passes: 100 m driven in all with the 5 m approach
RUN_IN = 95.0
#: the sweep of both vehicles
SWEEP = {"speed": [5.0, 8.0], "road_class": ["A", "B"], "road_seed": [1, 2, 3, 4, 5, 6]}


def _vehicles() -> dict[str, dict]:
    """The two damped vehicles' sweep files (from the example's), by name."""
    example = read_toml(EXAMPLES / "DRIVEBY.toml", DriveByError)
    cart = json.loads(json.dumps(example))
    cart["vehicle"] = {"model": "test-cart", "damping_ratio": 0.1}
    cart["sweep"] = dict(SWEEP)
    car = json.loads(json.dumps(example))
    car["vehicle"] = {"model": "two-axle-car"}
    car["sensors"] = [{"name": "front", "body": "body", "position": 0.0, "quantity": "acceleration"},
                      {"name": "rear", "body": "body", "position": 2.6, "quantity": "acceleration"},
                      {"name": "axle1", "body": "axle1", "quantity": "acceleration"}]
    car["identification"] = {"method": "sensor", "band": [1.0, 20.0]}
    car["sweep"] = dict(SWEEP)
    rough = read_toml(EXAMPLES / "ROUGH.toml", DriveByError)  # roughness cancellation: reliable passes on class A
    pair = json.loads(json.dumps(rough))
    pair["vehicle"] = {"model": "test-cart", "damping_ratio": 0.1}
    pair["sweep"] = {"speed": [5.0, 8.0, 10.0], "road_class": ["A"], "road_seed": [1, 2, 3, 4, 5, 6]}
    return {"damped_cart": cart, "two_axle_car": car, "damped_cart_pair": pair}


def _run(data: dict, run_in: float):
    data = json.loads(json.dumps(data))
    data.setdefault("crossing", {})["run_in"] = run_in
    with tempfile.TemporaryDirectory() as tmp:
        return run_driveby(parse_driveby(data, EXAMPLES), tmp, figures=False).load()


def compare(rest, settled) -> dict:
    """The settled sweep against the one at rest (module docstring)."""
    f0, f1 = rest["identified_frequency_hz"].values, settled["identified_frequency_hz"].values
    moved = np.abs(f1 - f0)
    ok0 = rest["identified_frequency_reliable"].values.astype(bool)
    ok1 = settled["identified_frequency_reliable"].values.astype(bool)
    h0, h1 = rest["sensor_history"].values, settled["sensor_history"].values  # (case, sensor, sample)
    first, last = settled["on_bridge_start_sample"].values, settled["on_bridge_end_sample"].values
    ratios = []
    for i in range(h1.shape[0]):
        for s in range(h1.shape[1]):
            on = slice(int(first[i]), int(last[i]))
            ratios.append(float(_rms(h1[i, s, on] - h0[i, s, on]) / _rms(h1[i, s, on])))
    return {"passes": int(f0.size), "moved": int(np.sum(moved > 1e-9)),
            "largest_move_hz": round(float(moved.max()), 4),
            "largest_move_per_resolution": round(float(np.max(moved / settled["resolution_hz"].values)), 3),
            "reliability_changed": int(np.sum(ok0 != ok1)), "reliable_at_rest": int(ok0.sum()),
            "reliable_settled": int(ok1.sum()),
            "record_difference_median": round(float(np.median(ratios)), 3),
            "record_difference_max": round(float(np.max(ratios)), 3)}


def _rms(x: np.ndarray) -> float:
    return float(np.sqrt(np.mean(np.square(x))))


def main() -> dict:
    numbers: dict = {"measured": datetime.date.today().isoformat(), "run_in_m": RUN_IN, "approach_m": 5.0}
    for name, data in _vehicles().items():
        numbers[name] = compare(_run(data, 0.0), _run(data, RUN_IN))
    (FIG / "driveby-start-numbers.json").write_text(json.dumps(numbers, indent=1) + "\n")
    return numbers


if __name__ == "__main__":
    print(json.dumps(main(), indent=1))
