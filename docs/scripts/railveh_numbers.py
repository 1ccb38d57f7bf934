"""Recompute the numbers the rail-vehicle section of the docs quotes; store them in
docs/figures/railveh-numbers.json and draw docs/figures/railveh-track-spectra.png.

    python docs/scripts/railveh_numbers.py            # a few seconds

* ``presets``: each rail-car preset's static axle load, linearised Hertz stiffness per wheelset and
  natural frequencies on rigid track (vbikit.vehicle.rail_car).
* ``track``: each registered track spectrum's band and standard deviation over it (closed form).
* ``stiff_contact``: the ICE3 coach over a 20 m simply supported span (6 modes, 2 % damping) at
  80 m/s on a German low-disturbance track (seed 1): the exact integrator's automatic step, the
  number of steps, the peak wheel–rail force and the deck response for rigid, Hertz and stiffer
  contacts (run times are measured, dated); ``entry_x_m``: where the peak wheel force occurs on a
  smooth track (the wheel's entry onto the deflected span).
* ``train``: eight ICE3 coaches (24.775 m apart, a substitute coach length) over the same span at
  80 m/s, smooth track, with 3 and 6 modes: peak midspan acceleration and deflection with Hertz and
  rigid contact and as moving forces (the coaches' static axle loads).
tests/rail_vehicles/test_railveh_numbers.py recomputes the fast parts and checks the JSON.
"""
from __future__ import annotations

import dataclasses
import datetime
import json
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[2]
NUMBERS = ROOT / "docs" / "figures" / "railveh-numbers.json"
FIGURE = ROOT / "docs" / "figures" / "railveh-track-spectra.png"
STIFF_CONTACTS = ("rigid", "hertz", 1e10, 1e11, 1e12)


def presets() -> dict:
    from vbikit.vehicle import RAIL_CAR_PRESETS, rail_car

    out = {}
    for name, p in RAIL_CAR_PRESETS.items():
        car = rail_car(p)
        f = car.natural_frequencies()
        out[name] = {"axle_load_kN": round(float(p.static_axle_loads()[0]) / 1e3, 2),
                     "hertz_per_wheelset_GN_per_m": round(float(p.contact_stiffness()[0]) / 1e9, 3),
                     "frequencies_Hz": [round(float(x), 2) for x in f],
                     "length_axles_m": round(p.axle_offsets[-1], 3)}
    return out


def track() -> dict:
    from vbikit.road import TRACK_PSDS

    return {name: {"wavelengths_m": [round(1 / p.n_max, 3), round(1 / p.n_min, 1)],
                   "sigma_mm": round(float(np.sqrt(p.band_variance())) * 1e3, 3)}
            for name, p in TRACK_PSDS.items()}


def stiff_contact() -> dict:
    from vbikit.bridge import EulerBernoulliBeam
    from vbikit.road import track_profile
    from vbikit.solve import Crossing, simulate
    from vbikit.vehicle import RAIL_CAR_PRESETS, rail_car

    bridge = EulerBernoulliBeam(20.0, 2.0e10, 15000.0, 0.02, n_modes=6)
    road = track_profile("german-low", 1, spacing=0.02, length=1000.0)
    out = {}
    for contact in STIFF_CONTACTS:
        car = rail_car(dataclasses.replace(RAIL_CAR_PRESETS["ice3-coach"], contact=contact))
        crossing = Crossing(bridge, car, road=road, speed=80.0, approach=5.0)
        simulate(crossing)  # compile / warm
        t0 = time.perf_counter()
        res = simulate(crossing)
        elapsed = time.perf_counter() - t0
        out[str(contact)] = {"highest_vehicle_Hz": round(float(car.natural_frequencies().max()), 1),
                             "dt_us": round(res.integration_dt * 1e6, 2), "steps": int(res.n_steps),
                             "run_s": round(elapsed, 3),
                             "max_wheel_force_kN": round(float(res.wheel_forces.max()) / 1e3, 1),
                             "min_wheel_force_kN": round(float(res.wheel_forces.min()) / 1e3, 1),
                             "midspan_deflection_mm": round(float(np.abs(res.displacement(10.0)).max()) * 1e3, 3),
                             "midspan_acceleration_m_s2": round(float(np.abs(res.acceleration(10.0)).max()), 3)}
        smooth = simulate(Crossing(bridge, car, speed=80.0, approach=5.0))
        i, j = np.unravel_index(np.argmax(smooth.wheel_forces), smooth.wheel_forces.shape)
        out[str(contact)]["entry_x_m"] = round(float(smooth.wheel_positions()[i, j]), 3)
        out[str(contact)]["smooth_max_wheel_force_kN"] = round(float(smooth.wheel_forces.max()) / 1e3, 1)
    return out


