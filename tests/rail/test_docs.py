"""docs/railway.md quotes the numbers docs/scripts/rail_numbers.py stored in
docs/figures/rail-numbers.json, and the code still gives them (the example sweep: slow)."""
import importlib.util
import json
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
STORED = json.loads((ROOT / "docs" / "figures" / "rail-numbers.json").read_text())
PAGE = re.sub(r"\s+", " ", (ROOT / "docs" / "railway.md").read_text())
HINT = "run python docs/scripts/rail_numbers.py and update docs/railway.md"


def _script():
    spec = importlib.util.spec_from_file_location("rail_numbers", ROOT / "docs" / "scripts" / "rail_numbers.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def quoted() -> list[str]:
    s, out = STORED, []
    for name, r in s["hslm"].items():
        out.append(f"| {name} | {r['N']} | {r['D']:g} | {r['d']:g} | {r['P_kN']:g} | {r['axles']} | {r['length_m']:g} |")
    c = s["codes"]
    out += [f"{v:g} % (L = 5 m)" if k == "5" else f"{v:g} % ({k} m)" for k, v in c["delta_zeta_pct"].items()]
    z = c["zeta_pct_10m"]
    out += [f"{z['steel']:g} % (steel, composite)", f"{z['prestressed-concrete']:g} % (prestressed concrete)",
            f"{z['reinforced-concrete']:g} % (reinforced concrete, filler beam)",
            f"Φ2 = {c['phi2_20m']:g}", f"Φ3 = {c['phi3_20m']:g}", f"{c['lm71_moment_20m_kNm']:g} kN m at midspan",
            f"{c['lm71_shear_20m_kN']:g} kN of shear"]
    v = s["verification"]
    out += [f"agree to {v['simulate_rel_err']:.1e} of the peak", f"at {v['resonance_ratio']:g} × n0 D"]
    a = s["accuracy"]
    out += [f"largest acceleration is {a['grid_peak']:g} m/s²", f"gives {a['refined_peak']:g} m/s² at {a['refined_speed_kmh']:g} km/h",
            f"error bound of {a['refinement_bound_pct']:g} %", f"gives {a['dense_peak']:g} m/s², {a['refined_vs_dense_pct']:g} % above",
            f"{a['wagons_static_ratio_pct']:g} % above the midspan one, at {a['wagons_static_position_m']:g} m",
            f"largest {a['wagons_dynamic_ratio_pct']:g} % above its midspan value, at {a['wagons_dynamic_position_m']:g} m",
            f"spacing is {a['ice3_table_wavelength_m']:g} m", f"moment is {a['moment_grid_kNm']:g} kN m",
            f"the refined one {a['moment_refined_kNm']:g} kN m with an error bound of {a['moment_bound_pct']:g} %",
            f"the dense sweep's {a['moment_dense_kNm']:g} kN m",
            f"lies {a['acc_sampling_change_pct']:g} % above its largest time sample, with a remaining error bound of "
            f"{a['acc_sampling_bound_pct']:g} %", f"by at most {a['acc_largest_sampling_change_pct']:g} % of the largest peak, "
            f"with bounds up to {a['acc_largest_sampling_bound_pct']:g} % of it"]
    e = s["example"]
    out += [f"n0 = {e['n0_hz']:g} Hz, {e['n_modes']} modes, ζ = {e['damping_pct']:g} %", f"{e['speeds']} speeds",
            f"Peak deck acceleration {e['peak_acc']:g} m/s² ({e['peak_train']} at {e['peak_speed_kmh']:g} km/h",
            "the span fails" if not e["passes"] else "the span passes", f"φ'dyn of the deflection is {e['phi_dyn_deflection']:g}",
            f"moment is {e['moment_ratio']:g} and the shear {e['shear_ratio']:g}", f"so {e['moment_governs'].replace('Phi x', 'Φ ×')} governs",
            f"{e['acc_sampling_change_pct']:g} % and {e['acc_sampling_bound_pct']:g} % for the governing peak, "
            f"{e['acc_largest_sampling_change_pct']:g} % and {e['acc_largest_sampling_bound_pct']:g} % of the largest over the sweep",
            "no flag" if not e["flags"] else f"flags: {', '.join(e['flags'])}",
            f"moved by at most {e['deflection_moment_largest_sampling_change']:g} of their own value in the example; "
            f"{e['shear_sample_or_limit_pct']:g} % of the shear's peaks"]
    return out


def test_page_quotes_the_stored_numbers():
    missing = [q for q in quoted() if q not in PAGE]
    assert not missing, f"{missing}: {HINT}"


def _close(now, stored, where):
    if isinstance(stored, dict):
        assert set(now) == set(stored), where
        for k in stored:
            _close(now[k], stored[k], f"{where}.{k}")
    elif isinstance(stored, float):
        assert now == pytest.approx(stored, rel=1e-9, abs=1e-12), f"{where}: {HINT}"
    else:
        assert now == stored, f"{where}: {HINT}"


def test_fast_numbers_are_reproduced():
    now = _script().compute(slow=False)
    for key in ("hslm", "codes", "verification", "accuracy"):
        if key == "verification":  # a round-off level: its order of magnitude
            assert now[key]["simulate_rel_err"] < 10 * STORED[key]["simulate_rel_err"] + 1e-12
            _close({k: v for k, v in now[key].items() if k != "simulate_rel_err"},
                   {k: v for k, v in STORED[key].items() if k != "simulate_rel_err"}, key)
        else:
            _close(now[key], STORED[key], key)


@pytest.mark.slow
def test_example_numbers_are_reproduced(tmp_path, monkeypatch):
    script = _script()
    monkeypatch.setattr(script, "FIGURE", tmp_path / "rail-acceleration.png")
    _close(script.example(), STORED["example"], "example")
