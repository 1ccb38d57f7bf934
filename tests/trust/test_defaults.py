"""One set of defaults for Python and the CLI: every example scenario run through ``vbikit run`` and
through the Python API as the README shows it (defaults left to the models) gives identical numbers."""
from __future__ import annotations

import json
from pathlib import Path

import pytest
from typer.testing import CliRunner

from vbikit.analysis import point_response
from vbikit.bridge import EulerBernoulliBeam
from vbikit.bridge.continuous import ContinuousBeam
from vbikit.bridge.presets import paper_beam, paper_deck
from vbikit.cli import app
from vbikit.contact import MultiPointTire, PointTire
from vbikit.road import Defect, RoadPSD, random_profile, with_defects
from vbikit.scenario import Scenario
from vbikit.solve import Crossing, simulate
from vbikit.vehicle.presets import hs20_44, moving_force, sprung_mass

ROOT = Path(__file__).resolve().parents[2]
runner = CliRunner()


def _cli(path: Path) -> dict:
    res = runner.invoke(app, ["run", str(path), "--json"])
    assert res.exit_code == 0, res.output
    return json.loads(res.stdout)


def _bridge2_crossing(defect: bool) -> Crossing:
    road = random_profile(RoadPSD.iso("C"), seed=1)
    if defect:
        road = with_defects(road, [Defect.of_kind("depression", start=0.0)])
    return Crossing(paper_deck(2, n_modes=20), hs20_44(), MultiPointTire(6), road, speed=75 / 3.6)


#: each example scenario and the Python API call that the README's "From Python" section composes
#: for it, leaving every default to the models (lateral offset, response girder, damping, approach)
PYTHON = {
    "examples/paper/bridge2_hs20_girder4.toml": lambda: (_bridge2_crossing(False), None),
    "examples/paper/fig9_tire_models.toml": lambda: (_bridge2_crossing(True), None),
    "examples/verification/fryba_moving_force.toml": lambda: (Crossing(
        EulerBernoulliBeam(25.0, 8.323e9, 2303.0, damping_ratio=0.0, n_modes=50), moving_force(100e3), PointTire(),
        speed=119.446, approach=0.0, free_vibration=0.5), 12.5),
    "examples/verification/yang_yau_sprung_mass.toml": lambda: (Crossing(
        EulerBernoulliBeam(25.0, 8.323e9, 2303.0, damping_ratio=0.0, n_modes=10), sprung_mass(5750.0, 1595e3, 0.0),
        PointTire(), speed=100 / 3.6, approach=0.0, free_vibration=0.5), 12.5),
    "examples/bridges/three_span_continuous_hs20.toml": lambda: (Crossing(
        ContinuousBeam((20.0, 25.0, 20.0), 1.286e10, 7537.0, n_modes=12, neutral_axis_depth=0.78), hs20_44(),
        MultiPointTire(6), random_profile(RoadPSD.iso("C"), seed=1), speed=75 / 3.6), None),
    "examples/bridges/three_span_grillage_hs20.toml": lambda: (Crossing(
        paper_deck(2, n_modes=20, spans=(16.76, 20.0, 16.76)), hs20_44(), MultiPointTire(6),
        random_profile(RoadPSD.iso("C"), seed=1), speed=75 / 3.6), None),
    "src/vbikit/scenario/demo.toml": lambda: (Crossing(
        paper_beam(16.76, "II", n_modes=20), hs20_44(), MultiPointTire(6), random_profile(RoadPSD.iso("C"), seed=1),
        speed=75 / 3.6), None),
}


SCENARIO_EXAMPLES = sorted({str(p.relative_to(ROOT)) for p in (ROOT / "examples").rglob("*.toml")
                            if p.parts[-2] not in ("studies", "field", "base", "lifetime")}  # base: traffic base scenarios
                           | {"src/vbikit/scenario/demo.toml"})


def _from_scenario(example: str) -> tuple[Crossing, float | None]:
    """The Python API on a scenario file (docs/scenario.md): load, build, simulate."""
    from vbikit.scenario import build, load_scenario

    built = build(load_scenario(ROOT / example))
    return built.crossing, built.response_x


def test_the_paper_and_verification_examples_have_their_python_composition():
    assert {e for e in SCENARIO_EXAMPLES if e.startswith(("examples/paper/", "examples/verification/"))} | \
        {"src/vbikit/scenario/demo.toml"} <= set(PYTHON)


@pytest.mark.parametrize("example", SCENARIO_EXAMPLES)
def test_every_example_validates_and_runs(example):
    res = runner.invoke(app, ["validate", str(ROOT / example)])
    assert res.exit_code == 0, res.output


@pytest.mark.parametrize("example", sorted(ROOT.glob("examples/studies/*.toml")), ids=lambda p: p.name)
def test_every_study_example_validates(example):
    res = runner.invoke(app, ["study", "validate", str(example)])
    assert res.exit_code == 0, res.output


@pytest.mark.parametrize("example", SCENARIO_EXAMPLES)
def test_cli_and_python_api_agree(example):
    cli = _cli(ROOT / example)
    crossing, x = PYTHON.get(example, lambda: _from_scenario(example))()
    result = simulate(crossing)
    response = point_response(result, x)
    im = response.displacement_impact
    # identical inputs, identical code path after the models: equal to the last bit
    assert cli["impact_factor"] == im.impact_factor
    assert cli["max_dynamic_displacement"] == im.dynamic_peak
    assert cli["strain_impact_factor"] == response.strain_impact.impact_factor
    assert cli["response_y"] == response.y
    assert cli["n_steps"] == result.n_steps and cli["dt"] == result.dt
    if not crossing.single:
        assert [v["lateral_offset"] for v in cli["inputs"]["vehicles"]] == [m.lateral_offset for m in crossing.vehicles]
    else:
        assert cli["inputs"]["lateral_offset"] == crossing.lateral_offset


def test_paper_deck_defaults_are_the_scenario_defaults():
    """The issue's case: Crossing(paper_deck(2, …)) drove at y = 0 and read y = 0 (IM 0.2280)
    while the scenario used the preset's 1.4 m and Girder 4 (IM 0.2229)."""
    bridge = paper_deck(2, n_modes=20)
    crossing = Crossing(bridge, hs20_44(), MultiPointTire(6), random_profile(RoadPSD.iso("C"), seed=1), speed=75 / 3.6)
    assert crossing.lateral_offset == 1.4
    assert bridge.default_response_y == pytest.approx(2.13)  # Girder 4 of five at 2.13 m


def test_beam_damping_default_is_the_scenario_default():
    data = {"bridge": {"model": "beam", "span": 20.0, "EI": 1e10, "mass_per_length": 5000.0},
            "vehicle": {"model": "sprung-mass"}, "crossing": {"speed": 20.0}}
    assert EulerBernoulliBeam(20.0, 1e10, 5000.0).damping_ratio == Scenario.model_validate(data).bridge.damping_ratio == 0.02
