# A study that asks for load effects at the automatic step is told, before it runs, when the
# impact factors settle only at a finer step (the base crossing through the run's step check).
# The case: two 20 m spans on elastic bearings, 40 modes, no damping, quarter car at 70 km/h,
# pier moment — the automatic step alone gives a pier-moment IM 12 % low (docs/theory.md).
from __future__ import annotations

from vbikit.study.check import check_study
from vbikit.study.spec import parse_study

BRIDGE = {"model": "continuous-beam", "spans": [20.0, 20.0], "EI": 4.865e10, "mass_per_length": 18358.0,
          "support_stiffness": [5e8, 2e8, 5e8], "rotational_stiffness": [2e9, 2e9], "damping_ratio": 0.0,
          "n_modes": 40}


def _study(response: dict) -> dict:
    base = {"bridge": BRIDGE, "vehicle": {"model": "quarter-car"}, "tire": {"model": "point"},
            "road": {"class": "none"}, "crossing": {"speed_kmh": 70}, "response": response}
    return {"name": "elastic", "base": base, "axes": {"crossing.speed_kmh": [70, 80]}}


def test_load_effects_at_the_automatic_step_get_advice():
    warnings = check_study(parse_study(_study({"moment": [20.0]}))).warnings
    # the run starts at the step the load effects need (9.0e-5 s, vbikit.analysis.effect_step) and the
    # halving check settles at 2.3e-5 s: the advice names it and the automatic step it replaces
    advice = [w for w in warnings if "settle only at dt" in w or "not converged in the time step" in w]
    assert advice and all("crossing.dt" in w for w in advice)
    assert any("0.00249 s" in w for w in advice)


def test_no_advice_without_load_effects_asked():
    warnings = check_study(parse_study(_study({"x": 10.0}))).warnings
    assert not [w for w in warnings if "settle only at dt" in w or "not converged in the time step" in w]
