"""The references a scenario's models rely on (``vbikit cite``, ``vbikit run --json``)."""
from __future__ import annotations

from collections.abc import Callable

from vbikit.contact.registry import tire_model
from vbikit.references import MODEL_REFERENCES, REFERENCES, Reference
from vbikit.scenario.schema import Scenario
from vbikit.solve.integrators import get_integrator

#: sections whose models declare their own references (by model name); the other sections'
#: ``"<section>:<model>"`` names are looked up in :data:`vbikit.references.MODEL_REFERENCES`
DECLARED_REFERENCES: dict[str, Callable[[str], tuple[str, ...]]] = {
    "tire": lambda name: tire_model(name).references,
    "integrator": lambda name: get_integrator(name).references,
}


def scenario_models(scenario: Scenario) -> list[str]:
    """The ``"<section>:<model>"`` names of the models a scenario uses, in first-use order."""
    road = scenario.road
    names = [f"bridge:{scenario.bridge.model}"]
    if scenario.vehicles:  # several vehicles, each with its tire (default the scenario's)
        for v in scenario.vehicles:
            names += [f"vehicle:{v.model}", f"tire:{(v.tire or scenario.tire).model}"]
    else:
        names += [f"vehicle:{scenario.vehicle.model}", f"tire:{scenario.tire.model}"]
    if road.road_class == "psd":
        names.append("road:psd")
    elif road.road_class != "none" and road.profile_file is None:
        names.append("road:iso")
    names.append(f"integrator:{scenario.crossing.integrator}")
    names.append("impact:code-lines")  # every run reports the design-code allowances beside its IM
    return names


def model_reference_keys(name: str) -> tuple[str, ...]:
    """Reference keys of one ``"<section>:<model>"`` name (the model class's own for the sections
    of ``DECLARED_REFERENCES``); unknown names contribute nothing."""
    section, _, model = name.partition(":")
    declared = DECLARED_REFERENCES.get(section)
    return declared(model) if declared is not None else MODEL_REFERENCES.get(name, ())


def scenario_references(scenario: Scenario) -> list[Reference]:
    """The bibliography entries of the models ``scenario`` uses, in first-use order."""
    keys: list[str] = []
    for name in ("*", *scenario_models(scenario)):
        keys += [k for k in model_reference_keys(name) if k not in keys]
    return [REFERENCES[k] for k in keys]
