"""Recompute the numbers docs/railway.md quotes and store them in docs/figures/rail-numbers.json,
and draw docs/figures/rail-acceleration.png (the example sweep's acceleration envelopes).

    python docs/scripts/rail_numbers.py          # about a minute (the example sweep)

tests/rail/test_docs.py checks that every number the page quotes is the JSON's, and recomputes the
fast parts (``hslm``, ``codes``, ``verification``); the example sweep is recomputed by a slow test.
"""
from __future__ import annotations

import json
import math
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
NUMBERS = ROOT / "docs" / "figures" / "rail-numbers.json"
FIGURE = ROOT / "docs" / "figures" / "rail-acceleration.png"
EXAMPLE = ROOT / "examples" / "railway" / "hslm_20m.toml"


def hslm() -> dict:
    from vbikit.vehicle.trains import HSLM_A_TABLE, hslm_a

    out = {}
    for k, (n, D, d, P) in HSLM_A_TABLE.items():
        t = hslm_a(k)
        out[t.name] = {"N": n, "D": D, "d": d, "P_kN": P, "axles": t.n_axles, "length_m": round(t.length, 4)}
    return out


def codes() -> dict:
    from vbikit.bridge.beam import EulerBernoulliBeam
    from vbikit.rail import codes as c

    beam = EulerBernoulliBeam(20.0, 1e10, 1e4)
    return {
        "delta_zeta_pct": {f"{L:g}": round(100 * c.additional_damping(L), 4) for L in (5.0, 10.0, 15.0, 20.0, 25.0)},
        "zeta_pct_20m": {name: round(100 * d.ratio(20.0), 4) for name, d in c.DECK_DAMPING.items()},
        "zeta_pct_10m": {name: round(100 * d.ratio(10.0), 4) for name, d in c.DECK_DAMPING.items()},
        "phi2_20m": round(c.phi2(20.0), 4), "phi3_20m": round(c.phi3(20.0), 4),
        "lm71_moment_20m_kNm": round(c.lm71_peak(beam.load_effect("moment", 10.0).influence, 20.0) / 1e3, 2),
        "lm71_shear_20m_kN": round(c.lm71_peak(beam.load_effect("shear", 0.0).influence, 20.0) / 1e3, 2),
    }


def verification() -> dict:
    """The solver against simulate (HSLM-A4, 280 km/h, 4 modes) and the resonance of 12 axles."""
    import numpy as np

    from vbikit.bridge.beam import EulerBernoulliBeam
    from vbikit.solve import Crossing, simulate
    from vbikit.solve.moving_loads import moving_load_history, moving_load_sweep
    from vbikit.vehicle.trains import hslm_a, train_vehicle

    beam = EulerBernoulliBeam(20.0, 1.2e10, 15000.0, 0.015, n_modes=4)
    train = hslm_a(4)
    v, dx = 280 / 3.6, 0.05
    h = moving_load_history(beam, train.axle_positions, train.axle_loads, v, dx=dx, free_vibration=0.4)
    r = simulate(Crossing(beam, train_vehicle(train), speed=v, approach=0.0, dt=dx / v, free_vibration=0.4))
    n = min(r.time.size, h.time.size - 1)
    err = float(np.max(np.abs(h.xi_ddot[1:n + 1] - r.xi_ddot[:n])) / np.max(np.abs(r.xi_ddot)))
    one = EulerBernoulliBeam(15.0, 8.0e9, 12000.0, 0.01, n_modes=1)
    n0 = float(one.frequencies_hz[0])
    speeds = n0 * 20.0 * np.linspace(0.85, 1.15, 61)
    env = moving_load_sweep(one, 20.0 * np.arange(12), np.full(12, 170e3), speeds, [7.5], dx=0.01, free_vibration=1.0)
    v_star = float(speeds[int(np.argmax(env.max_acceleration[:, 0]))])
    return {"simulate_rel_err": float(f"{err:.1e}"), "resonance_ratio": round(v_star / (n0 * 20.0), 4),
            "n0_hz": round(n0, 4)}


