"""TOML scenario schema, validation and assembly into model objects."""
from vbikit.scenario.build import BuiltScenario, build
from vbikit.scenario.pipeline import run
from vbikit.scenario.report import Report
from vbikit.scenario.schema import (
    Scenario,
    ScenarioError,
    demo_scenario_text,
    load_scenario,
    parse_scenario,
    scenario_from_toml,
)

__all__ = [
    "BuiltScenario",
    "Report",
    "Scenario",
    "ScenarioError",
    "build",
    "demo_scenario_text",
    "load_scenario",
    "parse_scenario",
    "run",
    "scenario_from_toml",
]
