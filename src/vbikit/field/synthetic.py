"""A synthetic field test with known truth (for testing the workflow and as a worked example).

``write_synthetic_case`` simulates the field-test crossings (dump truck at 64.4 km/h on
``cypress-bayou`` with a 38.1 mm wood bump at the span entry on an ISO class A profile) with a
*true* bridge (stiffness factor and damping ratio chosen by the caller), then writes what a
data-acquisition system would record: the responses at the record's own sampling rate, on its
own clock (trigger at ``trigger_time``), with white noise, and an accelerometer offset and
linear drift.  It writes ``FIELD.toml`` describing the test with the *nominal* model
(stiffness factor 1, damping 2 %) and returns the truth.
"""
from __future__ import annotations

import logging
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from scipy.interpolate import CubicSpline

from vbikit.bridge.presets import cypress_bayou
from vbikit.contact.tires import MultiPointTire
from vbikit.road.defects import Defect, with_defects
from vbikit.road.psd import RoadPSD, random_profile
from vbikit.solve import Crossing, simulate

log = logging.getLogger(__name__)

#: [paper] truck speed of the field test, 40 mph [km/h]
FIELD_SPEED_KMH = 64.4
#: [substitute] two spans of approach (spans 1–2 of the bridge, model data §4c) [m]
APPROACH = 2 * 16.76


@dataclass(frozen=True)
class SyntheticTruth:
    """What the synthetic records were made from (SI units)."""

    stiffness_factor: float
    damping_ratio: float
    trigger_time: dict[str, float]
    acc_offset: float
    acc_drift: float
    t_ref: dict[str, float]
    noise: dict[str, float]
    sampling_rate: float


CASES = {"case1": (2.0, 5), "case2": (-2.0, 3)}  # [substitute] lateral offset [m], most loaded girder (model data §4c)


