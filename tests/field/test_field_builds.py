"""The field workflow builds its models and checks its runs as a scenario does: the bridge through
the [bridge] spec (its errors name bridge.<key>), the tires through the [tire] builder, the time
step and budgets through preflight's shared checks."""
from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from vbikit.bridge import ScaledBridge, cypress_bayou
from vbikit.contact.tires import DiskTire, MultiPointTire, PointTire, RigidDiskTire
from vbikit.field import FieldFileError, load_field_toml
from vbikit.field.workflow import FIELD_TIRES, base_bridge, check_field, field_tire
from vbikit.scenario.preflight import MIN_STEPS
from vbikit.solve.budget import BudgetError, Limits



def edit(example: Path, old: str, new: str) -> Path:
    p = example / "FIELD.toml"
    text = p.read_text()
    assert old in text
    p.write_text(text.replace(old, new, 1))
    return p


def test_the_field_bridge_is_the_scenario_build_of_its_preset(example):
    spec = load_field_toml(edit(example, "stiffness_factor = 1.0", "stiffness_factor = 1.0\n[bridge.deck]\nn_elements = 10"))
    bridge = base_bridge(spec)
    np.testing.assert_array_equal(bridge.omega, cypress_bayou(n_modes=10, damping_ratio=0.02, n_elements=10).omega)


@pytest.mark.parametrize("bridge, deck, message", [
    ("paper-bridge-2-beam", "n_girders = 3", r"FIELD\.toml: bridge\.deck: \[bridge\.deck\] applies to .*not 'paper-bridge-2-beam'"),
    ("cypress-bayou", "span_x = 3.0", r"FIELD\.toml: bridge\.deck: unknown \[bridge\.deck\] key\(s\) 'span_x'"),
    ("cypress-bayou", "n_girders = 5.0", r"FIELD\.toml: bridge\.deck\.n_girders: must be an integer"),
])
def test_bridge_errors_name_the_scenario_key(example, bridge, deck, message):
    path = edit(example, 'model = "cypress-bayou"', f'model = "{bridge}"')
    spec = load_field_toml(edit(example, "stiffness_factor = 1.0", f"stiffness_factor = 1.0\n[bridge.deck]\n{deck}"))
    assert spec.path == path
    with pytest.raises(FieldFileError, match=message):
        base_bridge(spec)


def test_the_field_tires_are_the_scenario_tires_with_their_defaults():
    assert tuple(FIELD_TIRES) == ("point", "multipoint", "disk", "rigid-disk")
    assert [field_tire(n) for n in FIELD_TIRES] == [PointTire(), MultiPointTire(), DiskTire(), RigidDiskTire()]


def test_a_step_too_long_is_refused_by_the_shared_rule(example):
    spec = load_field_toml(edit(example, "free_vibration = 8.0", "free_vibration = 8.0\ndt = 2.0"))
    with pytest.raises(FieldFileError, match=rf"case 'case1', point tire: crossing\.dt = 2 s gives fewer than {MIN_STEPS} steps"):
        check_field(spec, ["point"])


def test_the_run_budget_is_the_shared_one(example):
    spec = load_field_toml(example / "FIELD.toml")
    check_field(spec, ["point"])
    with pytest.raises(FieldFileError, match=r"case 'case1', point tire: .*steps"):
        check_field(spec, ["point"], Limits(max_steps=100))
    assert issubclass(BudgetError, ValueError)


def test_scaled_bridge_scales_frequencies_by_the_root_of_the_factor():
    base = cypress_bayou(n_modes=4, n_elements=10)
    scaled = ScaledBridge(base, 1.21, 0.03)
    np.testing.assert_allclose(scaled.omega, 1.1 * base.omega, rtol=1e-15)
    np.testing.assert_array_equal(scaled.damping_ratios, np.full(4, 0.03))
    np.testing.assert_array_equal(ScaledBridge(base, 2.0).damping_ratios, base.damping_ratios)
    x, y = [3.0, 8.38], [0.0, 2.13]
    for shapes in ("mode_shapes", "mode_slopes", "strain_shapes"):
        np.testing.assert_array_equal(getattr(scaled, shapes)(x, y), getattr(base, shapes)(x, y))
    assert scaled.span == base.span and scaled.lateral_edges == base.lateral_edges
    for bad in (0.0, -1.0, float("nan")):
        with pytest.raises(ValueError, match="stiffness_factor must be > 0"):
            ScaledBridge(base, bad)
    with pytest.raises(ValueError, match="damping_ratio must be in"):
        ScaledBridge(base, 1.0, 1.0)


def test_a_run_in_reaches_every_case_and_a_profile_too_short_for_it_is_refused_before_running(example):
    """``crossing.run_in`` (0 by default: the example's synthetic records were simulated at rest) reaches each
    case's crossing; beyond the measured profiles (from x = −45.52 m, the truck's rear axle at about −38 m with the
    33.52 m approach) the check before any simulation refuses it, naming the case, the run-in and the remedy; out of
    range it is refused naming the key."""
    from vbikit.field.workflow import base_bridge, case_crossing

    spec = load_field_toml(example / "FIELD.toml")
    assert spec.run_in == 0.0
    spec = load_field_toml(edit(example, "free_vibration = 8.0", "free_vibration = 8.0\nrun_in = 3.0"))
    crossing = case_crossing(spec, spec.cases[0], field_tire("point"), base_bridge(spec))
    assert crossing.run_in == 3.0
    check_field(spec, ["point"])
    spec = load_field_toml(edit(example, "run_in = 3.0", "run_in = 50.0"))
    with pytest.raises(FieldFileError, match=r"case 'case1', point tire: road profile .* \(approach, run-in, vehicle "
                                             r"length, span, free vibration\): give a longer road"):
        check_field(spec, ["point"])
    with pytest.raises(FieldFileError, match=r"crossing.run_in: expected a number in \[0, 1000\] \[m\], got 2000"):
        load_field_toml(edit(example, "run_in = 50.0", "run_in = 2000.0"))
