"""docs/lifetime.md quotes the numbers of docs/figures/lifetime-numbers.json (written by
docs/scripts/lifetime_numbers.py); the slow test recomputes the example."""
import importlib.util
import json
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
HINT = "run python docs/scripts/lifetime_numbers.py (it rewrites the JSON, the figures and the page's block)"


def _script():
    spec = importlib.util.spec_from_file_location("lifetime_numbers", ROOT / "docs" / "scripts" / "lifetime_numbers.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def test_page_quotes_the_stored_numbers():
    script = _script()
    numbers = json.loads(script.NUMBERS.read_text())
    page = script.PAGE.read_text()
    assert script.render(numbers) in page, HINT
    assert script.render_exact(numbers) in page, HINT
    assert script.render_knot(numbers) in page, HINT


def test_page_quotes_the_design_life_range_of_the_example_detail():
    """The prose on the fatigue limit over the design life quotes the example week's AASHTO E flange as stored:
    its largest simulated range below (ΔF)_TH = 31.03 MPa, its estimated 100-year largest above, and the bound."""
    script = _script()
    d = json.loads(script.NUMBERS.read_text())["example"]["details"]["flange_AASHTO_E"]
    page = script.PAGE.read_text()
    assert d["max_stress_range_static"] < 31.03e6 < d["max_stress_range_design_life"], HINT
    assert (f"reaches an estimated {d['max_stress_range_design_life'] / 1e6:.1f} MPa in 100 years (upper\n"
            f"  bound {d['max_stress_range_design_life_bound'] / 1e6:.1f} MPa with the dynamics)") in page, HINT


def test_knot_example_states_what_the_limits_do():
    """The page's knot example as stored: the run's static reference at its steps below the exact
    static peak of the static pass (by the stored shortfall), and with the limits at the knots equal
    to it (the breakpoint sweep's peak is one of the limits) — the claim the page makes in words; to
    1e-6, since the limits are read δ = 1e-6 of a step either side of the knot (``vbikit._vertex.KNOT_OFFSET``:
    a line's slope times δ's travel, measured 2.7e-9 of the peak)."""
    k = json.loads(_script().NUMBERS.read_text())["knot_example"]
    assert abs(k["steps_static"]) < abs(k["exact_static"])
    assert k["shortfall"] == pytest.approx(1.0 - abs(k["steps_static"]) / abs(k["exact_static"]), rel=1e-12)
    assert k["limits_static"] == pytest.approx(k["exact_static"], rel=1e-6), HINT
    for name in ("gumbel", "adr", "fatigue", "traffic"):
        assert (ROOT / "docs" / "figures" / f"lifetime-{name}.png").is_file()


@pytest.mark.slow
def test_example_numbers_are_reproduced():
    """The example week again: every count, characteristic value, ADR and damage as stored (run
    times aside); the convolution's exactness below 1e-9."""
    script = _script()
    stored = json.loads(script.NUMBERS.read_text())
    now = script.example()
    for key in ("n_days", "n_trucks", "n_events", "n_dynamic", "n_sample"):
        assert now[key] == stored["example"][key], f"{key}: {HINT}"
    for group in ("effects", "details"):
        for name, values in stored["example"][group].items():
            for key, value in values.items():
                if isinstance(value, float):
                    assert now[group][name][key] == pytest.approx(value, rel=1e-9, nan_ok=True), f"{name}.{key}: {HINT}"
    assert all(v < 1e-9 for v in script.exactness().values())
    exact = script.exact_peaks()
    for key in ("events", "over_1pct", "over_01pct", "events_over_1pct", "events_over_01pct", "reaction_day"):
        assert exact[key] == stored["exact_peaks"][key], f"{key}: {HINT}"
    for key in ("reaction_day_max_sampled", "reaction_day_max_exact"):
        assert exact[key] == pytest.approx(stored["exact_peaks"][key], rel=1e-9), f"{key}: {HINT}"
    knot = script.knot_example()
    for key in ("day", "event", "trucks", "candidates"):
        assert knot[key] == stored["knot_example"][key], f"{key}: {HINT}"
    for key in ("dt_s", "exact_static", "steps_static", "shortfall", "limits_static", "limits_total"):
        assert knot[key] == pytest.approx(stored["knot_example"][key], rel=1e-9), f"{key}: {HINT}"