def write_synthetic_case(out_dir: str | Path, stiffness_factor: float = 1.10, damping_ratio: float = 0.025,
                         sampling_rate: float = 200.0, seed: int = 7, free_vibration: float = 8.0,
                         acc_offset: float = 0.03, acc_drift: float = 0.004,
                         noise: dict[str, float] | None = None, cases: tuple[str, ...] = ("case1", "case2")) -> SyntheticTruth:
    """Write profiles, response CSVs and FIELD.toml into ``out_dir``; return the truth.

    ``acc_offset`` [m/s²] and ``acc_drift`` [m/s³] are added to every accelerometer as
    offset + drift · (t_sim − t_entry) (t_entry: front axle at the span entry); ``noise`` is the
    standard deviation of Gaussian white noise per quantity (SI), default 10 µm, 0.01 m/s², 0.5 µε.
    """
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    noise = noise or {"displacement": 1e-5, "acceleration": 0.01, "strain": 0.5e-6}
    rng = np.random.default_rng(seed)
    speed = FIELD_SPEED_KMH / 3.6
    x0, x1 = -APPROACH - 12.0, 16.76 + speed * (free_vibration + 1.0) + 12.0
    base = RoadPSD.iso("A")
    profiles = {}
    for side, s in (("left", seed), ("right", seed + 1)):
        p = random_profile(base, s, spacing=0.1, length=x1 - x0 + 1.0, x_start=x0)
        p = with_defects(p, [Defect.of_kind("bump", start=-0.184)])  # 38.1 mm wood bump ending at the span entry
        keep = (p.x >= x0) & (p.x <= x1)
        path = out / f"profile_{side}.csv"
        with path.open("w") as fh:
            fh.write(f"# synthetic measured profile (ISO class A, seed {s}) + 38.1 mm wood bump; x from the span entry\n")
            fh.write("x [m],elevation [m]\n")
            for x, z in zip(p.x[keep], p.z[keep]):
                fh.write(f"{x:.4f},{z:.6f}\n")
        profiles[side] = path
    from vbikit.road.measured import read_profile_csv
    from vbikit.vehicle.presets import dump_truck

    left, right = read_profile_csv(profiles["left"]), read_profile_csv(profiles["right"])
    bridge = cypress_bayou(damping_ratio=damping_ratio, E_girder=36e9 * stiffness_factor, E_deck=33e9 * stiffness_factor)
    triggers, t_refs = {}, {}
    toml = [
        "# Synthetic field test written by vbikit.field.synthetic (examples/field/make_synthetic.py).",
        f"# Truth: stiffness factor {stiffness_factor:.4g}, damping ratio {damping_ratio:.4g}; this file describes the NOMINAL model.",
        'name = "synthetic Cypress Bayou test"', "",
        "[bridge]", 'model = "cypress-bayou"', "n_modes = 10", "damping_ratio = 0.02", "stiffness_factor = 1.0", "",
        "[vehicle]", 'model = "dump-truck"', "",
        "[crossing]", f"speed_kmh = {FIELD_SPEED_KMH}", f"approach = {APPROACH}", f"free_vibration = {free_vibration}", "",
        "[signal]", "lowpass_hz = 40.0", 'drift = "quiet"', "quiet_tail = 1.0",
        "bands_hz = [[0.0, 5.0], [5.0, 15.0], [15.0, 30.0], [30.0, 40.0]]", "",
    ]
    for k, name in enumerate(cases):
        lateral, girder = CASES[name]
        res = simulate(Crossing(bridge, dump_truck(), MultiPointTire(), left, speed=speed, approach=APPROACH,
                                free_vibration=free_vibration, lateral_offset=lateral, road_right=right))
        t_entry = APPROACH / speed
        trigger = 1.237 + 0.311 * k  # s on the recorder's clock (not on a sample instant)
        t0_rec = 0.0  # recorder starts at its own t = 0, i.e. t_sim = t_entry - trigger
        shift = t_entry - trigger
        t_rec = np.arange(t0_rec, res.time[-1] - shift - 1e-9, 1.0 / sampling_rate)
        t_rec = t_rec[t_rec + shift >= 0.0]
        t_sim = t_rec + shift
        y = float(bridge.girder_y[girder - 1])
        xm = 16.76 / 2
        cols = {
            f"G{girder}_disp [mm]": (CubicSpline(res.time, res.displacement(xm, y))(t_sim)
                                     + rng.normal(0, noise["displacement"], t_sim.size)) * 1e3,
            f"G{girder}_acc [m/s^2]": CubicSpline(res.time, res.acceleration(xm, y))(t_sim)
            + acc_offset + acc_drift * (t_sim - t_entry) + rng.normal(0, noise["acceleration"], t_sim.size),
            f"G{girder}_strain [microstrain]": (CubicSpline(res.time, res.strain(xm, y))(t_sim)
                                                + rng.normal(0, noise["strain"], t_sim.size)) * 1e6,
        }
        path = out / f"{name}_responses.csv"
        with path.open("w") as fh:
            fh.write(f"# synthetic record, {name}: dump truck at {FIELD_SPEED_KMH} km/h, lateral offset {lateral} m\n")
            fh.write("time [s]," + ",".join(cols) + "\n")
            data = np.column_stack([t_rec] + list(cols.values()))
            for row in data:
                fh.write(f"{row[0]:.5f},{row[1]:.5f},{row[2]:.5f},{row[3]:.3f}\n")
        triggers[name], t_refs[name] = trigger, t_entry
        toml += [
            "[[case]]", f'name = "{name}"', f'responses = "{path.name}"', f"lateral_offset = {lateral}",
            f"sampling_rate = {sampling_rate}", f"trigger_time = {trigger}", 'align = "trigger"',
            'profile_left = "profile_left.csv"', 'profile_right = "profile_right.csv"', "",
        ]
        for q, unit, col in (("displacement", "mm", "disp"), ("acceleration", "m/s^2", "acc"), ("strain", "microstrain", "strain")):
            toml += ["[[case.channel]]", f'name = "G{girder}_{col}"', f'quantity = "{q}"', f"girder = {girder}",
                     f"x = {xm}", f'unit = "{unit}"', ""]
    (out / "FIELD.toml").write_text("\n".join(toml))
    log.info("synthetic field test written to %s", out)
    return SyntheticTruth(stiffness_factor, damping_ratio, triggers, acc_offset, acc_drift, t_refs, noise, sampling_rate)