def accuracy() -> dict:
    """The cases of tests/rail/test_trust.py: a 20 km/h grid against its refined peak and a dense sweep
    (HSLM-A3, 20 m span); the moment envelope of six four-axle wagons of 22.5 t per axle on a 25 m span
    (exact static, against midspan); the resonance wavelength of ICE 3 read from a table file."""
    import numpy as np

    from vbikit.rail.run import build_bridge, run_rail
    from vbikit.rail.signature import dominant_wavelength
    from vbikit.rail.spec import parse_rail_spec
    from vbikit.solve.moving_loads import moving_load_sweep
    from vbikit.vehicle.trains import hslm_a, ice3

    data = {"bridge": {"span": 20.0, "EI": 7.9e10, "mass_per_length": 25000.0}, "trains": {"presets": ["hslm-a3"]},
            "speeds": {"min": 200.0, "max": 260.0, "step": 20.0}}
    result = run_rail(data, figures=False)
    ds, acc = result.dataset, result.checks["acceleration"]
    t = hslm_a(3)
    v = np.arange(249.0, 253.0, 0.02) / 3.6
    dense = moving_load_sweep(build_bridge(parse_rail_spec(data))[0], t.axle_positions, t.axle_loads, v, ds.point.values, (),
                              dx=ds.attrs["dx_m"], free_vibration=1.0 / ds.attrs["first_frequency_hz"])
    true = float(dense.max_acceleration.max())
    mom = result.checks["moment"]
    vm = np.arange(249.0, 255.0, 0.02) / 3.6
    bridge = build_bridge(parse_rail_spec(data))[0]
    dense_m = moving_load_sweep(bridge, t.axle_positions, t.axle_loads, vm, ds.point.values[:1],
                                (bridge.load_effect("moment", 10.0),), dx=ds.attrs["dx_m"],
                                free_vibration=1.0 / ds.attrs["first_frequency_hz"]).max_effect[:, 0]
    true_m = float(dense_m.max()) + 0.5 * mom["phi_irregularity"] * float(ds["static_moment"].sel(train="HSLM-A3"))
    wagon = np.array([0.0, 1.8, 9.0, 10.8])
    axles = np.concatenate([wagon + 14.0 * k for k in range(6)])
    import tempfile

    with tempfile.TemporaryDirectory() as tmp:
        table = Path(tmp) / "d2.csv"
        table.write_text("".join(f"{a:.3f},{22.5 * 9.81:.4f}\n" for a in axles))
        wagons = run_rail({"bridge": {"span": 25.0, "EI": 2.5e10, "mass_per_length": 12000.0},
                           "trains": {"tables": [str(table)]}, "speeds": {"min": 40.0, "max": 120.0, "step": 40.0}},
                          figures=False).dataset.attrs
    i3 = ice3()
    return {
        "grid_peak": round(acc["grid_peak"], 3), "refined_peak": round(acc["peak"], 3),
        "refined_speed_kmh": round(3.6 * acc["speed"], 1), "refinement_bound_pct": round(100 * acc["refinement_bound"], 3),
        "dense_peak": round(true, 3), "refined_vs_dense_pct": round(100 * (true - acc["peak"]) / true, 3),
        "moment_grid_kNm": round(mom["grid_design"] / 1e3, 1), "moment_refined_kNm": round(mom["dynamic_design"] / 1e3, 1),
        "moment_bound_pct": round(100 * mom["refinement_bound"], 3), "moment_dense_kNm": round(true_m / 1e3, 1),
        "wagons_static_ratio_pct": round(100 * (wagons["static_moment_max_over_midspan"] - 1), 2),
        "wagons_static_position_m": round(wagons["static_moment_max_position_m"], 4),
        "wagons_dynamic_ratio_pct": round(100 * (wagons["moment_max_over_midspan"] - 1), 2),
        "wagons_dynamic_position_m": round(wagons["moment_max_position_m"], 3),
        "ice3_table_wavelength_m": round(dominant_wavelength(i3.axle_positions, i3.axle_loads), 6),
        "acc_sampling_change_pct": round(100 * acc["time_sampling_change"], 4),
        "acc_sampling_bound_pct": round(100 * acc["time_sampling_bound"], 4),
        "acc_largest_sampling_change_pct": round(100 * acc["largest_time_sampling_change"], 3),
        "acc_largest_sampling_bound_pct": round(100 * acc["largest_time_sampling_bound"], 3),
    }


def example() -> dict:
    from vbikit.rail.run import run_rail

    result = run_rail(EXAMPLE, None, figures=False)
    from vbikit.rail.figures import plot_acceleration_envelopes

    plot_acceleration_envelopes(result.dataset, FIGURE)
    ds, c = result.dataset, result.checks
    a = c["acceleration"]
    return {
        "n0_hz": round(ds.attrs["first_frequency_hz"], 3), "n_modes": int(ds.attrs["n_modes"]),
        "damping_pct": round(100 * ds.attrs["damping_ratio"], 3), "speeds": int(ds.speed.size),
        "peak_acc": round(a["peak"], 3), "peak_train": a["train"], "peak_speed_kmh": round(3.6 * a["speed"], 1),
        "passes": a["passes"],
        "moment_ratio": round(c["moment"]["ratio"], 3), "shear_ratio": round(c["shear"]["ratio"], 3),
        "moment_governs": c["moment"]["governs"], "phi_dyn_deflection": round(c["deflection"]["phi_dyn"], 3),
        "acc_sampling_change_pct": round(100 * a["time_sampling_change"], 4),
        "acc_sampling_bound_pct": round(100 * a["time_sampling_bound"], 4),
        "acc_largest_sampling_change_pct": round(100 * a["largest_time_sampling_change"], 3),
        "acc_largest_sampling_bound_pct": round(100 * a["largest_time_sampling_bound"], 3),
        "flags": sorted({f["code"] for f in c.get("flags", [])}),
        # the quasi-static histories over the sweep (train × speed): how far a vertex between the samples moved
        # their peaks, and the share of the shear's peaks that are a sample or a one-sided limit (no vertex)
        "deflection_moment_largest_sampling_change": float(f"{max(float(ds['deflection_sampling_change'].max()), float(ds['moment_sampling_change'].max())):.2g}"),
        "shear_sample_or_limit_pct": round(100 * float((ds["shear_sampling_change"] == 0).mean()), 1),
    }


def compute(slow: bool = True) -> dict:
    out = {"hslm": hslm(), "codes": codes(), "verification": verification(), "accuracy": accuracy()}
    if slow:
        out["example"] = example()
    return out


def main() -> None:
    numbers = compute()
    NUMBERS.write_text(json.dumps(numbers, indent=1, ensure_ascii=False) + "\n")
    print(json.dumps(numbers, indent=1, ensure_ascii=False))


if __name__ == "__main__":
    sys.path.insert(0, str(ROOT / "src"))
    main()
