"""Numbers of docs/driveby.md, "How accurate is this": the labels, reliability flags and
multi-pass estimates of the cases issue 32 found wrong with no warning, and of the examples.

    python docs/scripts/driveby_accuracy.py     # writes docs/figures/driveby-accuracy.json
"""
from __future__ import annotations

import datetime
import json
import math
import tempfile
from pathlib import Path

import numpy as np

from vbikit._toml import read_toml
from vbikit.driveby.spec import DriveByError, parse_driveby
from vbikit.driveby.study import run_driveby

ROOT = Path(__file__).resolve().parents[2]
FIG = ROOT / "docs" / "figures"
EXAMPLES = ROOT / "examples" / "driveby"


def run(data: dict) -> "xarray.Dataset":  # noqa: F821
    with tempfile.TemporaryDirectory() as tmp:
        return run_driveby(parse_driveby(data, EXAMPLES), tmp, figures=False).load()


def cases(ds) -> list[dict]:
    """Per case: speed, road, seed, severity, identified [Hz], error [%], label, SNR [dB], reliable, reason."""
    return [{"speed": float(ds["speed"][i]), "road": str(ds["road_class"].values[i]), "seed": int(ds["road_seed"][i]),
             "severity": float(ds["damage_severity"][i]), "identified_hz": round(float(ds["identified_frequency_hz"][i]), 4),
             "error_pct": round(100 * float(ds["frequency_error"][i]), 2), "resolution_pct":
             round(100 * float(ds["resolution_hz"][i] / ds["bridge_frequency_hz"][i]), 2),
             "label": str(ds["identified_frequency_label"].values[i]), "snr_db": round(float(ds["peak_snr_db"][i]), 1),
             "reliable": bool(ds["identified_frequency_reliable"][i]), "reason": str(ds["identified_frequency_reason"].values[i])}
            for i in range(ds.sizes["case"])]


def multipass(ds, i: int = 0) -> dict:
    return {"median_hz": round(float(ds["multipass_frequency_hz"][i]), 4),
            "q25_hz": round(float(ds["multipass_q25_hz"][i]), 4), "q75_hz": round(float(ds["multipass_q75_hz"][i]), 4),
            "error_pct": round(100 * (float(ds["multipass_frequency_hz"][i] / ds["bridge_frequency_hz"][i]) - 1), 2),
            "n_passes": int(ds["multipass_n_passes"][i]), "n_reliable": int(ds["multipass_n_reliable"][i]),
            "n_agree": int(ds["multipass_n_agree"][i])}


#: roughness cancellation on a class A road: speeds [m/s] and road seeds of the sweep
SWEEP_SPEEDS, SWEEP_SEEDS = [5.0, 8.0, 10.0, 12.0, 15.0], [1, 2, 3, 4, 5]


def by_speed(ds) -> list[dict]:
    """Per speed: passes, reliable passes, the largest error of a reliable pass [%] and in units of
    its resolution 1/T, and the largest error of all passes [%]."""
    rows = []
    for v in SWEEP_SPEEDS:
        sel = ds["speed"].values == v
        ok = sel & ds["identified_frequency_reliable"].values.astype(bool)
        err = 100 * ds["frequency_error"].values
        res = 100 * ds["resolution_hz"].values / ds["bridge_frequency_hz"].values
        rows.append({"speed": v, "passes": int(sel.sum()), "reliable": int(ok.sum()),
                     "max_reliable_error_pct": round(float(np.max(np.abs(err[ok]))), 2) if ok.any() else None,
                     "max_reliable_error_per_resolution": round(float(np.max(np.abs(err[ok]) / res[ok])), 2) if ok.any() else None,
                     "max_error_pct": round(float(np.max(np.abs(err[sel]))), 2), "resolution_pct": round(float(res[sel][0]), 2)})
    return rows


def main() -> dict:
    example = read_toml(EXAMPLES / "DRIVEBY.toml", DriveByError)
    rough = read_toml(EXAMPLES / "ROUGH.toml", DriveByError)
    # (a) a 40 m span at 3.0 Hz (EI from the closed form) crossed at 8 m/s by the 3.2 Hz cart
    span, f_b, m = 40.0, 3.0, 4800.0
    near = json.loads(json.dumps(example))
    near["bridge"].update(spans=[span], EI=(2 * math.pi * f_b / (math.pi / span) ** 2) ** 2 * m)
    near["sweep"] = {"speed": [8.0]}
    near["identification"].pop("band")
    # the example (b, d: class A, one cart) and roughness cancellation at 8 and 15 m/s (c)
    ex = run(example)
    fast = json.loads(json.dumps(rough))
    fast["sweep"].update(speed=[15.0], road_class=["A"])
    r8, r15 = run(rough), run(fast)
    sweep = json.loads(json.dumps(rough))
    sweep["sweep"] = {"speed": SWEEP_SPEEDS, "road_class": ["A"], "road_seed": SWEEP_SEEDS}
    rs = run(sweep)
    car = json.loads(json.dumps(example))  # method "sensor": a two-axle car with three accelerometers
    car["vehicle"] = {"model": "two-axle-car"}
    car["sensors"] = [{"name": "front", "body": "body", "position": 0.0, "quantity": "acceleration"},
                      {"name": "rear", "body": "body", "position": 2.6, "quantity": "acceleration"},
                      {"name": "axle1", "body": "axle1", "quantity": "acceleration"}]
    car["identification"] = {"method": "sensor", "band": [1.0, 20.0]}
    car["sweep"] = {"speed": [5.0, 8.0, 10.0], "road_class": ["none", "A"]}
    rc = run(car)
    damaged = int(np.flatnonzero(ex["damage_severity"].values > 0)[0])
    numbers = {
        "measured": datetime.date.today().isoformat(),
        "near_vehicle": cases(run(near))[0],
        "example": cases(ex),
        "example_multipass_healthy": multipass(ex, 0),
        "example_multipass_damaged": multipass(ex, damaged),
        "example_multipass_shift_pct": round(100 * float(ex["multipass_frequency_shift"][damaged]), 2),
        "example_true_shift_pct": round(100 * float(ex["bridge_frequency_shift"][damaged]), 2),
        "rough_8": cases(r8), "rough_8_multipass": multipass(r8),
        "rough_15": cases(r15), "rough_15_multipass": multipass(r15),
        "rough_sweep": by_speed(rs), "rough_sweep_multipass": multipass(rs),
        "car": [c | {"sensors_identified": int(rc["sensors_identified"][i]), "sensors_agree": int(rc["sensors_agree"][i])}
                for i, c in enumerate(cases(rc))],
    }
    (FIG / "driveby-accuracy.json").write_text(json.dumps(numbers, indent=1, ensure_ascii=False) + "\n")
    return numbers


if __name__ == "__main__":
    print(json.dumps(main(), indent=1, ensure_ascii=False))
