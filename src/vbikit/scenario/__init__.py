"""TOML scenario schema, validation and assembly into model objects."""
from typing import TYPE_CHECKING

from vbikit._lazy import lazy_exports

if TYPE_CHECKING:  # imported on first use (vbikit._lazy); listed here for type checkers and the API reference
    from vbikit.scenario.build import BuiltScenario, build
    from vbikit.scenario.pipeline import run, run_random
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
    "run_random",
    "scenario_from_toml",
]

__getattr__, __dir__ = lazy_exports(globals(), {
    "vbikit.scenario.build": ["BuiltScenario", "build"],
    "vbikit.scenario.pipeline": ["run", "run_random"],
    "vbikit.scenario.report": ["Report"],
    "vbikit.scenario.schema": ["Scenario", "ScenarioError", "demo_scenario_text", "load_scenario", "parse_scenario", "scenario_from_toml"],
})