def train() -> dict:
    from vbikit.bridge import EulerBernoulliBeam
    from vbikit.solve import Crossing, VehicleMotion, simulate
    from vbikit.vehicle import RAIL_CAR_PRESETS, moving_force, rail_car

    coach, speed, pitch = RAIL_CAR_PRESETS["ice3-coach"], 80.0, 24.775
    out = {}
    for n_modes in (3, 6):
        bridge = EulerBernoulliBeam(20.0, 2.0e10, 15000.0, 0.02, n_modes=n_modes)
        row = {"highest_mode_Hz": round(float(bridge.frequencies_hz.max()), 1)}
        for contact in ("hertz", "rigid", "moving-force"):
            if contact == "moving-force":
                loads = coach.static_axle_loads()
                motions = tuple(VehicleMotion(moving_force(float(loads[k])), speed=speed, entry_time=(i * pitch + s) / speed)
                                for i in range(8) for k, s in enumerate(coach.axle_offsets))
            else:
                car = rail_car(dataclasses.replace(coach, contact=contact))
                motions = tuple(VehicleMotion(car, speed=speed, entry_time=i * pitch / speed) for i in range(8))
            res = simulate(Crossing(bridge, vehicles=motions, approach=5.0))
            row[contact] = {"midspan_acceleration_m_s2": round(float(np.abs(res.acceleration(10.0)).max()), 3),
                            "midspan_deflection_mm": round(float(np.abs(res.displacement(10.0)).max()) * 1e3, 3)}
        out[f"{n_modes}_modes"] = row
    return out


def figure(path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from vbikit.road import TRACK_PSDS, track_profile

    fig, (ax, bx) = plt.subplots(1, 2, figsize=(10, 3.8))
    for name, p in TRACK_PSDS.items():
        n = np.geomspace(p.n_min, p.n_max, 200)
        ax.loglog(1 / n, p(n), label=name, ls="-" if name.startswith("german") else "--")
    ax.set_xlabel("wavelength [m]")
    ax.set_ylabel("G(n) [m³/cycle]")
    ax.legend(fontsize=7, ncol=2)
    for name in ("german-low", "german-high"):
        prof = track_profile(name, 1)
        keep = (prof.x > 0) & (prof.x < 100)
        bx.plot(prof.x[keep], prof.z[keep] * 1e3, lw=0.8, label=f"{name}, seed 1")
    bx.set_xlabel("x [m]")
    bx.set_ylabel("vertical irregularity [mm]")
    bx.legend(fontsize=7)
    fig.tight_layout()
    from vbikit._files import save_figure

    save_figure(fig, path, dpi=120)


def main() -> None:
    from vbikit._files import write_text

    numbers = {"measured": datetime.date.today().isoformat(), "presets": presets(), "track": track(),
               "stiff_contact": stiff_contact(), "train": train()}
    write_text(NUMBERS, json.dumps(numbers, indent=1) + "\n")
    figure(FIGURE)
    print(f"wrote {NUMBERS.relative_to(ROOT)} and {FIGURE.relative_to(ROOT)}")


if __name__ == "__main__":
    main()
