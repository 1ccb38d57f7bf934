"""Numbers and figures of docs/driveby.md: identification error against speed, road roughness and
sensor noise, the damage indicator against severity, and the example's run time.

    python docs/scripts/driveby_numbers.py      # writes docs/figures/driveby-numbers.json and driveby-*.png
"""
from __future__ import annotations

import datetime
import json
import math
import time
from pathlib import Path

import numpy as np

from vbikit.bridge.continuous import ContinuousBeam
from vbikit.bridge.damage import Damage
from vbikit.driveby import (Sampling, Sensor, SingleAxle, contact_acceleration_from_measured, identify_frequency,
                            measure, on_bridge, sensor_cart)
from vbikit.road.psd import ISO_CLASSES, RoadPSD, random_profile  # noqa: F401
from vbikit.solve import Crossing, simulate

ROOT = Path(__file__).resolve().parents[2]
FIG = ROOT / "docs" / "figures"
SPAN, EI, MASS, RATE = 25.0, 2.4e10, 4800.0, 200.0


def bridge(severity: float = 0.0) -> ContinuousBeam:
    damage = (Damage(11.25, 2.5, severity),) if severity > 0 else ()
    return ContinuousBeam(spans=(SPAN,), EI=EI, mass_per_length=MASS, n_modes=6, damage=damage)


def road(cls: str, seed: int):
    if cls == "none":
        return None
    from vbikit.scenario import build, parse_scenario

    built = build(parse_scenario({"bridge": {"model": "beam", "span": SPAN, "EI": EI, "mass_per_length": MASS},
                                  "vehicle": {"model": "sprung-mass"}, "road": {"class": cls, "seed": seed},
                                  "crossing": {"speed": 5.0, "approach": 5.0}}))
    return built.crossing.road


def identify(b, speed, cls="none", seed=1, noise=0.0):
    cart = sensor_cart()
    result = simulate(Crossing(b, cart, road=road(cls, seed), speed=speed, approach=5.0, dt=1 / (5 * RATE)))
    m = measure(result, [Sensor("acc", body="body", noise_rms=noise)], Sampling(RATE), seed=seed)
    t_on = result.time[on_bridge(result)]
    w = (m.time >= t_on[0]) & (m.time <= t_on[-1])
    a_c = contact_acceleration_from_measured(m.values[0], SingleAxle.of(cart), m.dt)
    return identify_frequency(a_c[w], RATE, speed, SPAN, band=(1.0, 20.0))


def identify_residual(b, speed, cls, seed, gap=4.0):
    """Roughness cancellation: the cart and an identical one ``gap`` behind; residual of their
    back-calculated contact accelerations, the carts' own frequency excluded (± 2 / T)."""
    from vbikit.driveby import residual_response
    from vbikit.solve import VehicleMotion

    cart = sensor_cart()
    crossing = Crossing(b, vehicles=(VehicleMotion(cart, speed), VehicleMotion(cart, speed, entry_time=gap / speed)),
                        road=road(cls, seed), approach=5.0, dt=1 / (5 * RATE))
    result = simulate(crossing)
    m = measure(result, [Sensor("a1", body="body", vehicle=1), Sensor("a2", body="body", vehicle=2)], Sampling(RATE))
    single = SingleAxle.of(cart)
    a = [contact_acceleration_from_measured(m.values[j], single, m.dt) for j in range(2)]
    res = residual_response(a[0], a[1], RATE, gap, speed)
    t_on = result.time[on_bridge(result, 0)]
    w = (m.time >= t_on[0]) & (m.time <= t_on[-1]) & np.isfinite(res)
    return identify_frequency(res[w], RATE, speed, SPAN, band=(1.0, 20.0), vehicle_hz=cart.natural_frequencies(),
                              exclude_vehicle=True)


def signal_level(b, speed=8.0) -> float:
    """rms [m/s²] of the cart's acceleration while on the deck (smooth road): the signal noise competes with."""
    cart = sensor_cart()
    result = simulate(Crossing(b, cart, speed=speed, approach=5.0, dt=1 / (5 * RATE)))
    m = measure(result, [Sensor("acc", body="body")], Sampling(RATE))
    t_on = result.time[on_bridge(result)]
    w = (m.time >= t_on[0]) & (m.time <= t_on[-1])
    return float(np.sqrt(np.mean(m.values[0][w] ** 2)))


def main() -> dict:
    healthy = bridge()
    f1 = float(healthy.frequencies_hz[0])
    speeds = [5.0, 7.5, 10.0, 15.0, 20.0]
    by_speed = [100 * (identify(healthy, v).frequency_hz / f1 - 1) for v in speeds]
    classes = ["none", "A", "B"]
    seeds = [1, 2, 3]
    by_road = {c: [100 * (identify(healthy, 8.0, c, s).frequency_hz / f1 - 1) for s in seeds] for c in classes}
    by_road_residual = {c: [100 * (identify_residual(healthy, 8.0, c, s).frequency_hz / f1 - 1) for s in seeds]
                        for c in classes}
    noises = [0.0, 1e-6, 1e-5, 1e-4, 1e-3]
    by_noise = {str(n): [100 * (identify(healthy, 8.0, "none", s, n).frequency_hz / f1 - 1) for s in seeds] for n in noises}
    severities = [0.1, 0.2, 0.3, 0.4, 0.5]
    damage = []
    for s in severities:
        d = bridge(s)
        for v in (5.0, 10.0):
            ident = identify(d, v)
            f_h = identify(healthy, v).frequency_hz
            damage.append({"severity": s, "speed": v, "identified_shift_pct": 100 * (ident.frequency_hz / f_h - 1),
                           "true_shift_pct": 100 * (float(d.frequencies_hz[0]) / f1 - 1),
                           "resolution_pct": 100 * ident.resolution_hz / f1})
    from vbikit.driveby.study import run_driveby
    import tempfile

    with tempfile.TemporaryDirectory() as tmp:
        t0 = time.perf_counter()
        ds = run_driveby(ROOT / "examples" / "driveby" / "DRIVEBY.toml", tmp, figures=True)
        example_seconds = time.perf_counter() - t0
        import shutil

        for name in ("driveby-spectrogram.png",):
            shutil.copy(Path(tmp) / name, FIG / "driveby-spectrogram.png")
        smooth = ds["road_class"].values == "none"
        damaged = smooth & (ds["damage_severity"].values > 0)
        example_shapes = [{"speed": float(ds["speed"].values[i]), "mac": round(float(ds["mode_shape_mac"].values[i]), 4),
                           "curvature_x": round(float(ds["curvature_change_x"].values[i]), 2)}
                          for i in np.flatnonzero(damaged)]
        example_max_err = float(100 * np.max(np.abs(ds["frequency_error"].values[smooth])))
    numbers = {
        "measured": datetime.date.today().isoformat(),
        "f1_hz": round(f1, 4),
        "speeds": speeds, "error_by_speed_pct": [round(e, 3) for e in by_speed],
        "max_error_5_10_pct": round(max(abs(e) for e, v in zip(by_speed, speeds) if v <= 10), 3),
        "error_by_road_pct": {c: [round(e, 2) for e in v] for c, v in by_road.items()},
        "error_by_road_residual_pct": {c: [round(e, 2) for e in v] for c, v in by_road_residual.items()},
        "signal_rms": float(f"{signal_level(healthy):.3g}"),
        "noise_rms": noises, "error_by_noise_pct": {k: [round(e, 3) for e in v] for k, v in by_noise.items()},
        "damage": [{k: round(v, 3) for k, v in row.items()} for row in damage],
        "example_seconds": round(example_seconds, 1), "example_cases": int(ds.sizes["case"]),
        "example_max_smooth_error_pct": round(example_max_err, 3),
        "example_shapes": example_shapes,
    }
    figures(numbers)
    (FIG / "driveby-numbers.json").write_text(json.dumps(numbers, indent=1) + "\n")
    return numbers


def figures(n: dict) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, 3, figsize=(11, 3.4))
    axes[0].plot(n["speeds"], n["error_by_speed_pct"], "o-")
    axes[0].set_xlabel("speed [m/s]")
    axes[0].set_ylabel("identification error [%]")
    axes[0].set_title("smooth road")
    for i, (c, errs) in enumerate(n["error_by_road_pct"].items()):
        axes[1].plot([i - 0.1] * len(errs), errs, "o", color="C0", label="one cart" if i == 0 else None)
    for i, (c, errs) in enumerate(n["error_by_road_residual_pct"].items()):
        axes[1].plot([i + 0.1] * len(errs), errs, "s", color="C1", label="residual of two carts" if i == 0 else None)
    axes[1].set_ylim(-10, 2000)
    axes[1].legend(fontsize=7, loc="center left")
    axes[1].set_xticks(range(len(n["error_by_road_pct"])), list(n["error_by_road_pct"]))
    axes[1].set_yscale("symlog", linthresh=1.0)
    axes[1].set_xlabel("ISO 8608 class (3 seeds), 8 m/s")
    axes[1].set_title("road roughness")
    for i, (k, errs) in enumerate(n["error_by_noise_pct"].items()):
        axes[2].plot([float(k)] * len(errs), errs, "o", color="C0")
    axes[2].set_xscale("symlog", linthresh=1e-6)
    axes[2].set_yscale("symlog", linthresh=1.0)
    axes[2].set_xlabel("noise rms [m/s²], 8 m/s, smooth")
    axes[2].set_title("sensor noise")
    for ax in axes:
        ax.axhline(1, color="k", lw=0.6, ls=":")
        ax.axhline(-1, color="k", lw=0.6, ls=":")
    fig.tight_layout()
    fig.savefig(FIG / "driveby-error.png", dpi=110)
    plt.close(fig)
    fig, ax = plt.subplots(figsize=(5.5, 3.5))
    for v, mk in ((5.0, "o"), (10.0, "s")):
        rows = [r for r in n["damage"] if r["speed"] == v]
        ax.errorbar([r["severity"] for r in rows], [r["identified_shift_pct"] for r in rows],
                    yerr=[r["resolution_pct"] for r in rows], fmt=mk, capsize=3, label=f"identified, {v:g} m/s (± 1/T)")
    rows = [r for r in n["damage"] if r["speed"] == 5.0]
    ax.plot([r["severity"] for r in rows], [r["true_shift_pct"] for r in rows], "k-", label="true (modal model)")
    ax.set_xlabel("severity (EI loss over 2.5 m at midspan)")
    ax.set_ylabel("first-frequency shift [%]")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(FIG / "driveby-damage.png", dpi=110)
    plt.close(fig)


if __name__ == "__main__":
    print(json.dumps(main(), indent=1))
